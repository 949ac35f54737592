#pragma once
/// \file
/// \brief The density pass: the SPH sum for rho_i over the neighbour list.
///
/// Two forms appear in the papers:
///  - **pair-averaged** (Selhammar 1997 eq 5): \f$ \rho_i = \sum_j \bar m_{ij}\, W(r_{ij}, \bar h_{ij}) \f$,
///    with \f$ \bar m_{ij} = (m_i + m_j)/2 \f$ and \f$ \bar h_{ij} = (h_i + h_j)/2 \f$, the self term
///    \f$ m_i W(0, h_i) \f$ included;
///  - **gather** (Watkins et al. 1996 eq A1): \f$ \rho_i = \sum_j m_j\, W(r_{ij}, h_i) \f$.
///
/// The self term can be left out (Watkins' "random, unsettled" distribution, Fig. 3a, excludes
/// it: a random set has no particle-free zone around each particle, and with the self term the
/// density is biased high).

#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <string>

namespace sph {

/// Which density sum to use.
struct DensityForm {
  enum class Sum { pair_averaged, gather };
  Sum sum = Sum::pair_averaged;
  bool self_term = true;

  static DensityForm selhammar() { return {Sum::pair_averaged, true}; }
  static DensityForm watkins(bool self_term = true) { return {Sum::gather, self_term}; }
  const char* name() const { return sum == Sum::pair_averaged ? "pair-averaged (Selhammar eq 5)" : "gather (Watkins eq A1)"; }
};

/// rho_i of one particle by the chosen form.
template <int D, class K>
double density_of(const Particles<D>& p, const NeighbourList<D>& list, std::size_t i, DensityForm form) {
  const auto& h = p.smoothing_length;
  const auto& m = p.mass;
  double rho = form.self_term ? m[i] * K::value(0.0, h[i]) : 0.0;
  for (const Neighbour& n : list.of(i)) {
    const std::size_t j = n.index;
    const double r = list.separation(p.position, i, n).norm();
    if (form.sum == DensityForm::Sum::pair_averaged) {
      rho += 0.5 * (m[i] + m[j]) * K::value(r, 0.5 * (h[i] + h[j]));
    } else {
      rho += m[j] * K::value(r, h[i]);
    }
  }
  return rho;
}

/// Does nothing: the default for what compute_density does after each particle's sum.
struct NoFinish {
  void operator()(std::size_t) const {}
};

/// The density pass: writes p.density for every particle, then calls `finish(i)` for it in the
/// same loop (the simulation computes pressure and sound speed there, saving a pass over the
/// particles).  A particle whose sum is not positive and finite (no neighbours and no self
/// term, or a NaN upstream) is an error that names it.
template <int D, class K = Kernel<D>, class Finish = NoFinish>
void compute_density(Particles<D>& p, const NeighbourList<D>& list, DensityForm form = DensityForm::selhammar(),
                     const Finish& finish = {}) {
  const std::size_t n = p.size();
  require_positive_masses(p, "density");
  long bad = -1;
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
  for (std::size_t i = 0; i < n; ++i) {
    const double rho = density_of<D, K>(p, list, i, form);
    p.density[i] = rho;
    if (std::isfinite(rho) && rho > 0) {
      finish(i);
    } else {
#pragma omp critical
      if (bad < 0 || static_cast<long>(i) < bad) bad = static_cast<long>(i);
    }
  }
  if (bad >= 0) {
    const auto i = static_cast<std::size_t>(bad);
    throw Error("density: particle " + std::to_string(i) + " at " + to_string<D>(p.position[i]) +
                " has density " + std::to_string(p.density[i]) + " (" +
                std::to_string(list.of(i).size()) + " neighbours, h = " +
                std::to_string(p.smoothing_length[i]) + ")");
  }
}

}  // namespace sph
