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

#include <span>
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

/// rho_i of one particle by the chosen form.  The loop over neighbours has no branches (the
/// form is chosen outside it, and a pair past the kernel's support adds an exact zero), so the
/// compiler runs it on several pairs at once in SIMD registers.
template <int D, class K>
double density_of(const Particles<D>& p, const NeighbourList<D>& list, const PositionView<D>& positions,
                  std::size_t i, DensityForm form) {
  const PositionView<D> x = positions;  // a private copy: its pointers stay in registers
  const double* h = p.smoothing_length.data();
  const double* m = p.mass.data();
  const std::span<const Neighbour> nb = list.of(i);
  const auto count = static_cast<std::ptrdiff_t>(nb.size());
  double rho = 0;
  if (form.sum == DensityForm::Sum::pair_averaged) {
#pragma omp simd simdlen(8) if(simd : D > 1) reduction(+ : rho)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      const Neighbour& n = nb[static_cast<std::size_t>(k)];
      const std::size_t j = n.index;
      rho += 0.5 * (m[i] + m[j]) * K::value(x.distance(i, n), 0.5 * (h[i] + h[j]));
    }
  } else {
#pragma omp simd simdlen(8) if(simd : D > 1) reduction(+ : rho)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      const Neighbour& n = nb[static_cast<std::size_t>(k)];
      rho += m[n.index] * K::value(x.distance(i, n), h[i]);
    }
  }
  return rho + (form.self_term ? m[i] * K::value(0.0, h[i]) : 0.0);
}

/// Does nothing: the default for what compute_density does after each particle's sum.
struct NoFinish {
  void operator()(std::size_t) const {}
};

/// The density pass: writes p.density for every particle, then calls `finish(i)` for it in the
/// same loop (the simulation computes pressure and sound speed there, saving a pass over the
/// particles).  A particle whose sum is not positive and finite (no neighbours and no self
/// term, or a NaN upstream) is an error that names it.  `positions` are p.position one array
/// per axis (PositionArrays); the overload below makes them.
template <int D, class K = Kernel<D>, class Finish = NoFinish>
void compute_density(Particles<D>& p, const NeighbourList<D>& list, const PositionView<D>& positions,
                     DensityForm form = DensityForm::selhammar(), const Finish& finish = {}) {
  const std::size_t n = p.size();
  require_positive_masses(p, "density");
  long bad = -1;
#pragma omp parallel for schedule(dynamic, 512) if (n >= parallel_threshold)
  for (std::size_t i = 0; i < n; ++i) {
    const double rho = density_of<D, K>(p, list, positions, i, form);
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

/// The density pass at the particles' current positions.
template <int D, class K = Kernel<D>, class Finish = NoFinish>
void compute_density(Particles<D>& p, const NeighbourList<D>& list, DensityForm form = DensityForm::selhammar(),
                     const Finish& finish = {}) {
  PositionArrays<D> positions;
  positions.assign(p.position);
  compute_density<D, K>(p, list, positions.view(list.box()), form, finish);
}

}  // namespace sph
