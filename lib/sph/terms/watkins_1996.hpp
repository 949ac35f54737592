#pragma once
/// \file
/// \brief The Navier-Stokes viscosity of Watkins, Bhattal, Francis, Turner & Whitworth (1996):
/// the viscous acceleration of their eq 2 from first derivatives applied twice.
///
/// \f[ \rho\,\frac{d\mathbf v}{dt}\Big|_\mathrm{visc} = -\mu_s\nabla\times\nabla\times\mathbf v
///     + (\mu_b + 2\mu_s)\nabla(\nabla\cdot\mathbf v) + (\nabla\cdot\mathbf v)\nabla\mu_b
///     + 2(\nabla\mu_s\cdot\nabla)\mathbf v + \nabla\mu_s\times(\nabla\times\mathbf v)
///     - \tfrac23\nabla(\mu_s\nabla\cdot\mathbf v) \qquad\text{(eq 2)} \f]
/// with \f$ \mu_s \f$ and \f$ \mu_b \f$ the coefficients of shear and bulk viscosity.  For
/// constant coefficients only the first two terms remain, and the second is
/// \f$ (\mu_b + \tfrac43\mu_s)\nabla(\nabla\cdot\mathbf v) \f$.
///
/// How the step computes it (terms.hpp):
///  - **gradient pass** (after the density, so \f$ \rho_j \f$ is known): the velocity gradient
///    \f$ J_i = \sum_j (m_j/\rho_j)(\mathbf v_j - \mathbf v_i)\otimes\nabla_i W_{ij} \f$, whose
///    antisymmetric part is the curl (eq 4) and whose trace is the divergence (eq 6); when the
///    coefficients vary, also \f$ \nabla\mu_s \f$ and \f$ \nabla\mu_b \f$ (eq 7).  Then, per
///    particle, the terms that need only i's own first derivatives: \f$ (\nabla\cdot\mathbf v)
///    \nabla\mu_b \f$, \f$ 2(\nabla\mu_s\cdot\nabla)\mathbf v = 2J\nabla\mu_s \f$ (eq 8) and
///    \f$ \nabla\mu_s\times(\nabla\times\mathbf v) \f$;
///  - **force pass** (the second loop over the same list): the second derivatives, by eq 5 and
///    its divergence twin, from the curls and divergences of i and j;
///  - **after the force pass**: the per-particle terms above are added, and the gas is heated by
///    the viscous dissipation \f$ \Phi/\rho \f$, \f$ \Phi = \mu_s(2\,e{:}e - \tfrac23(\nabla\cdot
///    \mathbf v)^2) + \mu_b(\nabla\cdot\mathbf v)^2 \f$ with \f$ e \f$ the symmetric part of J.
///
/// **What it does not conserve.**  A differenced sum \f$ \sum_j V_j (A_j - A_i)\nabla_i W_{ij} \f$
/// is symmetric under \f$ i \leftrightarrow j \f$ where the pressure force is antisymmetric: the
/// pair does not push its two particles equally and oppositely, so total momentum is conserved
/// only as well as the derivative is accurate, and the dissipation \f$ \Phi \f$ balances the
/// kinetic energy the force removes only to the same accuracy.  This is the price of the
/// accuracy of Figs 1-3 (no zeroth-order error); chapter 7 measures it on static fields, and the
/// flows of the next chapter measure the drift.
///
/// **Walls** (Watkins et al. sect. 4.1.1).  Fixed boundary particles have no velocity of their
/// own worth differencing: a fluid particle beside a wall at rest would see a jump from its
/// speed to zero across one smoothing length and its derivatives would be wrong there.  So the
/// walls lend each fluid neighbour i a *pseudo-velocity* extrapolated from i's own along the
/// flow's profile, and a *pseudo-curl* for the second pass (a Walls policy, ParabolicWalls for
/// the plane channel).  It differs for each particle that looks at the wall, so it is applied
/// inside the pair functions, never stored on the wall particle.  NoWalls, the default, costs
/// nothing.
///
/// **Time step.**  An explicit viscous step is stable for
/// \f$ \delta t < C h^2/\nu \f$ (\f$ \nu = \mu/\rho \f$); the term brings the limit
/// \f$ 0.125\, h_i^2 \rho_i / (\mu_b + \tfrac43\mu_s) \f$, the constant Morris, Fox & Zhu (1997)
/// use for a one-pass Laplacian.  For these two passes it is cautious: a mode of wavenumber k
/// decays at \f$ \nu k^2 \hat W(k)^2 \f$, at most \f$ 1.2\,\nu/h^2 \f$ for M4 (at
/// \f$ kh \approx 1.8 \f$), so an explicit step is stable up to about \f$ 1.7\, h^2/\nu \f$.  The
/// other side of the same fact: modes at the particle scale are hardly damped at all
/// (\f$ \hat W \to 0 \f$).

