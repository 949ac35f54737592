#pragma once
/// \file
/// \brief The exact Riemann solver for an ideal gas: the reference solution of every shock tube.
///
/// Two uniform gases meet at \f$ x_0 \f$ at \f$ t = 0 \f$.  The solution is self-similar in
/// \f$ S = (x - x_0)/t \f$: a left wave, a contact and a right wave, each outer wave a shock or a
/// rarefaction fan, enclosing the "star" region of constant pressure \f$ p_* \f$ and velocity
/// \f$ u_* \f$.  We follow E.F. Toro, *Riemann Solvers and Numerical Methods for Fluid Dynamics*,
/// 3rd ed. (Springer 2009), chapter 4, and cite its equation numbers:
///
///  1. the pressure function (eqs 4.5-4.8)
///     \f[ f(p) = f_L(p) + f_R(p) + (u_R - u_L) = 0, \qquad
///         f_K(p) = \begin{cases}
///           (p - p_K)\sqrt{\dfrac{A_K}{p + B_K}} & p > p_K \text{ (shock)}\\[1ex]
///           \dfrac{2 c_K}{\gamma - 1}
///             \left[\left(\dfrac{p}{p_K}\right)^{\frac{\gamma-1}{2\gamma}} - 1\right]
///             & p \le p_K \text{ (rarefaction)}
///         \end{cases} \f]
///     with \f$ A_K = 2/((\gamma+1)\rho_K) \f$, \f$ B_K = p_K(\gamma-1)/(\gamma+1) \f$;
///  2. its root \f$ p_* \f$ by Newton's method (eqs 4.37, 4.44) from Toro's adaptive starting
///     guess (PVRS, two-rarefaction or two-shock, eqs 4.46-4.48), kept inside a bracket and
///     falling back to bisection whenever a Newton step would leave it, so it always converges;
///  3. \f$ u_* = \tfrac12(u_L + u_R) + \tfrac12[f_R(p_*) - f_L(p_*)] \f$ (eq 4.9);
///  4. sampling of the wave pattern at \f$ S \f$ (section 4.5, eqs 4.50-4.63).
///
/// A solution exists only if the two rarefactions cannot pull the gas apart, the pressure
/// positivity condition (eq 4.40)
/// \f[ \frac{2}{\gamma - 1}(c_L + c_R) > u_R - u_L . \f]
/// When it fails a vacuum forms between the waves; we report it as an error rather than
/// silently returning a solution with a vacuum region (Toro section 4.6 treats that case).
/// Sound speeds are written c here (Toro writes a).

#include "sph/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace sph {

/// A uniform ideal-gas state in one dimension.
struct GasState {
  double density = 0;   ///< rho
  double velocity = 0;  ///< u, along the tube axis
  double pressure = 0;  ///< P
};

/// Sound speed \f$ c = \sqrt{\gamma P/\rho} \f$ of an ideal gas.
inline double sound_speed(const GasState& w, double gamma) {
  return std::sqrt(gamma * w.pressure / w.density);
}

/// Internal energy per unit mass \f$ u = P/((\gamma - 1)\rho) \f$ of an ideal gas.
inline double internal_energy(const GasState& w, double gamma) {
  return w.pressure / ((gamma - 1.0) * w.density);
}

/// Controls of the iteration for p*.
struct RiemannOptions {
  double tolerance = 1e-12;  ///< relative change of p between iterations (Toro eq 4.44)
  int max_iterations = 100;  ///< Newton or bisection steps before giving up
};

/// The kind of an outer wave.
enum class WaveKind { shock, rarefaction };

/// One outer wave: its kind and its speeds.  For a shock the head and the tail coincide; for a
/// rarefaction the head runs into the undisturbed gas and the tail borders the star region.
struct Wave {
  WaveKind kind = WaveKind::shock;
  double head_speed = 0;
  double tail_speed = 0;
  const char* name() const { return kind == WaveKind::shock ? "shock" : "rarefaction"; }
};

namespace riemann_detail {

/// The constants of one side K = L or R (Toro eq 4.8) and its pressure function.
struct Side {
  GasState state;
  double gamma = 1.4;
  double sound_speed = 0;
  double A = 0;  ///< A_K = 2/((gamma+1) rho_K)
  double B = 0;  ///< B_K = p_K (gamma-1)/(gamma+1)

