#pragma once
/// \file
/// \brief The standard artificial viscosity of Monaghan & Gingold (1983).
///
/// Selhammar (1997) eq 6, Watkins et al. (1996) eqs 9-11:
/// \f[ \Pi_{ij} = \frac{-\alpha\,\mu_{ij}\,\bar c_{ij} + \beta\,\mu_{ij}^2}{\bar\rho_{ij}}, \qquad
///     \mu_{ij} = \frac{\bar h_{ij}\; \mathbf r_{ij}\cdot\mathbf v_{ij}}{r_{ij}^2 + \nu^2}
///     \quad\text{if } \mathbf r_{ij}\cdot\mathbf v_{ij} < 0, \text{ else } \Pi_{ij} = 0, \f]
/// with \f$ \bar c_{ij} \f$ and \f$ \bar\rho_{ij} \f$ the pair means.  The \f$ \alpha \f$ term
/// is linear in the approach speed (in the continuum limit a bulk and a shear viscosity, each of
/// kinematic coefficient about \f$ \alpha c h/8 \f$: Watkins et al. 1996), the \f$ \beta \f$ term
/// the von Neumann-Richtmyer viscosity (quadratic), which stops particles passing through each
/// other in strong shocks.  \f$ \nu^2 = \epsilon_\nu \bar h_{ij}^2 \f$ keeps \f$ \mu \f$ finite for
/// close pairs.  The papers differ here (see the page 'Reading the two papers', docs/papers.md):
/// Monaghan and Watkins use \f$ \epsilon_\nu = 0.01 \f$; Selhammar writes \f$ \nu = 0.01h \f$, i.e.
/// \f$ \epsilon_\nu = 10^{-4} \f$.  We expose it and default to the Monaghan/Watkins value.

#include "sph/error.hpp"
#include "sph/fields.hpp"
#include "sph/pair.hpp"
#include "sph/terms.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace sph {

/// The term of the standard viscosity (eq 6 of Selhammar): the pair bracket
/// \f$ \Pi_{ij} = (-\alpha \bar c_{ij} \mu_{ij} + \beta \mu_{ij}^2)/\bar\rho_{ij} \f$ for
/// approaching pairs, and its signal speed for the time step.
// [declaration]
struct MonaghanGingold1983 {
  static constexpr bool tracks_mu = true;  ///< the force pass keeps max_j mu_ij (eq 7)
  static constexpr const char* name = "Monaghan & Gingold (1983) AV";

  double alpha = 1.0;        ///< bulk (linear) coefficient
  double beta = 2.0;         ///< von Neumann-Richtmyer (quadratic) coefficient
  double nu2_factor = 0.01;  ///< nu^2 = nu2_factor * h_bar^2

  MonaghanGingold1983() = default;
  MonaghanGingold1983(double a, double b, double nu2 = 0.01) : alpha(a), beta(b), nu2_factor(nu2) {
    require(std::isfinite(a) && a >= 0,
            "artificial viscosity: alpha must be non-negative (got " + std::to_string(a) + ")");
    require(std::isfinite(b) && b >= 0,
            "artificial viscosity: beta must be non-negative (got " + std::to_string(b) + ")");
    require(std::isfinite(nu2) && nu2 > 0,
            "artificial viscosity: the nu^2 factor must be positive");
  }

  std::string describe() const {
    char s[96];
    std::snprintf(s, sizeof s, "Monaghan-Gingold AV, alpha = %g, beta = %g", alpha, beta);
    return s;
  }
  // [declaration]

  /// \f$ \Pi_{ij} \f$ for one pair, added to the bracket, with \f$ \bar\rho_{ij} \f$ and
  /// \f$ \bar c_{ij} \f$ the pair means, and \f$ |\mu_{ij}| \f$ for the time step (only pairs
  /// inside the kernel's support at \f$ \bar h_{ij} \f$ count there).  Without a branch: a
  /// receding pair has \f$ \mu = 0 \f$ and so \f$ \Pi = 0 \f$ exactly.
  // [bracket]
  template <int D>
  Bracket bracket(const Pair<D>& p, const ParticleView<D>& in) const {
    const double rho_bar = 0.5 * (in.rho[p.i] + in.rho[p.j]);
    const double c_bar = 0.5 * (in.c[p.i] + in.c[p.j]);
    const double mu = p.rv < 0 ? p.h_bar * p.rv / (p.r2 + nu2_factor * p.h_bar * p.h_bar) : 0.0;
    return {(-alpha * mu * c_bar + beta * mu * mu) / rho_bar, p.r2 < p.support2 ? -mu : 0.0};
  }
  // [bracket]

  /// The viscous part of the signal speed in the time step, Selhammar eq 7:
  /// \f$ 1.2(\alpha c_i + \beta \mu_{i,\max}) \f$.
  // [signal_speed]
  template <int D>
  double signal_speed(std::size_t i, const ParticleView<D>& in) const {
    return 1.2 * (alpha * in.c[i] + beta * in.max_mu[i]);
  }
  // [signal_speed]
};

}  // namespace sph
