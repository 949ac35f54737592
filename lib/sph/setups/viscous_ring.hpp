#pragma once
/// \file
/// \brief The particles of Watkins et al.'s (1996, sect. 4.2) viscous ring: concentric rings of
/// uniform spacing, each particle's mass the Lynden-Bell & Pringle surface density at its radius
/// times the area it stands for, Keplerian rotation plus the drift of their eq 21.
///
/// Their numbers: 14500 particles, h = 0.045, the ring of radius \f$ R_0 = 1 \f$ started at
/// \f$ \tau_0 = 0.016 \f$ around a point mass with G = M = 1.  They do not give the radial
/// extent of the particles; the set-up takes it as an option (`inner`, `outer`).  The rings
/// are \f$ \delta r \approx \Delta \f$ apart (a whole number of them across the annulus), and
/// ring k at radius \f$ R_k \f$ holds \f$ n_k = \mathrm{round}(2\pi R_k\,\delta r/\Delta^2) \f$
/// particles, so that each stands for \f$ \Delta^2 \f$ of area and the particles fill the
/// annulus uniformly; \f$ \Delta \f$ is chosen to give the requested number in the annulus.
/// Each ring is turned by the golden angle against the last, so that no radial lines of
/// particles form.  A particle's mass is \f$ \sigma(R_k, \tau_0)\,2\pi R_k\,\delta r/n_k \f$:
/// the particles carry the ring's mass within the annulus (for \f$ 0.75 \le x \le 1.25 \f$
/// at \f$ \tau_0 = 0.016 \f$, all of it but half a per cent).

#include "sph/error.hpp"
#include "sph/particles.hpp"
#include "sph/reference/viscous_ring.hpp"

#include <cmath>
#include <numbers>

namespace sph::setups {

/// What makes the ring's particles.
struct ViscousRingDisc {
  int particles = 14500;  ///< about this many (the rings hold a whole number each)
  double inner = 0.5;     ///< the annulus the particles fill, in units of \f$ R_0 \f$
  double outer = 1.5;
  double tau0 = 0.016;  ///< \f$ \tau \f$ at the start (Watkins: 0.016)
  double h = 0.045;     ///< the one smoothing length (Watkins: 0.045)
  double G = 1, M = 1;  ///< the point mass (Watkins: 1 and 1)
  ViscousRing ring{1.0, 1.0, 1.5e-3};

  /// \f$ \Delta \f$: the spacing that puts `particles` into the annulus.
  double spacing() const {
    const double r0 = ring.radius;
    return r0 * std::sqrt(std::numbers::pi * (outer * outer - inner * inner) / particles);
  }

  void validate() const {
    require(particles >= 100 && particles <= 10'000'000,
            "viscous ring: 100 to 10^7 particles (got " + show(particles) + ")");
    require(std::isfinite(inner) && std::isfinite(outer) && inner > 0 && outer > inner,
            "viscous ring: the annulus needs 0 < inner < outer (got " + show(inner) + ", " +
                show(outer) + ")");
    require(std::isfinite(tau0) && tau0 > 0, "viscous ring: tau0 must be positive");
    require(std::isfinite(h) && h > 0, "viscous ring: the smoothing length must be positive");
    require(std::isfinite(G) && G > 0 && std::isfinite(M) && M > 0,
            "viscous ring: G and the central mass must be positive");
  }
};

/// The particles of \p disc at \f$ \tau_0 \f$, each with the disc's h.
inline Particles<2> make_viscous_ring(const ViscousRingDisc& disc) {
  disc.validate();
  const double r0 = disc.ring.radius;
  const double a = disc.inner * r0, b = disc.outer * r0;
  const double delta = disc.spacing();
  const int rings = std::max(1, static_cast<int>(std::lround((b - a) / delta)));
  const double dr = (b - a) / rings;
  const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
  Particles<2> p;
  for (int k = 0; k < rings; ++k) {
    const double r = a + (k + 0.5) * dr;
    const int n =
        std::max(1, static_cast<int>(std::lround(2 * std::numbers::pi * r * dr / (delta * delta))));
    const double mass = disc.ring.surface_density(r, disc.tau0) * 2 * std::numbers::pi * r * dr / n;
    const double v_phi = std::sqrt(disc.G * disc.M / r);
    const double v_r = disc.ring.radial_velocity(r, disc.tau0);
    for (int j = 0; j < n; ++j) {
      const double phi = 2 * std::numbers::pi * j / n + golden * k;
      const Vec<2> e_r(std::cos(phi), std::sin(phi)), e_phi(-std::sin(phi), std::cos(phi));
      p.add(r * e_r, v_r * e_r + v_phi * e_phi, mass, 0.0, disc.h);
    }
  }
  return p;
}

}  // namespace sph::setups