  Side() = default;
  Side(GasState w, double g)
      : state(w),
        gamma(g),
        sound_speed(sph::sound_speed(w, g)),
        A(2.0 / ((g + 1.0) * w.density)),
        B(w.pressure * (g - 1.0) / (g + 1.0)) {}

  /// f_K(p) and its derivative f_K'(p) (Toro eqs 4.6-4.7 and 4.37).  The shock branch also
  /// takes p = p_K, where both branches agree to first order; it keeps a cold side (p_K = 0)
  /// free of 0/0.
  std::pair<double, double> pressure_function(double p) const {
    const double pK = state.pressure;
    if (p >= pK) {
      // Shock: Rankine-Hugoniot across a wave into the gas at rest relative to it.
      const double root = std::sqrt(A / (p + B));
      return {(p - pK) * root, root * (1.0 - 0.5 * (p - pK) / (p + B))};
    }
    // Rarefaction: isentropic, the Riemann invariant across the fan.
    const double ratio = p / pK;
    const double z = (gamma - 1.0) / (2.0 * gamma);
    const double f = 2.0 * sound_speed / (gamma - 1.0) * (std::pow(ratio, z) - 1.0);
    const double df =
        std::pow(ratio, -(gamma + 1.0) / (2.0 * gamma)) / (state.density * sound_speed);
    return {f, df};
  }

  /// The mass flux Q_K through a shock into this side's gas (Toro eqs 4.20-4.21).
  double shock_mass_flux(double p_star) const { return std::sqrt((p_star + B) / A); }

  /// Density behind the wave: Rankine-Hugoniot for a shock (eqs 4.50, 4.57), the isentrope
  /// for a rarefaction (eqs 4.53, 4.60).
  double star_density(double p_star) const {
    const double rho = state.density, pK = state.pressure;
    if (p_star > pK) {
      const double g6 = (gamma - 1.0) / (gamma + 1.0);
      return rho * (p_star + g6 * pK) / (g6 * p_star + pK);
    }
    return rho * std::pow(p_star / pK, 1.0 / gamma);
  }

  /// Sound speed behind a rarefaction (eqs 4.55, 4.62).
  double star_sound_speed(double p_star) const {
    return sound_speed * std::pow(p_star / state.pressure, (gamma - 1.0) / (2.0 * gamma));
  }
};

/// "left state: density is -1 (must be positive)" and similar, for one state.
inline void validate_state(const GasState& w, const char* side) {
  const std::string who = std::string("Riemann solver: ") + side + " state ";
  require(std::isfinite(w.density) && std::isfinite(w.velocity) && std::isfinite(w.pressure),
          who + "is not finite (density " + show(w.density) + ", velocity " + show(w.velocity) +
              ", pressure " + show(w.pressure) + ")");
  require(w.density != 0.0,
          who +
              "has density 0: a vacuum state given as input; this solver does not "
              "treat vacuum (Toro 2009 section 4.6)");
  require(w.density > 0.0, who + "has negative density " + show(w.density));
  require(w.pressure >= 0.0, who + "has negative pressure " + show(w.pressure));
}

/// A number for messages, with enough digits to tell close values apart.
inline std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

}  // namespace riemann_detail

/// The exact solution of one Riemann problem, ready to be sampled at any (x, t).
///
/// \code
/// sph::RiemannSolution sod({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
/// sod.star_pressure();             // 0.30313
/// sod.sample(0.3, 0.2).density;    // between contact and shock: 0.26557
/// sod.describe();                  // "left rarefaction, contact, right shock ..."
/// \endcode
class RiemannSolution {
 public:
  /// A placeholder to assign a real problem to later: uniform gas at rest, rho = P = 1,
  /// gamma = 1.4, so p* = 1, u* = 0 and both waves have zero strength.
  RiemannSolution() : RiemannSolution({1.0, 0.0, 1.0}, {1.0, 0.0, 1.0}, 1.4) {}

  /// Solves the problem; throws sph::Error for bad input, for a vacuum that the data would
  /// generate, and if the iteration does not converge.
  RiemannSolution(GasState left, GasState right, double gamma, double interface_x = 0.0,
                  RiemannOptions options = {})
      : gamma_(gamma), x0_(interface_x) {
    validate(left, right, gamma, interface_x);
    left_ = riemann_detail::Side(left, gamma);
    right_ = riemann_detail::Side(right, gamma);
    require_no_vacuum();
    p_star_ = solve_star_pressure(options);
    u_star_ = star_velocity_from(p_star_);
    rho_star_left_ = left_.star_density(p_star_);
    rho_star_right_ = right_.star_density(p_star_);
    set_waves();
  }

