#pragma once
/// \file
/// \brief The spreading of a viscous ring around a point mass (Lynden-Bell & Pringle 1974), the
/// reference of Watkins et al.'s (1996) second dynamic test, and the scaled modified Bessel
/// function it needs.
///
/// A thin ring of mass m at radius \f$ R_0 \f$ around a point mass M, in Keplerian rotation,
/// with a constant kinematic shear viscosity \f$ \nu \f$: the viscous torque between
/// neighbouring annuli moves mass in and angular momentum out.  In the dimensionless radius
/// \f$ x = R/R_0 \f$ and time \f$ \tau = 12\nu t/R_0^2 \f$ the surface density is (Watkins et al.
/// eq 20, after Pringle 1981)
/// \f[ \sigma(x, \tau) = \frac{m}{\pi R_0^2}\,\tau^{-1}\,x^{-1/4}
///     \exp\!\left[-\frac{1 + x^2}{\tau}\right] I_{1/4}\!\left(\frac{2x}{\tau}\right), \f]
/// and the gas drifts with the radial velocity of their eq 21,
/// \f$ v_R = -(3\nu/R_0)\,\partial_x \ln(x^{1/2}\sigma) \f$.
///
/// **The Bessel function.**  At the early times of the test, \f$ \tau = 0.016 \f$, the argument
/// \f$ z = 2x/\tau \f$ is 125 at the ring and passes 709 at x = 5.7, where \f$ I_{1/4}(z) \sim
/// e^z \f$ overflows a double while the exponential beside it underflows.  Their product is
/// harmless, so we never form either: with the *scaled* function
/// \f$ \tilde I_\nu(z) = e^{-z} I_\nu(z) \f$ (scaled_bessel_i),
/// \f[ \sigma = \frac{m}{\pi R_0^2}\,\tau^{-1}\,x^{-1/4}\,
///     \exp\!\left[-\frac{(1 - x)^2}{\tau}\right] \tilde I_{1/4}(2x/\tau), \f]
/// finite at every x.  \f$ \tilde I_\nu \f$ is computed from its power series for
/// \f$ z \le 40 \f$ (positive terms, no cancellation; a term is carried as its logarithm until
/// it is small enough to hold) and from the asymptotic series
/// \f$ \tilde I_\nu(z) \approx (2\pi z)^{-1/2} \sum_k (-1)^k a_k(\nu)\, z^{-k} \f$,
/// \f$ a_k = \prod_{j=1}^k [4\nu^2 - (2j - 1)^2] / (k!\,8^k) \f$, above: at z = 40 its smallest
/// term is far below round-off.  tests/sph/test_viscous_ring.cpp checks both against the
/// standard library's std::cyl_bessel_i where that does not overflow, and against each other
/// where they overlap.
///
/// **The radial velocity.**  With \f$ I_\nu' = I_{\nu+1} + (\nu/z) I_\nu \f$,
/// \f[ \partial_x \ln(x^{1/2}\sigma) = \frac{1}{2x}
///     + \frac{2}{\tau}\left[\frac{\tilde I_{5/4}(z)}{\tilde I_{1/4}(z)} - x\right], \f]
/// again of scaled functions only.  Inside the ring's radius of zero torque the gas falls in,
/// outside it moves out.

#include "sph/error.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace sph {

