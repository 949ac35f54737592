#pragma once
/// \file
/// \brief Plane Poiseuille flow: the steady profile between two plates and the start-up flow
/// from rest that leads to it -- the reference of Watkins et al.'s (1996) first dynamic test.
///
/// A fluid of constant density \f$ \rho \f$ and kinematic shear viscosity
/// \f$ \nu = \mu_s/\rho \f$ lies between plates at \f$ y = \pm a \f$, is driven along x by a
/// uniform acceleration g, and sticks to the plates.  Nothing depends on x, the flow stays along
/// x, and the Navier-Stokes equation is the one-dimensional diffusion equation with a source,
/// \f[ \frac{\partial v_x}{\partial t} = g + \nu\,\frac{\partial^2 v_x}{\partial y^2}, \qquad
///     v_x(\pm a, t) = 0. \f]
/// Its steady state is Watkins et al.'s eq 15,
/// \f$ v_\infty(y) = g(a^2 - y^2)/(2\nu) \f$ (their \f$ \mu_s \f$ with \f$ \rho = 1 \f$):
/// 1.92 on the axis for their a = 0.4, g = 3.6, \f$ \mu_s = 0.15 \f$.
///
/// **From rest.**  The difference \f$ v_x - v_\infty \f$ obeys the source-free equation with the
/// same walls, so it is a sum of the walls' cosine modes, each decaying at its own rate; the
/// coefficients make \f$ v_x = 0 \f$ at t = 0 (the cosine series of the parabola):
/// \f[ v_x(y, t) = \frac{g}{2\nu}(a^2 - y^2)
///     - \frac{16\,g\,a^2}{\nu\pi^3} \sum_{n=0}^\infty \frac{(-1)^n}{(2n+1)^3}
///       \cos\!\left(\frac{(2n+1)\pi y}{2a}\right)
///       \exp\!\left(-\frac{(2n+1)^2\pi^2\nu t}{4a^2}\right). \f]
/// The slowest mode, n = 0, sets the time the flow takes to settle:
/// \f$ t_\nu = 4a^2/(\pi^2\nu) \f$ (0.432 for Watkins' flow); after \f$ 5 t_\nu \f$ the axis is
/// within 0.7 % of its final speed.  The terms fall as \f$ (2n+1)^{-3} \f$ even at t = 0, so the
/// sum is taken until a term is below a relative tolerance of the steady axis speed: at t = 0
/// the default \f$ 10^{-10} \f$ takes about a thousand terms and leaves a remainder below
/// \f$ 10^{-8} \f$ of the axis speed; from a tenth of \f$ t_\nu \f$ on, the exponentials cut
/// the sum to a handful of terms (tests/sph/test_poiseuille.cpp).

#include "sph/error.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace sph {

/// Plane Poiseuille flow between \f$ y = \pm a \f$: the steady profile (Watkins et al. 1996
/// eq 15) and the flow started from rest.
class PoiseuilleFlow {
 public:
  /// Plates at \f$ y = \pm \f$ \p half_width, driving acceleration \p acceleration, kinematic
  /// viscosity \p kinematic_viscosity (\f$ \mu_s/\rho \f$).
  PoiseuilleFlow(double half_width, double acceleration, double kinematic_viscosity)
      : a_(half_width), g_(acceleration), nu_(kinematic_viscosity) {
    require(std::isfinite(a_) && a_ > 0,
            "Poiseuille flow: the half-width a must be positive (got " + show(a_) + ")");
    require(std::isfinite(g_),
            "Poiseuille flow: the acceleration g must be finite (got " + show(g_) + ")");
    require(std::isfinite(nu_) && nu_ > 0,
            "Poiseuille flow: the kinematic viscosity must be positive (got " + show(nu_) + ")");
  }

  double half_width() const { return a_; }
  double acceleration() const { return g_; }
  double kinematic_viscosity() const { return nu_; }

  /// The steady speed at height y, eq 15: \f$ g(a^2 - y^2)/(2\nu) \f$ (zero outside the plates).
  double steady(double y) const {
    require(std::isfinite(y), "Poiseuille flow: y must be finite");
    return std::abs(y) >= a_ ? 0.0 : g_ * (a_ * a_ - y * y) / (2 * nu_);
  }

  /// The steady speed on the axis, \f$ g a^2/(2\nu) \f$.
  double axis_speed() const { return g_ * a_ * a_ / (2 * nu_); }

  /// The time of the slowest mode, \f$ t_\nu = 4a^2/(\pi^2\nu) \f$: the difference from the
  /// steady flow falls by e in each \f$ t_\nu \f$ once the faster modes have gone.
  double settling_time() const { return 4 * a_ * a_ / (std::numbers::pi * std::numbers::pi * nu_); }

  /// The speed at height y and time t of the flow started from rest at t = 0: the steady profile
  /// less its cosine series, summed until a term is below \p tolerance times the axis speed.
  double from_rest(double y, double t, double tolerance = 1e-10) const {
    require(
        std::isfinite(y) && std::isfinite(t),
        "Poiseuille flow: y and t must be finite (got y = " + show(y) + ", t = " + show(t) + ")");
    require(t >= 0, "Poiseuille flow: the flow starts at t = 0 (got t = " + show(t) + ")");
    require(tolerance > 0, "Poiseuille flow: the tolerance must be positive");
    if (std::abs(y) >= a_) return 0.0;
    const double pi = std::numbers::pi;
    const double amplitude = 16 * g_ * a_ * a_ / (nu_ * pi * pi * pi);
    const double limit = tolerance * std::abs(axis_speed());
    double sum = 0;
    for (int n = 0;; ++n) {
      const double k = 2 * n + 1;
      const double decay = std::exp(-k * k * pi * pi * nu_ * t / (4 * a_ * a_));
      const double bound = amplitude * decay / (k * k * k);  // the size of every later term
      if (bound < limit) break;
      sum += (n % 2 == 0 ? 1.0 : -1.0) / (k * k * k) * std::cos(k * pi * y / (2 * a_)) * decay;
      if (n > 10'000'000) {
        throw Error("Poiseuille flow: the series did not converge at y = " + show(y) +
                    ", t = " + show(t));
      }
    }
    return steady(y) - amplitude * sum;
  }

 private:
  double a_, g_, nu_;
};

}  // namespace sph
