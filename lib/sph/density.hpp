#pragma once
/// \file
/// \brief The density pass: the SPH sum for rho_i over the neighbour list.
///
/// Two forms appear in the papers:
///  - **pair-averaged** (Selhammar 1997 eq 5):
///    \f$ \rho_i = \sum_j \bar m_{ij}\, W(r_{ij}, \bar h_{ij}) \f$, with
///    \f$ \bar m_{ij} = (m_i + m_j)/2 \f$ and \f$ \bar h_{ij} = (h_i + h_j)/2 \f$, the self
///    term \f$ m_i W(0, h_i) \f$ included;
///  - **gather** (Watkins et al. 1996 eq A1): \f$ \rho_i = \sum_j m_j\, W(r_{ij}, h_i) \f$.
///
/// The same pass can sum, when a term of the scene asks for them (fields.hpp, Needs), the rate
/// of change of that density by the continuity equation and the velocity divergence and curl,
/// with the same masses and kernel as the density:
/// \f[ \dot\rho_i = \sum_j w_{ij}\, \mathbf v_{ij}\cdot\nabla_i W_{ij}, \qquad
///     (\nabla\cdot\mathbf v)_i = -\frac{\dot\rho_i}{\rho_i}, \qquad
///     (\nabla\times\mathbf v)_i
///       = \frac{1}{\rho_i} \sum_j w_{ij}\, \mathbf v_{ij}\times\nabla_i W_{ij}, \f]
/// with \f$ w_{ij} = \bar m_{ij} \f$ and \f$ W_{ij} = W(r_{ij}, \bar h_{ij}) \f$ (pair-averaged)
/// or \f$ m_j \f$ and \f$ W(r_{ij}, h_i) \f$ (gather).  \f$ \dot\rho_i \f$ is then exactly the
/// time derivative of the density sum at fixed h (Selhammar eqs 10-11 use it to tell
/// compression from a shock).  For a linear velocity field, wherever the kernel's first moments
/// vanish (the interior of a regular lattice), both derivatives are those of the field times
/// the discrete normalisation of the kernel's second moment,
/// \f$ \kappa = -\rho_i^{-1} \sum_j w_{ij} (\mathbf r_{ij})_x (\nabla_i W_{ij})_x \f$, which is 1
/// only in the continuum limit: on cubic lattices at h = 1.3 dx it is 1 + 1.9 %, 1 + 1.1 % and
/// 1 - 0.4 % in 1D, 2D and 3D (tests/sph/test_velocity_fields.cpp).  SPHENIX sums these fields
/// in its density loop too.
///
/// The self term can be left out (Watkins' "random, unsettled" distribution, Fig. 3a, excludes
/// it: a random set has no particle-free zone around each particle, and with the self term the
/// density is biased high).

#include "sph/fields.hpp"
#include "sph/integration/active_set.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <span>
#include <utility>
#include <string>

namespace sph {

/// Which density sum to use.
struct DensityForm {
  enum class Sum { pair_averaged, gather };
  Sum sum = Sum::pair_averaged;
  bool self_term = true;