  // --- the star region -------------------------------------------------------------------
  double star_pressure() const { return p_star_; }
  double star_velocity() const { return u_star_; }
  double star_density_left() const { return rho_star_left_; }
  double star_density_right() const { return rho_star_right_; }
  int iterations() const { return iterations_; }  ///< steps the iteration for p* took

  // --- the problem as given --------------------------------------------------------------
  const GasState& left_state() const { return left_.state; }
  const GasState& right_state() const { return right_.state; }
  double gamma() const { return gamma_; }
  double interface_position() const { return x0_; }

  // --- the waves ---------------------------------------------------------------------------
  const Wave& left_wave() const { return left_wave_; }
  const Wave& right_wave() const { return right_wave_; }
  double contact_speed() const { return u_star_; }

  /// Where a feature moving at `speed` is at time t.
  double position(double speed, double t) const { return x0_ + speed * t; }
  double contact_position(double t) const { return position(u_star_, t); }

  /// Position of the shock when the problem has exactly one (Sod, Monaghan & Gingold).
  double shock_position(double t) const { return position(only(WaveKind::shock).head_speed, t); }
  /// Head (undisturbed side) and tail (star side) of the rarefaction when there is exactly one.
  double rarefaction_head_position(double t) const {
    return position(only(WaveKind::rarefaction).head_speed, t);
  }
  double rarefaction_tail_position(double t) const {
    return position(only(WaveKind::rarefaction).tail_speed, t);
  }

  /// The state at (x, t).  At t = 0 it is the initial data: left for x < x0, right otherwise.
  GasState sample(double x, double t) const {
    require(std::isfinite(x) && std::isfinite(t) && t >= 0.0,
            "Riemann solution: cannot sample at x = " + show(x) + ", t = " + show(t) +
                " (need finite x and t >= 0)");
    if (t == 0.0) return x < x0_ ? left_.state : right_.state;
    const double S = (x - x0_) / t;
    return S <= u_star_ ? sample_left(S) : sample_right(S);
  }

  /// Internal energy per unit mass \f$ u = P/((\gamma-1)\rho) \f$ at (x, t).
  double internal_energy(double x, double t) const {
    return sph::internal_energy(sample(x, t), gamma_);
  }

  /// The wave pattern with speeds and the star state, e.g.
  /// "left rarefaction (head speed -1.18322, tail speed -0.0702728), contact (speed 0.927453),
  /// right shock (speed 1.75216); p* = 0.30313, u* = 0.927453, rho*L = 0.426319, rho*R = 0.265574".
  std::string describe() const { return describe_waves(nullptr); }
  /// The same with the positions of the waves at time t.
  std::string describe(double t) const { return describe_waves(&t); }

 private:
  /// Check gamma, the two states and the interface position.
  static void validate(const GasState& left, const GasState& right, double gamma, double x0) {
    require(std::isfinite(gamma) && gamma > 1.0,
            "Riemann solver: gamma = " + show(gamma) + " (must be finite and > 1)");
    require(std::isfinite(x0), "Riemann solver: interface position is not finite");
    riemann_detail::validate_state(left, "left");
    riemann_detail::validate_state(right, "right");
  }

  /// The pressure positivity condition (Toro eq 4.40): otherwise a vacuum is generated.
  void require_no_vacuum() const {
    const double critical = 2.0 / (gamma_ - 1.0) * (left_.sound_speed + right_.sound_speed);
    const double du = right_.state.velocity - left_.state.velocity;
    require(critical > du,
            "Riemann solver: vacuum generated: the pressure positivity condition "
            "2/(gamma-1) (c_L + c_R) > u_R - u_L (Toro 2009 eq 4.40) fails: 2/(gamma-1) (c_L + "
            "c_R) = " +
                riemann_detail::number(critical) + " <= u_R - u_L = " + riemann_detail::number(du));
  }

  /// f(p) and f'(p) of both sides together (eq 4.5).
  std::pair<double, double> total_pressure_function(double p) const {
    const auto [fL, dfL] = left_.pressure_function(p);
    const auto [fR, dfR] = right_.pressure_function(p);
    return {fL + fR + (right_.state.velocity - left_.state.velocity), dfL + dfR};
  }

