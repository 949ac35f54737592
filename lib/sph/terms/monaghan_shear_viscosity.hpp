#pragma once
/// \file
/// \brief Monaghan's artificial viscosity used as a physical one: the linear term of
/// Monaghan & Gingold (1983) on every pair, approaching or not, with walls.
///
/// \f[ \frac{d\mathbf v_i}{dt}\Big|_\mathrm{visc} = -\sum_j m_j\,\Pi_{ij}\,\nabla_i W_{ij},
///     \qquad \Pi_{ij} = -\frac{\alpha\,c\,\bar h_{ij}}{\bar\rho_{ij}}\,
///     \frac{\mathbf r_{ij}\cdot\mathbf v_{ij}}{r_{ij}^2 + 0.01\bar h_{ij}^2}. \f]
/// The artificial viscosity of chapter 4 switches this off for receding pairs; applied to all
/// pairs, its continuum limit is a Navier-Stokes viscosity of kinematic shear coefficient
/// \f$ \nu = \alpha c h / 2(D+2) \f$ -- \f$ \alpha c h/8 \f$ in 2D, the figure Watkins et al.
/// quote after Murray (1996) (their sect. 4.3) -- so a wanted \f$ \nu \f$ fixes
/// \f$ \alpha = 2(D+2)\,\nu/(c h) \f$ (`for_viscosity`).  The product \f$ \alpha c h \f$ is all
/// that enters, so the term does not care which of the three carries the viscosity.
///
/// Why \f$ 2(D+2) \f$, and what else comes with it.  The pair force is along
/// \f$ \hat{\mathbf r}_{ij} \f$ and proportional to \f$ \hat{\mathbf r}_{ij}\cdot\mathbf v_{ij}
/// \f$, so its continuum limit averages \f$ \hat r_a\hat r_b\hat r_c\hat r_d \f$ over
/// directions, \f$ (\delta_{ab}\delta_{cd} + \delta_{ac}\delta_{bd} + \delta_{ad}\delta_{bc})
/// /D(D+2) \f$, and the kernel's second moment turns the sum into
/// \f$ \nu(\nabla^2\mathbf v + 2\nabla(\nabla\cdot\mathbf v)) \f$: a shear viscosity
/// \f$ \nu \f$ and, matching eq 2 of Watkins et al., a bulk viscosity
/// \f$ \nu_b = \tfrac53\nu \f$, which the term cannot switch off.  A compression is damped at
/// \f$ \nu_b + \tfrac43\nu = 3\nu \f$, three times a shear.
///
/// Every pair pushes its two particles equally and oppositely along the line between them:
/// momentum and angular momentum are conserved to round-off, and the pair's lost kinetic energy
/// heats it, \f$ \dot u_i = \tfrac12\sum_j m_j \Pi_{ij}\,\mathbf v_{ij}\cdot\nabla_i W_{ij}
/// \ge 0 \f$.
///
/// With walls (boundaries/parabolic_walls.hpp) a wall particle lends the pair eq 17's
/// pseudo-velocity, as for the other two viscosities.  Time step: the explicit viscous limit
/// on the fastest-damped motion, the compression, \f$ 0.125\, h^2/3\nu \f$ -- the constant of
/// Morris, Fox & Zhu (1997), on the coefficient \f$ \nu_b + \tfrac43\nu \f$ that
/// Watkins' term uses too.

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

/// The linear artificial viscosity on all pairs, with the product \f$ \alpha c h \f$ of one
/// constant sound speed and smoothing length given, and walls of type Walls.
template <int D, class Walls = NoWalls>
struct MonaghanShearViscosity {
  double alpha = 0;  ///< \f$ \alpha \f$
  double c = 0;      ///< the sound speed in \f$ \Pi_{ij} \f$ (constant)
  double h = 0;      ///< the smoothing length the coefficient is quoted at (the time step's)
  Walls walls{};

  MonaghanShearViscosity() = default;
  MonaghanShearViscosity(double a, double sound_speed, double smoothing, Walls w = {})
      : alpha(a), c(sound_speed), h(smoothing), walls(std::move(w)) {
    require(std::isfinite(a) && a >= 0,
            "artificial viscosity on all pairs: alpha must be non-negative (got " + show(a) + ")");
    require(std::isfinite(sound_speed) && sound_speed > 0,
            "artificial viscosity on all pairs: the sound speed must be positive (got " +
                show(sound_speed) + ")");
    require(std::isfinite(smoothing) && smoothing > 0,
            "artificial viscosity on all pairs: the smoothing length must be positive (got " +
                show(smoothing) + ")");
  }
  /// The term whose continuum shear viscosity is \p nu at sound speed \p sound_speed and
  /// smoothing length \p smoothing: \f$ \alpha = 2(D+2)\nu/(c h) \f$.
  static MonaghanShearViscosity for_viscosity(double nu, double sound_speed, double smoothing,
                                              Walls w = {}) {
    require(std::isfinite(nu) && nu >= 0,
            "artificial viscosity on all pairs: nu must be non-negative (got " + show(nu) + ")");
    return MonaghanShearViscosity(2.0 * (D + 2) * nu / (sound_speed * smoothing), sound_speed,
                                  smoothing, std::move(w));
  }
  /// \f$ \nu = \alpha c h / 2(D+2) \f$.
  double viscosity() const { return alpha * c * h / (2.0 * (D + 2)); }

  std::string describe() const {
    char s[128];
    std::snprintf(s, sizeof s, "artificial viscosity on all pairs, alpha = %.3g (nu = %.3g)", alpha,
                  viscosity());
    return s;
  }

  PairAcceleration pair_acceleration(const Pair<D>& p, const ParticleView<D>& in) const {
    double rv = p.rv;
    if constexpr (Walls::active) {
      if (walls.lend_velocity && sees_wall(p.i, p.j, in)) {
        double v_ij[D];
        walls.velocity_difference(p.i, p.j, in, v_ij);  // eq 17 of Watkins et al.
        rv = 0;
        for (int a = 0; a < D; ++a) rv += v_ij[a] * p.r_ij[a];
      }
    }
    const double rho_bar = 0.5 * (in.rho[p.i] + in.rho[p.j]);
    const double pi_ij = -alpha * c * p.h_bar * rv / (rho_bar * (p.r2 + 0.01 * p.h_bar * p.h_bar));
    // -m_j Pi_ij grad_i W, with grad_i W = gradient_factor r_ij
    const double factor = -in.m[p.j] * pi_ij * p.gradient_factor;
    PairAcceleration out;
    for (int a = 0; a < D; ++a) out.a[a] = factor * p.r_ij[a];
    out.heat = -0.5 * factor * rv;
    return out;
  }

  static constexpr const char* timestep_name = "viscous diffusion";
  double timestep(std::size_t, const ParticleView<D>&) const {
    const double nu = viscosity();
    if (!(nu > 0)) return std::numeric_limits<double>::infinity();
    return 0.125 * h * h / (3 * nu);
  }
};

}  // namespace sph