  static DensityForm selhammar() { return {Sum::pair_averaged, true}; }
  static DensityForm watkins(bool self_term = true) { return {Sum::gather, self_term}; }
  const char* name() const {
    return sum == Sum::pair_averaged ? "pair-averaged (Selhammar eq 5)" : "gather (Watkins eq A1)";
  }
};

/// rho_i of one particle by the chosen form.  The loop over neighbours has no branches (the
/// form is chosen outside it, and a pair past the kernel's support adds an exact zero), so the
/// compiler runs it on several pairs at once in SIMD registers.
template <int D, class K>
double density_of(const Particles<D>& p, const NeighbourList<D>& list,
                  const PositionView<D>& positions, std::size_t i, DensityForm form) {
  const PositionView<D> x = positions;  // a private copy: its pointers stay in registers
  const double* h = p.smoothing_length.data();
  const double* m = p.mass.data();
  const std::span<const Neighbour> nb = list.of(i);
  const auto count = static_cast<std::ptrdiff_t>(nb.size());
  double rho = 0;
  if (form.sum == DensityForm::Sum::pair_averaged) {
#pragma omp simd simdlen(8) if (simd : D > 1) reduction(+ : rho)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      const Neighbour& n = nb[static_cast<std::size_t>(k)];
      const std::size_t j = n.index;
      rho += 0.5 * (m[i] + m[j]) * K::value(x.distance(i, n), 0.5 * (h[i] + h[j]));
    }
  } else {
#pragma omp simd simdlen(8) if (simd : D > 1) reduction(+ : rho)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      const Neighbour& n = nb[static_cast<std::size_t>(k)];
      rho += m[n.index] * K::value(x.distance(i, n), h[i]);
    }
  }
  return rho + (form.self_term ? m[i] * K::value(0.0, h[i]) : 0.0);
}

/// The velocity sums of one particle: \f$ \sum_j w_{ij} \mathbf v_{ij}\cdot\nabla_i W_{ij} \f$
/// and the components of \f$ \sum_j w_{ij} \mathbf v_{ij}\times\nabla_i W_{ij} \f$.
struct VelocitySums {
  double rate = 0;
  double curl[3] = {0, 0, 0};
};

