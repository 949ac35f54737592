#pragma once
/// \file
/// \brief A modern line to compare with: the viscosity switch of Morris & Monaghan (1997), in
/// the bounded form of Rosswog et al. (2000).
///
/// The standard viscosity with a coefficient of its own for every particle, which grows where
/// the gas is compressed and decays elsewhere:
/// \f[ \frac{d\alpha_i}{dt} = -\frac{\alpha_i - \alpha_\min}{\tau_i}
///     + \max(-\nabla\cdot\mathbf v_i, 0)\,(\alpha_\max - \alpha_i), \qquad
///     \tau_i = \frac{h_i}{\ell\, c_i}, \f]
/// and \f$ \Pi_{ij} \f$ of Monaghan & Gingold (1983) with \f$ \bar\alpha_{ij} \f$ and
/// \f$ \beta = 2\bar\alpha_{ij} \f$.  In a shock \f$ \alpha \f$ rises towards
/// \f$ \alpha_\max \f$ within a few particle crossings; behind it, it decays to
/// \f$ \alpha_\min \f$ over \f$ 1/\ell \approx 10 \f$ sound-crossing times of h.
/// Morris & Monaghan (1997, J. Comput. Phys. 136, 41) wrote the source without the factor
/// \f$ \alpha_\max - \alpha \f$, which Rosswog et al. (2000, A&A 360, 171) added to keep
/// \f$ \alpha \le \alpha_\max \f$; we use \f$ \alpha_\min = 0.1 \f$, \f$ \alpha_\max = 1 \f$,
/// \f$ \ell = 0.1 \f$.
///
/// It answers Selhammar's question differently: it does not ask whether a compression is a
/// shock, only whether it is one *now* -- \f$ \nabla\cdot\mathbf v < 0 \f$ -- so a smooth
/// compression still switches it on (the point Caramana, Shashkov & Whalen 1998 make about
/// every viscosity built on the divergence).
///
/// The coefficient's equation is integrated in the `with_kick` slot, exactly over each kick
/// with \f$ \tau_i \f$ and the source held (the equation is linear in \f$ \alpha \f$):
/// \f$ \alpha \to \alpha_\infty + (\alpha - \alpha_\infty)e^{-\lambda\delta t} \f$ with
/// \f$ \lambda = 1/\tau_i + S_i \f$, \f$ \alpha_\infty = (\alpha_\min/\tau_i +
/// S_i\alpha_\max)/\lambda \f$; so \f$ \alpha \f$ stays in \f$ [\alpha_\min, \alpha_\max] \f$
/// for any step.

#include "sph/error.hpp"
#include "sph/fields.hpp"
#include "sph/pair.hpp"
#include "sph/terms.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace sph {

/// The term of the Morris & Monaghan (1997) switch: a viscosity coefficient \f$ \alpha_i \f$
/// per particle that grows in compression and decays over a few sound-crossing times of h.
struct MorrisMonaghan1997 {
  static constexpr bool tracks_mu = true;
  static constexpr Needs needs = Needs::velocity_divergence;
  static constexpr const char* name = "Morris & Monaghan (1997) switch";

  double alpha_min = 0.1;
  double alpha_max = 1.0;
  double decay = 0.1;       ///< l in tau = h / (l c)
  double alpha_start = -1;  ///< the coefficient at t = 0 (negative: alpha_min)
  double nu2_factor = 0.01;

  std::vector<double> alpha;   ///< alpha_i
  std::vector<double> source;  ///< max(-div v_i, 0), from the last evaluation
  std::vector<double> inverse_tau;

  MorrisMonaghan1997() = default;
  MorrisMonaghan1997(double a_min, double a_max, double l = 0.1, double nu2 = 0.01)
      : alpha_min(a_min), alpha_max(a_max), decay(l), nu2_factor(nu2) {
    require(std::isfinite(a_min) && a_min >= 0 && std::isfinite(a_max) && a_max >= a_min,
            "Morris-Monaghan switch: need 0 <= alpha_min <= alpha_max (got " + show(a_min) + ", " +
                show(a_max) + ")");
    require(std::isfinite(l) && l > 0, "Morris-Monaghan switch: the decay factor must be positive");
    require(std::isfinite(nu2) && nu2 > 0,
            "Morris-Monaghan switch: the nu^2 factor must be positive");
  }

  std::string describe() const {
    char s[128];
    std::snprintf(s, sizeof s, "Morris-Monaghan switch, alpha in [%g, %g], beta = 2 alpha, l = %g",
                  alpha_min, alpha_max, decay);
    return s;
  }

  void resize(std::size_t n) {
    alpha.assign(n, alpha_start >= 0 ? alpha_start : alpha_min);
    source.assign(n, 0.0);
    inverse_tau.assign(n, 0.0);
  }

  template <int D>
  void after_density(std::size_t i, const ParticleView<D>& in) {
    source[i] = std::max(-in.divergence[i], 0.0);
    inverse_tau[i] = decay * in.c[i] / in.h[i];
  }

  template <int D>
  Bracket bracket(const Pair<D>& p, const ParticleView<D>& in) const {
    const double a = 0.5 * (alpha[p.i] + alpha[p.j]);
    const double rho_bar = 0.5 * (in.rho[p.i] + in.rho[p.j]);
    const double c_bar = 0.5 * (in.c[p.i] + in.c[p.j]);
    const double mu = p.rv < 0 ? p.h_bar * p.rv / (p.r2 + nu2_factor * p.h_bar * p.h_bar) : 0.0;
    return {a * (-mu * c_bar + 2.0 * mu * mu) / rho_bar, p.r2 < p.support2 ? -mu : 0.0};
  }

  template <int D>
  double signal_speed(std::size_t i, const ParticleView<D>& in) const {
    return 1.2 * alpha[i] * (in.c[i] + 2.0 * in.max_mu[i]);
  }

  /// The coefficient's own equation, exactly over the kick.
  template <int D>
  void with_kick(std::size_t i, double dt, const Vec<D>&, Vec<D>&, double&) {
    const double lambda = inverse_tau[i] + source[i];
    if (!(lambda > 0)) return;
    const double target = (alpha_min * inverse_tau[i] + source[i] * alpha_max) / lambda;
    alpha[i] = target + (alpha[i] - target) * std::exp(-lambda * dt);
  }
};

}  // namespace sph
