#pragma once
/// \file
/// \brief The Sedov-Taylor point explosion: the self-similar solution behind the shock, found by
/// integrating the similarity equations from the shock inwards.
///
/// An energy E released at a point of a cold gas of uniform density \f$ \rho_0 \f$ drives a
/// strong shock whose radius can depend only on E, \f$ \rho_0 \f$ and t (Taylor 1950; Sedov
/// 1959).  In j dimensions (j = 1 planar, 2 cylindrical, 3 spherical)
/// \f[ R(t) = \xi_0 \left(\frac{E t^2}{\rho_0}\right)^{1/(j+2)}, \qquad
///     U = \dot R = \alpha \frac{R}{t}, \qquad \alpha = \frac{2}{j+2}, \f]
/// and behind the shock every field is a fixed shape in \f$ \lambda = r/R(t) \f$:
/// \f[ \rho = \rho_0 G(\lambda), \qquad v = U f(\lambda), \qquad P = \rho_0 U^2 h(\lambda). \f]
///
/// **The similarity equations.**  Putting these forms into the equations of continuity,
/// momentum and entropy, \f$ (\partial_t + v\partial_r)(P\rho^{-\gamma}) = 0 \f$, leaves three
/// ordinary equations in \f$ \lambda \f$; with \f$ w = f - \lambda \f$:
/// \f[ w G' + G\left(f' + (j-1)\frac f\lambda\right) = 0, \qquad
///     w f' + \frac{h'}{G} = \frac{1-\alpha}{\alpha} f, \qquad
///     w\left(\frac{h'}{h} - \gamma\frac{G'}{G}\right) = \frac{2(1-\alpha)}{\alpha}. \f]
/// Eliminating \f$ G' \f$ and \f$ h' \f$ gives \f$ f' \f$ alone,
/// \f[ f' = \frac{\frac{1-\alpha}{\alpha} f w - \frac{2(1-\alpha)}{\alpha}\frac hG
///            + c^2 (j-1)\frac f\lambda}{w^2 - c^2}, \qquad c^2 = \gamma\frac hG, \f]
/// (\f$ c \f$ the sound speed in units of U), and then \f$ G' \f$ and \f$ h' \f$ from the first
/// and third equations.  The strong-shock jump conditions start the integration at
/// \f$ \lambda = 1 \f$:
/// \f$ G = (\gamma+1)/(\gamma-1) \f$, \f$ f = h = 2/(\gamma+1) \f$.  We integrate inwards with
/// the classical Runge-Kutta method on a uniform grid in \f$ \lambda \f$ down to
/// \f$ \lambda_\mathrm{min} \f$, and continue below it with the solution's behaviour at the
/// centre: a uniform pressure, \f$ f \propto \lambda \f$, and the density of a gas compressed
/// adiabatically from the shock, \f$ G \propto \lambda^{j/(\gamma-1)} \f$.  For
/// \f$ \gamma < 7 \f$ (Kamm & Timmes 2007's "standard" case) \f$ w^2 - c^2 \f$ stays negative
/// on the way, so nothing is singular.
///
/// **The constant \f$ \xi_0 \f$** comes from the energy: the kinetic plus thermal energy behind
/// the shock is
/// \f$ E = \sigma_j \rho_0 U^2 R^j \int_0^1 \left(\tfrac12 G f^2 + \tfrac{h}{\gamma-1}\right)
///     \lambda^{j-1} d\lambda \f$
/// (\f$ \sigma_j = 2, 2\pi, 4\pi \f$), and with \f$ U = \alpha R/t \f$ and R(t) above,
/// \f$ \xi_0 = (\alpha^2 \sigma_j I)^{-1/(j+2)} \f$ with I that integral.  It is computed here,
/// not copied: in 3D it comes out at 1.152 for \f$ \gamma = 5/3 \f$ and 1.033 for
/// \f$ \gamma = 1.4 \f$, as tabulated by Sedov.  Mass conservation, \f$ \sigma_j\int_0^1 G
/// \lambda^{j-1}d\lambda = \sigma_j/j \f$ (the shocked sphere holds the mass it swept up), is
/// not imposed anywhere and so checks the integration (tests/sph/test_sedov.cpp).