  /// Toro's adaptive starting guess (section 4.3.2 and 9.5.1, eqs 4.46-4.48): PVRS where the
  /// pressures are close, two-rarefaction where p* will be below both, two-shock otherwise.
  double starting_guess() const {
    const GasState &L = left_.state, &R = right_.state;
    const double cL = left_.sound_speed, cR = right_.sound_speed, g = gamma_;
    const double du = R.velocity - L.velocity;
    // Primitive-variable guess (eq 4.47).
    const double p_pv = std::max(
        0.0, 0.5 * (L.pressure + R.pressure) - 0.125 * du * (L.density + R.density) * (cL + cR));
    const double p_min = std::min(L.pressure, R.pressure), p_max = std::max(L.pressure, R.pressure);
    double guess;
    if (p_min > 0 && p_max / p_min <= 2.0 && p_pv >= p_min && p_pv <= p_max) {
      guess = p_pv;
    } else if (p_pv < p_min) {
      // Two rarefactions (eq 4.46): exact for two rarefaction waves.
      const double z = (g - 1.0) / (2.0 * g);
      guess = std::pow((cL + cR - 0.5 * (g - 1.0) * du) /
                           (cL / std::pow(L.pressure, z) + cR / std::pow(R.pressure, z)),
                       1.0 / z);
    } else {
      // Two shocks (eq 4.48), linearised about the PVRS value.
      const double gL = std::sqrt(left_.A / (p_pv + left_.B));
      const double gR = std::sqrt(right_.A / (p_pv + right_.B));
      guess = (gL * L.pressure + gR * R.pressure - du) / (gL + gR);
    }
    return (std::isfinite(guess) && guess > 0.0) ? guess : std::max(p_pv, 0.5 * p_max);
  }

  /// An upper end of the bracket: f(0) < 0 by the positivity condition, f increases, so
  /// doubling p until f(p) > 0 brackets the root in (0, p_high].
  double upper_bracket(double guess) const {
    double p = std::max({guess, left_.state.pressure, right_.state.pressure, 1e-300});
    for (int k = 0; k < 4000; ++k, p *= 2.0) {
      if (total_pressure_function(p).first > 0.0) return p;
    }
    throw Error("Riemann solver: could not bracket p* (f(p) stays negative up to p = " +
                riemann_detail::number(p) + ")");
  }

  /// p*: Newton's method (eq 4.37) safeguarded by a bracket, stopped on the relative change of
  /// eq 4.44.
  double solve_star_pressure(const RiemannOptions& options) {
    double p = starting_guess();
    double low = 0.0, high = upper_bracket(p);
    if (!(p > low && p < high)) p = 0.5 * (low + high);
    for (iterations_ = 1; iterations_ <= options.max_iterations; ++iterations_) {
      // Shrink the bracket with the sign of f.
      const auto [f, df] = total_pressure_function(p);
      if (f == 0.0) return p;
      (f < 0.0 ? low : high) = p;
      // Newton step, or bisection if it would leave the bracket.
      double next = p - f / df;
      if (!(next > low && next < high)) next = 0.5 * (low + high);
      // Converged when the relative change is below tolerance.
      const double change = 2.0 * std::abs(next - p) / (next + p);
      p = next;
      if (change <= options.tolerance) return p;
    }
    throw Error("Riemann solver: the iteration for p* did not converge in " +
                show(options.max_iterations) + " steps (last p = " + riemann_detail::number(p) +
                ", bracket [" + riemann_detail::number(low) + ", " + riemann_detail::number(high) +
                "], tolerance " + riemann_detail::number(options.tolerance) + ")");
  }

  /// u* from p* (eq 4.9).
  double star_velocity_from(double p) const {
    return 0.5 * (left_.state.velocity + right_.state.velocity) +
           0.5 * (right_.pressure_function(p).first - left_.pressure_function(p).first);
  }