/// \f$ e^{-z} I_\nu(z) \f$, the modified Bessel function of the first kind scaled by
/// \f$ e^{-z} \f$, for \f$ \nu \ge 0 \f$ and \f$ z \ge 0 \f$ (file comment: series below
/// z = 40, asymptotic series above).  Throws sph::Error for a negative or non-finite argument.
inline double scaled_bessel_i(double nu, double z) {
  require(std::isfinite(nu) && nu >= 0,
          "scaled_bessel_i: the order must be finite and non-negative (got " + show(nu) + ")");
  require(std::isfinite(z) && z >= 0,
          "scaled_bessel_i: the argument must be finite and non-negative (got " + show(z) + ")");
  if (z == 0) return nu == 0 ? 1.0 : 0.0;
  if (z <= 40) {
    // sum_k (z/2)^(2k+nu) / (k! Gamma(k+nu+1)) e^-z: the first term from its logarithm, each
    // next from the last by (z/2)^2 / ((k+1)(k+1+nu)); all positive.
    double term = std::exp(nu * std::log(0.5 * z) - std::lgamma(nu + 1) - z);
    double sum = term;
    const double q = 0.25 * z * z;
    for (int k = 0; k < 1000; ++k) {
      term *= q / ((k + 1) * (k + 1 + nu));
      sum += term;
      if (term < 1e-17 * sum && k > z) break;
    }
    return sum;
  }
  // (2 pi z)^(-1/2) sum_k (-1)^k a_k / z^k, stopped when a term no longer changes the sum or
  // starts to grow (the series is asymptotic).
  const double mu = 4 * nu * nu;
  double term = 1, sum = 1;
  for (int k = 1; k < 60; ++k) {
    const double next = -term * (mu - (2.0 * k - 1) * (2.0 * k - 1)) / (k * 8.0 * z);
    if (std::abs(next) >= std::abs(term)) break;
    term = next;
    sum += term;
    if (std::abs(term) < 1e-17 * std::abs(sum)) break;
  }
  return sum / std::sqrt(2 * std::numbers::pi * z);
}

/// The Lynden-Bell & Pringle ring: a ring of mass \p mass at radius \p radius around a point
/// mass, with kinematic viscosity \p nu.  Times are given as \f$ \tau = 12\nu t/R_0^2 \f$.
struct ViscousRing {
  double mass = 1.0;    ///< m, the ring's mass
  double radius = 1.0;  ///< \f$ R_0 \f$
  double nu = 1.5e-3;   ///< \f$ \nu \f$, the kinematic shear viscosity

  ViscousRing() = default;
  ViscousRing(double m, double r0, double viscosity) : mass(m), radius(r0), nu(viscosity) {
    require(std::isfinite(m) && m > 0, "viscous ring: the mass must be positive");
    require(std::isfinite(r0) && r0 > 0, "viscous ring: the radius R0 must be positive");
    require(std::isfinite(viscosity) && viscosity > 0,
            "viscous ring: the viscosity must be positive (got " + show(viscosity) + ")");
  }

  /// \f$ \tau \f$ at time t (counted from \f$ \tau = 0 \f$), and back.
  double tau(double t) const { return 12 * nu * t / (radius * radius); }
  double time(double tau_value) const { return tau_value * radius * radius / (12 * nu); }

  /// \f$ \sigma(R, \tau) \f$ (eq 20), for R > 0 and \f$ \tau > 0 \f$.
  double surface_density(double R, double tau_value) const {
    check(R, tau_value);
    const double x = R / radius, t = tau_value;
    return mass / (std::numbers::pi * radius * radius) / t * std::pow(x, -0.25) *
           std::exp(-(1 - x) * (1 - x) / t) * scaled_bessel_i(0.25, 2 * x / t);
  }

  /// \f$ v_R(R, \tau) \f$ (eq 21): negative inside the radius of zero torque, positive outside.
  double radial_velocity(double R, double tau_value) const {
    check(R, tau_value);
    const double x = R / radius, t = tau_value, z = 2 * x / t;
    const double ratio = scaled_bessel_i(1.25, z) / scaled_bessel_i(0.25, z);
    return -3 * nu / radius * (0.5 / x + 2 / t * (ratio - x));
  }

 private:
  static void check(double R, double t) {
    require(std::isfinite(R) && R > 0,
            "viscous ring: the radius must be positive and finite (got " + show(R) + ")");
    require(std::isfinite(t) && t > 0,
            "viscous ring: tau must be positive and finite (got " + show(t) + ")");
  }
};

}  // namespace sph