#include "sph/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace sph {

/// The self-similar Sedov-Taylor solution for one \f$ \gamma \f$ and dimension: \f$ \xi_0 \f$,
/// the shock radius R(t), and density, velocity and pressure at any r and t.
class SedovSolution {
 public:
  /// A point explosion of energy \p energy in a gas of density \p density and adiabatic index
  /// \p gamma, in \p dimension = 1, 2 or 3 dimensions; \p steps Runge-Kutta steps in
  /// \f$ \lambda \f$.
  SedovSolution(int dimension, double gamma, double energy = 1.0, double density = 1.0,
                int steps = 20000)
      : j_(dimension), gamma_(gamma), energy_(energy), density_(density) {
    require(dimension >= 1 && dimension <= 3, "Sedov solution: the dimension must be 1, 2 or 3");
    require(std::isfinite(gamma) && gamma > 1 && gamma < 7,
            "Sedov solution: gamma must lie in (1, 7) (the standard case), got " + show(gamma));
    require(std::isfinite(energy) && energy > 0 && std::isfinite(density) && density > 0,
            "Sedov solution: the energy and the ambient density must be positive");
    require(steps >= 100 && steps % 2 == 0,
            "Sedov solution: the integration needs an even number of steps, at least 100");
    alpha_ = 2.0 / (j_ + 2);
    integrate(steps);
    xi0_ = std::pow(alpha_ * alpha_ * surface() * energy_integral(), -1.0 / (j_ + 2));
  }

  int dimension() const { return j_; }
  double gamma() const { return gamma_; }
  double energy() const { return energy_; }
  double ambient_density() const { return density_; }
  /// \f$ \xi_0 \f$ of \f$ R = \xi_0 (E t^2/\rho_0)^{1/(j+2)} \f$.
  double xi0() const { return xi0_; }
  /// \f$ \sigma_j \f$: the "surface" of the unit sphere (2 in 1D: both sides of the plane).
  double surface() const {
    return j_ == 1 ? 2.0 : (j_ == 2 ? 2.0 * std::numbers::pi : 4.0 * std::numbers::pi);
  }
  /// The shock radius R(t).
  double shock_radius(double t) const {
    return xi0_ * std::pow(energy_ * t * t / density_, 1.0 / (j_ + 2));
  }
  /// The shock speed \f$ U = \alpha R/t \f$.
  double shock_speed(double t) const { return alpha_ * shock_radius(t) / t; }
  /// The time at which the shock reaches radius \p r.
  double time_at_radius(double r) const {
    return std::sqrt(density_ / energy_ * std::pow(r / xi0_, j_ + 2));
  }

  /// Density, radial velocity and pressure at radius r, time t > 0 (ambient and at rest, with
  /// zero pressure, outside the shock).
  struct State {
    double density = 0, velocity = 0, pressure = 0;
  };
  State sample(double r, double t) const {
    require(t > 0, "Sedov solution: the time must be positive");
    const double R = shock_radius(t), U = shock_speed(t);
    const double lambda = std::abs(r) / R;
    if (lambda >= 1.0) return {density_, 0.0, 0.0};
    const Shape s = shape(lambda);
    return {density_ * s.G, U * s.f * (r < 0 ? -1.0 : 1.0), density_ * U * U * s.h};
  }

  /// The dimensionless shape at \f$ \lambda \in [0, 1] \f$.
  struct Shape {
    double G = 0, f = 0, h = 0;
  };
  Shape shape(double lambda) const {
    if (lambda >= 1.0) return table_.front();
    if (lambda <= lambda_min_) {
      // The centre: uniform pressure, homologous velocity, adiabatic density.
      const Shape& c = table_.back();
      const double x = lambda / lambda_min_;
      return {c.G * std::pow(x, j_ / (gamma_ - 1)), c.f * x, c.h};
    }
    // The table runs from lambda = 1 (entry 0) down to lambda_min, uniformly.
    const double position = (1.0 - lambda) / step_;
    const auto k = std::min(static_cast<std::size_t>(position), table_.size() - 2);
    const double w = position - static_cast<double>(k);
    const Shape& a = table_[k];
    const Shape& b = table_[k + 1];
    return {a.G + w * (b.G - a.G), a.f + w * (b.f - a.f), a.h + w * (b.h - a.h)};
  }

