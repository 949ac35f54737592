#pragma once
/// \file
/// \brief A shear viscosity in one pass: the Laplacian of Brookshaw (1985) in the symmetric form
/// of Morris, Fox & Zhu (1997), the usual alternative to Watkins et al.'s two passes.
///
/// \f[ \frac{d\mathbf v_i}{dt}\Big|_\mathrm{visc} = \sum_j \frac{m_j(\mu_i + \mu_j)}{\rho_i\rho_j}
///     \,\frac{\mathbf r_{ij}\cdot\nabla_i W_{ij}}{r_{ij}^2 + 0.01\bar h_{ij}^2}\,
///     \mathbf v_{ij} \f]
/// (Morris, Fox & Zhu 1997, eq 8, with \f$ \mu \f$ the shear viscosity).  It is
/// \f$ \nabla\cdot(\mu\nabla\mathbf v)/\rho \f$ from the kernel's radial derivative, one sum
/// per particle, exact for a linear field on a regular set and, like Brookshaw's operator of
/// chapter 7, equal to the Navier-Stokes force only where \f$ \nabla\cdot\mathbf v = 0 \f$ and
/// \f$ \mu \f$ is constant: no bulk viscosity, no grad-div part.  Every pair pushes its two
/// particles equally and oppositely (the factor is symmetric, \f$ \mathbf v_{ij} \f$
/// antisymmetric), so it conserves momentum to round-off, which Watkins' differenced sums do
/// not; the force is along \f$ \mathbf v_{ij} \f$, not \f$ \mathbf r_{ij} \f$, so it does not
/// conserve angular momentum.  The gas is heated by the kinetic energy the pair loses:
/// \f$ \dot u_i = -\tfrac12\sum_j (\ldots)\, |\mathbf v_{ij}|^2 \ge 0 \f$.
///
/// With walls (boundaries/parabolic_walls.hpp) a wall particle lends the pair eq 17's
/// pseudo-velocity, as for Watkins' term; there is no second pass, so no pseudo-curl.
/// Time step: Morris et al.'s \f$ 0.125\,h^2/\nu \f$.

#include "sph/boundaries/parabolic_walls.hpp"
#include "sph/error.hpp"
#include "sph/fields.hpp"
#include "sph/pair.hpp"
#include "sph/terms.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace sph {

/// The one-pass shear viscosity of Morris, Fox & Zhu (1997) with a constant coefficient
/// \f$ \mu_s \f$ -- or, made by `kinematic`, a constant kinematic viscosity \f$ \nu \f$ and
/// \f$ \mu_i = \nu\rho_i \f$ at each particle (the viscous ring of chapter 10) -- and walls of
/// type Walls.
template <int D, class Walls = NoWalls>
struct MorrisFoxZhu1997 {
  double shear = 0;  ///< \f$ \mu_s \f$, constant
  double nu = 0;     ///< if positive, \f$ \mu_i = \nu\rho_i \f$ in place of `shear`
  Walls walls{};

  MorrisFoxZhu1997() = default;
  explicit MorrisFoxZhu1997(double mu_s, Walls w = {}) : shear(mu_s), walls(std::move(w)) {
    require(
        std::isfinite(mu_s) && mu_s >= 0,
        "one-pass viscosity: the shear viscosity must be non-negative (got " + show(mu_s) + ")");
  }

  /// The term with a constant kinematic viscosity \p viscosity: \f$ \mu_i + \mu_j =
  /// \nu(\rho_i + \rho_j) \f$ in the pair's factor.
  static MorrisFoxZhu1997 kinematic(double viscosity, Walls w = {}) {
    require(std::isfinite(viscosity) && viscosity > 0,
            "one-pass viscosity: the kinematic viscosity must be positive (got " + show(viscosity) +
                ")");
    MorrisFoxZhu1997 t(0.0, std::move(w));
    t.nu = viscosity;
    return t;
  }

  std::string describe() const {
    char s[96];
    if (nu > 0) {
      std::snprintf(s, sizeof s, "one-pass viscosity (Morris, Fox & Zhu 1997), nu_s = %g", nu);
      return s;
    }
    std::snprintf(s, sizeof s, "one-pass viscosity (Morris, Fox & Zhu 1997), mu_s = %g", shear);
    return s;
  }

  PairAcceleration pair_acceleration(const Pair<D>& p, const ParticleView<D>& in) const {
    double v_ij[D];
    for (int a = 0; a < D; ++a) v_ij[a] = p.v_ij[a];
    if constexpr (Walls::active) {
      if (walls.lend_velocity && sees_wall(p.i, p.j, in))
        walls.velocity_difference(p.i, p.j, in, v_ij);  // eq 17 of Watkins et al.
    }
    // r . grad_i W = gradient_factor r^2
    const double mu_sum = nu > 0 ? nu * (in.rho[p.i] + in.rho[p.j]) : 2 * shear;
    const double factor = in.m[p.j] * mu_sum / (in.rho[p.i] * in.rho[p.j]) * p.gradient_factor *
                          p.r2 / (p.r2 + 0.01 * p.h_bar * p.h_bar);
    PairAcceleration out;
    double v2 = 0;
    for (int a = 0; a < D; ++a) {
      out.a[a] = factor * v_ij[a];
      v2 += v_ij[a] * v_ij[a];
    }
    out.heat = -0.5 * factor * v2;
    return out;
  }

  static constexpr const char* timestep_name = "viscous diffusion";
  double timestep(std::size_t i, const ParticleView<D>& in) const {
    if (nu > 0) return 0.125 * in.h[i] * in.h[i] / nu;
    if (!(shear > 0)) return std::numeric_limits<double>::infinity();
    return 0.125 * in.h[i] * in.h[i] * in.rho[i] / shear;
  }
};

}  // namespace sph