  /// Kinds and speeds of the two outer waves (eqs 4.51-4.52, 4.54-4.55, 4.58-4.59, 4.61-4.62).
  void set_waves() {
    const GasState &L = left_.state, &R = right_.state;
    if (p_star_ > L.pressure) {
      const double S = L.velocity - left_.shock_mass_flux(p_star_) / L.density;
      left_wave_ = {WaveKind::shock, S, S};
    } else {
      left_wave_ = {WaveKind::rarefaction, L.velocity - left_.sound_speed,
                    u_star_ - left_.star_sound_speed(p_star_)};
    }
    if (p_star_ > R.pressure) {
      const double S = R.velocity + right_.shock_mass_flux(p_star_) / R.density;
      right_wave_ = {WaveKind::shock, S, S};
    } else {
      right_wave_ = {WaveKind::rarefaction, R.velocity + right_.sound_speed,
                     u_star_ + right_.star_sound_speed(p_star_)};
    }
  }

  /// The state at S = x/t left of the contact (Toro section 4.5, Fig 4.14).
  GasState sample_left(double S) const {
    // Undisturbed gas ahead of the wave.
    if (S <= left_wave_.head_speed) return left_.state;
    // Star region behind it.
    if (S >= left_wave_.tail_speed) return {rho_star_left_, u_star_, p_star_};
    // Inside the fan (eq 4.56).
    const GasState& L = left_.state;
    const double g = gamma_, c = left_.sound_speed;
    const double base = 2.0 / (g + 1.0) + (g - 1.0) / ((g + 1.0) * c) * (L.velocity - S);
    return {L.density * std::pow(base, 2.0 / (g - 1.0)),
            2.0 / (g + 1.0) * (c + 0.5 * (g - 1.0) * L.velocity + S),
            L.pressure * std::pow(base, 2.0 * g / (g - 1.0))};
  }

  /// The state at S = x/t right of the contact (mirror of sample_left).
  GasState sample_right(double S) const {
    // Undisturbed gas ahead of the wave.
    if (S >= right_wave_.head_speed) return right_.state;
    // Star region behind it.
    if (S <= right_wave_.tail_speed) return {rho_star_right_, u_star_, p_star_};
    // Inside the fan (eq 4.63).
    const GasState& R = right_.state;
    const double g = gamma_, c = right_.sound_speed;
    const double base = 2.0 / (g + 1.0) - (g - 1.0) / ((g + 1.0) * c) * (R.velocity - S);
    return {R.density * std::pow(base, 2.0 / (g - 1.0)),
            2.0 / (g + 1.0) * (-c + 0.5 * (g - 1.0) * R.velocity + S),
            R.pressure * std::pow(base, 2.0 * g / (g - 1.0))};
  }

  /// The one wave of a kind, or an error naming the pattern when there are zero or two.
  const Wave& only(WaveKind kind) const {
    const bool in_left = left_wave_.kind == kind, in_right = right_wave_.kind == kind;
    require(in_left != in_right, std::string("Riemann solution: the problem has ") +
                                     (in_left ? "two " : "no ") +
                                     (kind == WaveKind::shock ? "shocks" : "rarefactions") + " (" +
                                     describe() + "); use left_wave() / right_wave()");
    return in_left ? left_wave_ : right_wave_;
  }

  /// One wave's text: "left shock (speed 1.2)" or "at x = 0.35" when t is given.
  std::string describe_wave(const char* side, const Wave& w, const double* t) const {
    using riemann_detail::number;
    const auto where = [&](double speed) {
      return t ? "x = " + number(position(speed, *t)) : "speed " + number(speed);
    };
    std::string text = std::string(side) + " " + w.name() + " (";
    if (w.kind == WaveKind::shock) return text + where(w.head_speed) + ")";
    return text + "head " + where(w.head_speed) + ", tail " + where(w.tail_speed) + ")";
  }

  std::string describe_waves(const double* t) const {
    using riemann_detail::number;
    std::string text = describe_wave("left", left_wave_, t) + ", contact (" +
                       (t ? "x = " + number(contact_position(*t)) : "speed " + number(u_star_)) +
                       "), " + describe_wave("right", right_wave_, t);
    if (t) text += " at t = " + number(*t);
    return text + "; p* = " + number(p_star_) + ", u* = " + number(u_star_) +
           ", rho*L = " + number(rho_star_left_) + ", rho*R = " + number(rho_star_right_);
  }

  double gamma_;
  double x0_;
  riemann_detail::Side left_, right_;
  double p_star_ = 0, u_star_ = 0, rho_star_left_ = 0, rho_star_right_ = 0;
  int iterations_ = 0;
  Wave left_wave_, right_wave_;
};

}  // namespace sph