/// The density and the velocity sums the scene needs, for one particle, in one loop over its
/// neighbours: the pair's separation, distance and kernel shape are computed once and serve
/// both sums (Shape::evaluate gives W and dW/dq together).  rho is the same sum as
/// density_of's, to round-off: the compiler may vectorise and contract the longer loop body
/// differently (a different order of additions in the SIMD lanes, products fused into FMAs
/// elsewhere), so rho may differ from density_of's in its last bits -- a scene that asks for
/// velocity fields is not bitwise the scene that does not (tests/sph/test_velocity_fields.cpp
/// bounds the difference).  Returns rho without the self term.
template <int D, class K, Needs needs>
std::pair<double, VelocitySums> density_and_velocity_sums(
    const Particles<D>& p, const NeighbourList<D>& list, const PositionView<D>& positions,
    const std::array<const double*, D>& velocities, std::size_t i, DensityForm form) {
  constexpr bool curl = has(needs, Needs::velocity_curl) && D > 1;
  using Shape = typename K::shape;
  const PositionView<D> x = positions;  // private copies: their pointers stay in registers
  const std::array<const double*, D> v = velocities;
  const double* h = p.smoothing_length.data();
  const double* m = p.mass.data();
  const std::span<const Neighbour> nb = list.of(i);
  const auto count = static_cast<std::ptrdiff_t>(nb.size());
  const bool averaged = form.sum == DensityForm::Sum::pair_averaged;
  double rho = 0, rate = 0, c0 = 0, c1 = 0, c2 = 0;
#pragma omp simd simdlen(8) if (simd : D > 1) reduction(+ : rho, rate, c0, c1, c2)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const Neighbour& n = nb[static_cast<std::size_t>(k)];
    const std::size_t j = n.index;
    double r_ij[3] = {0, 0, 0}, v_ij[3] = {0, 0, 0}, r2 = 0, rv = 0;
#pragma GCC unroll 3
    for (int a = 0; a < D; ++a) {
      r_ij[a] = x.separation(a, i, n);
      v_ij[a] = v[a][i] - v[a][j];
      r2 += r_ij[a] * r_ij[a];
      rv += r_ij[a] * v_ij[a];
    }
    const double w = averaged ? 0.5 * (m[i] + m[j]) : m[j];
    const double inv_h = 1.0 / (averaged ? 0.5 * (h[i] + h[j]) : h[i]);
    const auto shape = Shape::evaluate(std::sqrt(r2) * inv_h);
    const double norm = K::sigma * power<D>(inv_h);
    rho += w * (norm * shape.w);
    const double wg = w * (norm * inv_h * inv_h * shape.dw_dq_over_q);
    rate += wg * rv;
    if constexpr (curl) {
      // v_ij x r_ij: in 2D its z-component only.
      if constexpr (D == 2) {
        c0 += wg * (v_ij[0] * r_ij[1] - v_ij[1] * r_ij[0]);
      } else {
        c0 += wg * (v_ij[1] * r_ij[2] - v_ij[2] * r_ij[1]);
        c1 += wg * (v_ij[2] * r_ij[0] - v_ij[0] * r_ij[2]);
        c2 += wg * (v_ij[0] * r_ij[1] - v_ij[1] * r_ij[0]);
      }
    }
  }
  return {rho, VelocitySums{rate, {c0, c1, c2}}};
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
///
/// With `needs` other than Needs::nothing, the same pass also writes the fields asked for into
/// `fields` (density_rate, velocity_divergence, velocity_curl), from `velocities` one array
/// per axis, in the same loop over each particle's neighbours as rho
/// (density_and_velocity_sums); without, the pass is the plain density sum and `velocities` is
/// not read.  rho is the same sum in both, equal to round-off.  Only the particles of
/// `active` are computed (all by default; with individual time steps, those whose step ends
/// now).
template <int D, class K = Kernel<D>, Needs needs = Needs::nothing, class Finish = NoFinish>
void compute_density(Particles<D>& p, const NeighbourList<D>& list,
                     const PositionView<D>& positions, DensityForm form = DensityForm::selhammar(),
                     const Finish& finish = {}, const std::array<const double*, D>& velocities = {},
                     DerivedFields<D>* fields = nullptr, ActiveSet active = {}) {
  const std::size_t n = p.size();
  require_positive_masses(p, "density");
  constexpr bool rates = any_velocity_field(needs);
  if constexpr (rates) {
    require(fields != nullptr, "density: velocity fields asked for without a place to put them");
    fields->resize(needs, n);
  }
  long bad = -1;
  const std::size_t count = active.size(n);
  // (chunks of 512 particles; of 64 for a subset, which is often small)
  const int chunk = active.all() ? 512 : 64;
#pragma omp parallel for schedule(dynamic, chunk) if (n >= parallel_threshold)
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = active[k];
    double rho;
    if constexpr (rates) {
      const auto [sum, sums] =
          density_and_velocity_sums<D, K, needs>(p, list, positions, velocities, i, form);
      rho = sum + (form.self_term ? p.mass[i] * K::value(0.0, p.smoothing_length[i]) : 0.0);
      if constexpr (has(needs, Needs::density_rate)) fields->density_rate[i] = sums.rate;
      if constexpr (has(needs, Needs::velocity_divergence))
        fields->velocity_divergence[i] = -sums.rate / rho;
      if constexpr (has(needs, Needs::velocity_curl)) {
        for (int a = 0; a < curl_components<D>; ++a)
          fields->velocity_curl[a][i] = sums.curl[a] / rho;
      }
    } else {
      rho = density_of<D, K>(p, list, positions, i, form);
    }
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
    throw Error("density: particle " + show(i) + " at " + to_string<D>(p.position[i]) +
                " has density " + show(p.density[i]) + " (" + show(list.of(i).size()) +
                " neighbours, h = " + show(p.smoothing_length[i]) + ")");
  }
}

/// The density pass at the particles' current positions.
template <int D, class K = Kernel<D>, class Finish = NoFinish>
void compute_density(Particles<D>& p, const NeighbourList<D>& list,
                     DensityForm form = DensityForm::selhammar(), const Finish& finish = {}) {
  PositionArrays<D> positions;
  positions.assign(p.position);
  compute_density<D, K, Needs::nothing>(p, list, positions.view(list.box()), form, finish);
}

}  // namespace sph