#include "sph/boundaries/parabolic_walls.hpp"
#include "sph/derivatives/particle_set.hpp"
#include "sph/error.hpp"
#include "sph/fields.hpp"
#include "sph/kernel.hpp"
#include "sph/pair.hpp"
#include "sph/particles.hpp"
#include "sph/terms.hpp"

#include <Eigen/Geometry>  // (the cross product of the 3D curl terms)

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace sph {

/// Constant coefficients of shear and bulk viscosity \f$ \mu_s, \mu_b \f$: eq 2 reduces to its
/// first two terms, and no gradient of a coefficient is computed.
struct ConstantViscosity {
  double shear = 0;  ///< \f$ \mu_s \f$
  double bulk = 0;   ///< \f$ \mu_b \f$
  static constexpr bool varies = false;
  template <int D>
  double shear_at(std::size_t, const ParticleView<D>&) const {
    return shear;
  }
  template <int D>
  double bulk_at(std::size_t, const ParticleView<D>&) const {
    return bulk;
  }
};

/// Constant *kinematic* viscosities \f$ \nu_s, \nu_b \f$: \f$ \mu = \rho\,\nu \f$ varies with the
/// density (the viscous ring of Lynden-Bell & Pringle has constant \f$ \nu \f$).
struct KinematicViscosity {
  double shear = 0;  ///< \f$ \nu_s \f$
  double bulk = 0;   ///< \f$ \nu_b \f$
  static constexpr bool varies = true;
  template <int D>
  double shear_at(std::size_t i, const ParticleView<D>& in) const {
    return in.rho[i] * shear;
  }
  template <int D>
  double bulk_at(std::size_t i, const ParticleView<D>& in) const {
    return in.rho[i] * bulk;
  }
};

/// Coefficients given per particle by the scene (one value each, by index).
struct ParticleViscosity {
  std::vector<double> shear;  ///< \f$ \mu_{s,i} \f$
  std::vector<double> bulk;   ///< \f$ \mu_{b,i} \f$
  static constexpr bool varies = true;
  template <int D>
  double shear_at(std::size_t i, const ParticleView<D>&) const {
    return shear[i];
  }
  template <int D>
  double bulk_at(std::size_t i, const ParticleView<D>&) const {
    return bulk[i];
  }
};

/// A bulk viscosity the size of the artificial viscosity's linear term, with no shear (Watkins
/// et al. sect. 4.3, their shock tube): \f$ \mu_{b,i} = \alpha\,\rho_i\,a_i\,h_i/8 \f$ at
/// each particle, the continuum limit they quote (after Murray 1996) of the \f$ \alpha \f$ term
/// for the kinematic \f$ \nu_b = \alpha a h/8 \f$.  The paper's \f$ a_0 \f$ is read two ways:
/// each particle's sound speed now (`sound_speed` empty, the default), or one given per particle
/// (the initial sound speed of its side, Table 1's \f$ a_0 \f$).
struct ArtificialBulk {
  double alpha = 1.0;               ///< \f$ \alpha \f$ (Watkins et al.: 1)
  std::vector<double> sound_speed;  ///< \f$ a_{0,i} \f$ per particle; empty: \f$ c_i \f$ now
  static constexpr bool varies = true;
  template <int D>
  double shear_at(std::size_t, const ParticleView<D>&) const {
    return 0.0;
  }
  template <int D>
  double bulk_at(std::size_t i, const ParticleView<D>& in) const {
    const double a = sound_speed.empty() ? in.c[i] : sound_speed[i];
    return alpha * in.rho[i] * a * in.h[i] / 8;
  }
};

/// The term: Watkins et al.'s Navier-Stokes viscosity in D = 1, 2 or 3 dimensions, with
/// coefficients of type Mu (ConstantViscosity, KinematicViscosity, ParticleViscosity,
/// ArtificialBulk).  In 1D there is no curl: the whole force is the grad-div part,
/// \f$ \partial_x[(\mu_b + \tfrac43\mu_s)\,\partial_x v] \f$, from the same two passes.
template <int D, class K = Kernel<D>, class Mu = ConstantViscosity, class Walls = NoWalls>
class WatkinsViscosity {
  static_assert(D >= 1 && D <= 3, "WatkinsViscosity: 1D, 2D or 3D");
  using Mat = derivatives::Mat<D>;
  static constexpr int curl_size = D == 1 ? 0 : D == 2 ? 1 : 3;

 public:
  Mu mu{};
  Walls walls{};

  WatkinsViscosity() = default;
  explicit WatkinsViscosity(Mu coefficients) : mu(std::move(coefficients)) {}
  WatkinsViscosity(Mu coefficients, Walls w) : mu(std::move(coefficients)), walls(std::move(w)) {}

  std::string describe() const {
    char s[160];
    if constexpr (std::is_same_v<Mu, ConstantViscosity>) {
      std::snprintf(s, sizeof s,
                    "Navier-Stokes viscosity (Watkins et al. 1996), mu_s = %g, "
                    "mu_b = %g",
                    mu.shear, mu.bulk);
    } else if constexpr (std::is_same_v<Mu, KinematicViscosity>) {
      std::snprintf(s, sizeof s,
                    "Navier-Stokes viscosity (Watkins et al. 1996), nu_s = %g, "
                    "nu_b = %g",
                    mu.shear, mu.bulk);
    } else if constexpr (std::is_same_v<Mu, ArtificialBulk>) {
      std::snprintf(s, sizeof s, "bulk viscosity (Watkins et al. 1996), mu_b = %g rho %s h / 8",
                    mu.alpha, mu.sound_speed.empty() ? "c" : "a_0");
    } else {
      std::snprintf(s, sizeof s, "Navier-Stokes viscosity (Watkins et al. 1996), per particle");
    }
    return s;
  }

  // --- the term's own fields, written by the gradient pass ----------------------------------
  std::vector<Mat> velocity_gradient;       ///< \f$ J_i \f$
  std::vector<std::array<double, 3>> curl;  ///< \f$ (\nabla\times\mathbf v)_i \f$ (2D: [0])
  std::vector<double> divergence;           ///< \f$ (\nabla\cdot\mathbf v)_i \f$
  std::vector<Vec<D>> local_acceleration;   ///< the per-particle terms of eq 2, over rho
  std::vector<double> dissipation;          ///< \f$ \Phi_i/\rho_i \f$
  std::vector<double> volume;               ///< \f$ m_i/\rho_i \f$ (after the density pass)
  std::vector<double> inverse_density;      ///< \f$ 1/\rho_i \f$

  void resize(std::size_t n) {
    velocity_gradient.assign(n, Mat::Zero());
    curl.assign(n, {0, 0, 0});
    divergence.assign(n, 0.0);
    local_acceleration.assign(n, Vec<D>::Zero());
    dissipation.assign(n, 0.0);
    volume.assign(n, 0.0);
    inverse_density.assign(n, 0.0);
  }

  // --- after each particle's density: its volume, so that no pair divides ------------------
  void after_density(std::size_t i, const ParticleView<D>& in) {
    inverse_density[i] = 1.0 / in.rho[i];
    volume[i] = in.m[i] * inverse_density[i];
  }

  /// What the gradient pass sums for particle i: the velocity gradient (eqs 4 and 6, the
  /// neighbour's volume as weight) and, for varying coefficients, their gradients (eq 7).
  template <int Dim>
  struct GradientSum {
    double J[D][D] = {};                           ///< J[a][b] = d v_a / d x_b
    double grad_shear[D] = {}, grad_bulk[D] = {};  ///< gradients of mu_s and mu_b
  };
  void gradient_pair(GradientSum<D>& sum, const Pair<D>& p, const ParticleView<D>& in) const {
    const double g = volume[p.j] * p.gradient_factor;  // V_j grad_i W_ij = g r_ij
    double v_ij[D];
    for (int a = 0; a < D; ++a) v_ij[a] = p.v_ij[a];
    if constexpr (Walls::active) {
      if (walls.lend_velocity && sph::sees_wall(p.i, p.j, in)) {
        walls.velocity_difference(p.i, p.j, in, v_ij);  // eq 17: j's pseudo-velocity
      }
    }
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) sum.J[a][b] -= g * v_ij[a] * p.r_ij[b];  // (v_j - v_i) x grad
    if constexpr (Mu::varies) {
      const double ds = mu.shear_at(p.j, in) - mu.shear_at(p.i, in);
      const double db = mu.bulk_at(p.j, in) - mu.bulk_at(p.i, in);
      for (int b = 0; b < D; ++b) {
        sum.grad_shear[b] += g * ds * p.r_ij[b];
        sum.grad_bulk[b] += g * db * p.r_ij[b];
      }
    }
  }
  void gradient_finish(std::size_t i, GradientSum<D>& sum, const ParticleView<D>& in) {
    Mat J;
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) J(a, b) = sum.J[a][b];
    velocity_gradient[i] = J;
    if constexpr (D > 1) {
      const auto w = derivatives::curl<D>(J);
      for (int c = 0; c < curl_size; ++c) curl[i][c] = w[c];
    }
    const double div = J.trace();
    divergence[i] = div;
    const double shear = mu.shear_at(i, in), bulk = mu.bulk_at(i, in);
    const Mat e = 0.5 * (J + J.transpose());
    const double phi = shear * (2 * e.squaredNorm() - 2.0 / 3.0 * div * div) + bulk * div * div;
    dissipation[i] = phi / in.rho[i];
    if constexpr (Mu::varies) {
      Vec<D> gs, gb;
      for (int b = 0; b < D; ++b) {
        gs[b] = sum.grad_shear[b];
        gb[b] = sum.grad_bulk[b];
      }
      // (div v) grad mu_b + 2 (grad mu_s . grad) v + grad mu_s x curl v
      Vec<D> a = div * gb + 2.0 * (J * gs);
      const auto& w = curl[i];
      if constexpr (D == 2) {
        a += Vec<2>(gs[1] * w[0], -gs[0] * w[0]);  // (gx, gy, 0) x (0, 0, w)
      } else if constexpr (D == 3) {
        a += gs.cross(Vec<3>(w[0], w[1], w[2]));
      }  // (1D: no curl)
      local_acceleration[i] = a / in.rho[i];
    }
  }

  // --- the force pass: the second derivatives -------------------------------------------------
  PairAcceleration pair_acceleration(const Pair<D>& p, const ParticleView<D>& in) const {
    const std::size_t i = p.i, j = p.j;
    const double g = volume[j] * inverse_density[i] * p.gradient_factor;  // V_j grad W / rho_i
    const double shear_i = mu.shear_at(i, in);
    // A wall lends i the curl of eq 19 and i's own divergence; other particles their own.
    double curl_j[3] = {curl[j][0], curl[j][1], curl[j][2]};
    double divergence_j = divergence[j];
    if constexpr (Walls::active) {
      if (walls.lend_curl && sph::sees_wall(i, j, in)) {
        const double f = walls.curl_factor(i, j, in);  // (NaN: see ParabolicWalls)
        for (int c = 0; c < 3; ++c) curl_j[c] = f * curl[i][c];
        divergence_j = divergence[i];
      }
    }
    // -mu_s (w_i - w_j) x grad W
    double cc[3] = {0, 0, 0};
    if constexpr (D == 1) {
      // no curl in 1D: the whole viscous force is the grad-div part below
    } else if constexpr (D == 2) {
      const double dw = curl[i][0] - curl_j[0];
      cc[0] = -dw * p.r_ij[1];  // (0, 0, dw) x (rx, ry, 0) = (-dw ry, dw rx)
      cc[1] = dw * p.r_ij[0];
    } else {
      const double d0 = curl[i][0] - curl_j[0], d1 = curl[i][1] - curl_j[1],
                   d2 = curl[i][2] - curl_j[2];
      cc[0] = d1 * p.r_ij[2] - d2 * p.r_ij[1];
      cc[1] = d2 * p.r_ij[0] - d0 * p.r_ij[2];
      cc[2] = d0 * p.r_ij[1] - d1 * p.r_ij[0];
    }
    // the grad-div part: (mu_b + 2 mu_s) (D_j - D_i) - 2/3 (mu_s,j D_j - mu_s,i D_i)
    double gd;
    if constexpr (Mu::varies) {
      gd = (mu.bulk_at(i, in) + 2 * shear_i) * (divergence_j - divergence[i]) -
           2.0 / 3.0 * (mu.shear_at(j, in) * divergence_j - shear_i * divergence[i]);
    } else {
      gd = (mu.bulk + 4.0 / 3.0 * mu.shear) * (divergence_j - divergence[i]);
    }
    PairAcceleration out;
    for (int a = 0; a < D; ++a) out.a[a] = g * (-shear_i * cc[a] + gd * p.r_ij[a]);
    return out;
  }

  void after_force(std::size_t i, const ParticleView<D>&, Vec<D>& a, double& dudt) {
    if constexpr (Mu::varies) a += local_acceleration[i];
    dudt += dissipation[i];
  }

  static constexpr const char* timestep_name = "viscous diffusion";
  double timestep(std::size_t i, const ParticleView<D>& in) const {
    const double mu_eff = mu.bulk_at(i, in) + 4.0 / 3.0 * mu.shear_at(i, in);
    if (!(mu_eff > 0)) return std::numeric_limits<double>::infinity();
    return 0.125 * in.h[i] * in.h[i] * in.rho[i] / mu_eff;
  }
};

}  // namespace sph
