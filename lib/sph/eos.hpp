#pragma once
/// \file
/// \brief Equations of state: pressure and sound speed from density and internal energy.
///
/// Each equation of state is a small value type with `pressure(rho, u)`, `sound_speed(rho, u)`
/// and `evolves_energy` (whether the energy equation is integrated at all: a polytropic or
/// isothermal gas has no use for du/dt, and a scene with one does not compute it).  One,
/// sph::Adiabats, takes the particle's index as well.

#include "sph/error.hpp"

#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace sph {

/// Ideal gas, \f$ P = (\gamma - 1)\rho u \f$, \f$ c = \sqrt{\gamma P/\rho} \f$
/// (Selhammar 1997 after eq 6).
struct IdealGas {
  double gamma = 5.0 / 3.0;
  static constexpr bool evolves_energy = true;
  static constexpr const char* name = "ideal gas";

  explicit IdealGas(double g = 5.0 / 3.0) : gamma(g) {
    require(std::isfinite(g) && g > 1.0,
            "ideal gas: the adiabatic index gamma must exceed 1 (got " + show(g) + ")");
  }
  double pressure(double rho, double u) const { return (gamma - 1.0) * rho * u; }
  double sound_speed(double rho, double u) const {
    return std::sqrt(gamma * pressure(rho, u) / rho);
  }
  /// u from pressure and density, for setting up states given as (rho, P).
  double internal_energy(double rho, double P) const { return P / ((gamma - 1.0) * rho); }
};

/// Polytropic gas, \f$ P = K\rho^\gamma \f$: pressure depends on density only.
struct Polytropic {
  double K = 1.0, gamma = 5.0 / 3.0;
  static constexpr bool evolves_energy = false;
  static constexpr const char* name = "polytropic";

  Polytropic() = default;
  Polytropic(double k, double g) : K(k), gamma(g) {
    require(std::isfinite(k) && k > 0, "polytropic gas: K must be positive");
    require(std::isfinite(g) && g >= 1.0, "polytropic gas: gamma must be at least 1");
  }
  double pressure(double rho, double) const { return K * std::pow(rho, gamma); }
  double sound_speed(double rho, double u) const {
    return std::sqrt(gamma * pressure(rho, u) / rho);
  }
};

/// Every particle on an adiabat of its own, \f$ P_i = K_i\rho_i^\gamma \f$: a polytrope whose K
/// differs from particle to particle.  Watkins et al. (1996, sect. 4.3) print their shock tube's
/// gas this way, K = 1 on one side and 1.25 on the other; chapter 9 runs it to show that such a
/// gas cannot be heated by a shock.  Nothing is integrated for the energy; the internal energy is
/// that of the ideal gas on the particle's adiabat, \f$ u_i = K_i\rho_i^{\gamma-1}/(\gamma-1)
/// \f$, set with the pressure so that the thermal energy and the figures read it.  The only
/// equation of state that knows the particle: the step passes it the index.
struct Adiabats {
  std::vector<double> K;  ///< \f$ K_i \f$, one per particle
  double gamma = 5.0 / 3.0;
  static constexpr bool evolves_energy = false;
  static constexpr bool per_particle = true;  ///< the step passes the particle's index
  static constexpr const char* name = "each particle on its own adiabat";

  Adiabats() = default;
  Adiabats(std::vector<double> k, double g) : K(std::move(k)), gamma(g) {
    require(std::isfinite(g) && g > 1.0, "adiabats: gamma must exceed 1 (got " + show(g) + ")");
    for (std::size_t i = 0; i < K.size(); ++i)
      require(std::isfinite(K[i]) && K[i] > 0, "adiabats: K of particle " + std::to_string(i) +
                                                   " is " + show(K[i]) + ", not a positive number");
  }
  double pressure(std::size_t i, double rho) const { return K[i] * std::pow(rho, gamma); }
  double sound_speed(std::size_t i, double rho) const {
    return std::sqrt(gamma * pressure(i, rho) / rho);
  }
  double internal_energy(std::size_t i, double rho) const {
    return pressure(i, rho) / ((gamma - 1.0) * rho);
  }
};

/// Isothermal gas, \f$ P = c^2 \rho \f$.
struct Isothermal {
  double c = 1.0;
  static constexpr bool evolves_energy = false;
  static constexpr const char* name = "isothermal";

  Isothermal() = default;
  explicit Isothermal(double sound) : c(sound) {
    require(std::isfinite(sound) && sound > 0, "isothermal gas: the sound speed must be positive");
  }
  double pressure(double rho, double) const { return c * c * rho; }
  double sound_speed(double, double) const { return c; }
};

/// An isothermal gas less its rest pressure, \f$ P = c^2(\rho - \rho_0) \f$: the weakly
/// compressible fluid of Morris, Fox & Zhu (1997) and most SPH liquids.  The pressure force is
/// the same as \f$ c^2\rho \f$'s for any density difference (a constant drops out of a
/// gradient), but a particle set at rest at \f$ \rho_0 \f$ feels no pressure at all, so the
/// push of the background pressure that makes a square lattice unstable is gone (chapter 8).
/// The pressure is negative where the fluid expands below \f$ \rho_0 \f$.
struct WeaklyCompressible {
  double c = 1.0;     ///< the sound speed
  double rho0 = 1.0;  ///< the density at zero pressure
  static constexpr bool evolves_energy = false;
  static constexpr const char* name = "weakly compressible";

  WeaklyCompressible() = default;
  WeaklyCompressible(double sound, double rest_density) : c(sound), rho0(rest_density) {
    require(std::isfinite(sound) && sound > 0,
            "weakly compressible fluid: the sound speed must be positive");
    require(std::isfinite(rest_density) && rest_density > 0,
            "weakly compressible fluid: the rest density must be positive");
  }
  double pressure(double rho, double) const { return c * c * (rho - rho0); }
  double sound_speed(double, double) const { return c; }
};

}  // namespace sph