  /// \f$ \int_0^1 (\tfrac12 G f^2 + h/(\gamma-1)) \lambda^{j-1} d\lambda \f$.
  double energy_integral() const {
    return integral([&](const Shape& s) { return 0.5 * s.G * s.f * s.f + s.h / (gamma_ - 1); });
  }
  /// \f$ \int_0^1 G \lambda^{j-1} d\lambda \f$, which must be 1/j.
  double mass_integral() const {
    return integral([](const Shape& s) { return s.G; });
  }

 private:
  // The right-hand side of the similarity equations: (G', f', h') at lambda.
  Shape derivative(double lambda, const Shape& s) const {
    const double j = j_, a = alpha_, g = gamma_;
    const double w = s.f - lambda;
    const double c2 = g * s.h / s.G;
    const double fp =
        ((1 - a) / a * s.f * w - 2 * (1 - a) / a * s.h / s.G + c2 * (j - 1) * s.f / lambda) /
        (w * w - c2);
    const double Gp = -s.G * (fp + (j - 1) * s.f / lambda) / w;
    const double hp = s.h * (2 * (1 - a) / (a * w) + g * Gp / s.G);
    return {Gp, fp, hp};
  }

  void integrate(int steps) {
    lambda_min_ = 1e-3;
    step_ = (1.0 - lambda_min_) / steps;
    table_.resize(static_cast<std::size_t>(steps) + 1);
    Shape s{(gamma_ + 1) / (gamma_ - 1), 2 / (gamma_ + 1), 2 / (gamma_ + 1)};
    table_[0] = s;
    const auto add = [](const Shape& x, const Shape& d, double c) {
      return Shape{x.G + c * d.G, x.f + c * d.f, x.h + c * d.h};
    };
    const double dl = -step_;  // inwards
    for (int k = 0; k < steps; ++k) {
      const double l = 1.0 - k * step_;
      const Shape k1 = derivative(l, s);
      const Shape k2 = derivative(l + 0.5 * dl, add(s, k1, 0.5 * dl));
      const Shape k3 = derivative(l + 0.5 * dl, add(s, k2, 0.5 * dl));
      const Shape k4 = derivative(l + dl, add(s, k3, dl));
      s = {s.G + dl / 6 * (k1.G + 2 * k2.G + 2 * k3.G + k4.G),
           s.f + dl / 6 * (k1.f + 2 * k2.f + 2 * k3.f + k4.f),
           s.h + dl / 6 * (k1.h + 2 * k2.h + 2 * k3.h + k4.h)};
      require(s.G > 0 && s.h > 0 && std::isfinite(s.f),
              "Sedov solution: the similarity integration left the physical range at lambda = " +
                  show(l + dl));
      table_[static_cast<std::size_t>(k) + 1] = s;
    }
  }

  // Simpson's rule over the table (an even number of intervals), plus a fine midpoint sum over
  // the centre's power laws below lambda_min.
  template <class F>
  double integral(F&& integrand) const {
    const std::size_t n = table_.size() - 1;
    const auto value = [&](std::size_t k) {
      const double l = 1.0 - static_cast<double>(k) * step_;
      return integrand(table_[k]) * std::pow(l, j_ - 1);
    };
    double sum = value(0) + value(n);
    for (std::size_t k = 1; k < n; ++k) sum += (k % 2 == 1 ? 4.0 : 2.0) * value(k);
    double total = sum * step_ / 3.0;
    // Below lambda_min: the integrand is a sum of powers of lambda; a fine midpoint sum is
    // ample for a slice that holds ~1e-3^j of the volume.
    const int m = 200;
    for (int k = 0; k < m; ++k) {
      const double l = lambda_min_ * (k + 0.5) / m;
      total += integrand(shape(l)) * std::pow(l, j_ - 1) * lambda_min_ / m;
    }
    return total;
  }

  int j_;
  double gamma_, energy_, density_;
  double alpha_ = 0, xi0_ = 0;
  double lambda_min_ = 0, step_ = 0;
  std::vector<Shape> table_;  // lambda = 1 - k step_, k = 0 .. steps
};

}  // namespace sph
