#pragma once
/// \file
/// \brief How each particle's smoothing length h is chosen: the rules, and what they read.
///
/// Three ways to choose h (SmoothingLengthRule):
///  - **fixed**: h_i as given (Watkins' static tests and Poiseuille flow);
///  - **neighbour number**: h_i such that particle i has N neighbours within 2h_i, within a
///    tolerance of ±ΔN (Selhammar: 64 in 3D; Watkins: ±10 %).  When the count falls outside the
///    tolerance we place 2h_i half-way between the N-th and (N+1)-th nearest neighbour, so the
///    count becomes N exactly -- no iteration is needed.  On a lattice the N-th and (N+1)-th
///    neighbour can lie on one shell; then 2h goes into the gap inside or outside that shell,
///    whichever count is nearer N (the count is then the nearest achievable, not N), and that
///    count is accepted like one within the tolerance until it changes -- otherwise a particle
///    of an unmoving lattice would select its h again every step, and always find the same;
///  - **density**: \f$ h_i = \left(\frac{N m_i}{V_D 2^D \rho_i}\right)^{1/D} \f$ with the
///    gather density \f$ \rho_i(h_i) \f$, solved per particle by Newton iteration (Watkins
///    eqs A6-A7; \f$ V_D \f$ is the volume of the unit ball, so N is the expected neighbour
///    number).
///
/// "Neighbours" never include the particle itself (its own periodic images do count).
///
/// Each rule settles h from a particle's candidates: the particles within a radius somewhat
/// beyond 2h, with their squared distances (CandidateSpan).  Beyond that radius the candidates
/// may be incomplete, so a rule that would need to look farther says so, and the caller
/// (NeighbourSearch, neighbour_search.hpp) searches a wider radius.  Whether a distance lies
/// within 2h is decided by support2 alone, everywhere.

#include "sph/box.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours/cell_grid.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace sph {

/// How smoothing lengths are chosen.
struct SmoothingLengthRule {
  enum class Mode { fixed, neighbour_number, density };
  Mode mode = Mode::neighbour_number;
  double neighbours = 64;           ///< target neighbour number N
  double tolerance = 0;             ///< neighbour_number: accepted deviation ±ΔN (absolute count)
  double density_tolerance = 1e-8;  ///< density: relative tolerance on h
  int max_iterations = 100;         ///< density: Newton iterations before giving up

  static SmoothingLengthRule fixed() { return {Mode::fixed}; }
  static SmoothingLengthRule neighbour_number(double n, double tolerance = 0) {
    return {Mode::neighbour_number, n, tolerance};
  }
  static SmoothingLengthRule from_density(double n) { return {Mode::density, n}; }
};

/// The candidates of one particle, with their squared distances: entry k is particle index[k],
/// periodic image image[k], at r_ij^2 = r2[k].  The rules below read them and never reorder
/// them.
struct CandidateSpan {
  const std::uint32_t* index;
  const Image* image;
  double* r2;
  std::size_t size;
};

/// Throw sph::Error unless `rule` is one a particle can meet: a target neighbour number of at
/// least 1, and a tolerance below it.
inline void validate_rule(const SmoothingLengthRule& rule) {
  if (rule.mode == SmoothingLengthRule::Mode::fixed) return;
  require(std::isfinite(rule.neighbours) && rule.neighbours >= 1,
          "smoothing length: the target neighbour number must be at least 1 (got " +
              show(rule.neighbours) + ")");
  require(rule.tolerance >= 0 && rule.tolerance < rule.neighbours,
          "smoothing length: the neighbour tolerance must lie in [0, N)");
}

/// Particles without a smoothing length get one from the mean volume per particle.
/// Throws sph::Error when a fixed h is not positive, or when all particles are at one point.
template <int D>
inline void initial_guess(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule) {
  const std::size_t n = p.size();
  bool all_set = true;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = p.smoothing_length[i];
    if (rule.mode == SmoothingLengthRule::Mode::fixed && !(std::isfinite(h) && h > 0)) {
      throw Error("particle " + show(i) + " has smoothing length " + show(h) +
                  " (fixed h must be positive)");
    }
    if (!(std::isfinite(h) && h > 0)) all_set = false;
  }
  if (all_set) return;
  const auto [lo, hi] = bounds<D>(p.position);
  // The volume per particle, over the axes the particles spread along: particles on a line
  // in 2D, or in a plane in 3D, fill a space of fewer dimensions, and their h comes from
  // the spacing along it (a zero extent would give h = 0).
  double volume = 1.0;
  int spread = 0;  // axes with an extent
  for (int a = 0; a < D; ++a) {
    const double extent = box.periodic[a] ? box.length(a) : hi[a] - lo[a];
    if (extent > 0) {
      volume *= extent;
      ++spread;
    }
  }
  if (spread == 0) {
    throw Error("neighbour search: all " + show(n) + " particles are at one point, " +
                to_string<D>(lo) +
                ", so nothing sets a length to start h from (give the particles "
                "distinct positions, or h)");
  }
  const double per_particle = volume / static_cast<double>(n);
  const double neighbours = std::max(rule.neighbours, 1.0);
  const double ball = spread == 1   ? unit_ball_volume<1>()
                      : spread == 2 ? unit_ball_volume<2>()
                                    : unit_ball_volume<3>();
  const double ratio = neighbours * per_particle / ball;
  const double guess = 0.5 * (spread == D ? root<D>(ratio) : std::pow(ratio, 1.0 / spread));
  for (auto& h : p.smoothing_length) {
    if (!(std::isfinite(h) && h > 0)) h = guess;
  }
}

/// (2h)^2, written once: the count, the kept pairs and the one-sided test must agree to the
/// last bit on which side of 2h a distance lies, and it grows with h in floating point too.
template <class K>
inline double support2(double h) {
  return (K::support * h) * (K::support * h);
}

/// How many of the candidates lie within 2h (r_ij^2 < support2(h)).
template <class K>
inline int count_within(const CandidateSpan& found, double h) {
  const double r2max = support2<K>(h);
  const double* r2 = found.r2;  // a local pointer: the loads are then contiguous, not gathered
  const std::size_t size = found.size;
  int count = 0;
#pragma omp simd reduction(+ : count)
  for (std::size_t k = 0; k < size; ++k) count += r2[k] < r2max;
  return count;
}

// (settle_by_count hands a lattice shell to settle_on_shell, which follows it)
template <class K>
inline bool settle_on_shell(double target, double shell, double tie, double radius,
                            const CandidateSpan& found, double& h, int& count);

/// settle_by_count's common case: the count within 2h is a few away from N, so the N-th and
/// (N+1)-th nearest candidates are among the k largest squared distances inside 2h (`below`:
/// the count is above N) or the k smallest outside it.  One pass keeps those k in a small
/// sorted array (no copy of a side, no selection over it; the test that picks a side is a
/// select, not a branch, so it costs no mispredictions) and returns the two squared distances,
/// the same values a full selection finds.  k must lie in [2, `few`], and the side must hold at
/// least k candidates.
inline constexpr std::size_t few = 16;
inline std::pair<double, double> nearest_ranks(const CandidateSpan& found, double reach2,
                                               bool below, std::size_t k) {
  // Keys ascending: the squared distances outside, or their negatives inside (so that the
  // largest inside come first); candidates on the other side get +inf.
  double best[few] = {};
  std::size_t m = 0;
  const double sign = below ? -1.0 : 1.0, none = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < found.size; ++c) {
    const double r2 = found.r2[c];
    const double key = (r2 < reach2) == below ? sign * r2 : none;
    if (m == k && !(key < best[k - 1])) continue;
    std::size_t at = m < k ? m++ : k - 1;  // insert, dropping the last when full
    while (at > 0 && key < best[at - 1]) {
      best[at] = best[at - 1];
      --at;
    }
    best[at] = key;
  }
  // below: best[k-1] is minus the N-th (the least of the k largest), best[k-2] minus the
  // (N+1)-th; otherwise best[k-2] is the N-th and best[k-1] the (N+1)-th.
  return below ? std::pair{-best[k - 1], -best[k - 2]} : std::pair{best[k - 2], best[k - 1]};
}

/// Neighbour-number rule: keep h while the count is within tolerance (or is the count a shell
/// forced last time, `shell`), else put 2h half-way between the N-th and (N+1)-th nearest
/// candidate.  False when the candidates do not reach that far (the caller widens the search).
template <class K>
inline bool settle_by_count(const SmoothingLengthRule& rule, double radius,
                            const CandidateSpan& found, double& h, int& shell) {
  const int count = count_within<K>(found, h);
  const bool accepted = std::abs(count - rule.neighbours) <= rule.tolerance || count == shell;
  if (accepted && K::support * h <= radius) return true;
  const auto n = static_cast<std::size_t>(std::llround(rule.neighbours));
  if (found.size < n + 1) return false;
  // The N-th and (N+1)-th smallest distances.  `count` of them lie inside the present 2h, so
  // both are found among the distances on one side of 2h only (typically a third of the
  // candidates): select from a copy of that side (the candidates keep their order).
  thread_local std::vector<double> side;
  const double reach2 = support2<K>(h);
  const auto inside = static_cast<std::size_t>(count);
  double rn2, rn12;  // the two squared distances
  if (inside == n) {
    // The N-th is the farthest inside, the (N+1)-th the nearest outside.
    rn2 = 0;
    rn12 = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < found.size; ++k) {
      const double r2 = found.r2[k];
      if (r2 < reach2)
        rn2 = std::max(rn2, r2);
      else
        rn12 = std::min(rn12, r2);
    }
  } else if (const bool below = inside > n;  // both inside 2h, at ranks n and n + 1 there
             (below ? inside - n : n - inside) < few) {
    // The count moved by a few (the common case from step to step): the two are among the
    // few largest distances inside (below) or the few smallest outside, kept in one pass.
    std::tie(rn2, rn12) =
        nearest_ranks(found, reach2, below, below ? inside - n + 1 : n - inside + 1);
  } else {
    side.clear();
    for (std::size_t k = 0; k < found.size; ++k) {
      if ((found.r2[k] < reach2) == below) side.push_back(found.r2[k]);
    }
    const std::size_t rank = below ? n - 1 : n - 1 - inside;  // of the N-th within `side`
    std::nth_element(side.begin(), side.begin() + static_cast<std::ptrdiff_t>(rank), side.end());
    rn2 = side[rank];
    rn12 = *std::min_element(side.begin() + static_cast<std::ptrdiff_t>(rank) + 1, side.end());
  }
  const double rn = std::sqrt(rn2);
  const double rn1 = std::sqrt(rn12);
  // Beyond `radius` the candidates may be incomplete, so order statistics there are not known.
  if (rn1 > radius) return false;
  // Distances that differ by round-off only form one shell (a lattice): no 2h separates them.
  const double tie = 1e-10 * rn1;
  if (rn1 - rn > tie) {
    h = 0.5 * (rn + rn1) / K::support;
    shell = -1;
    return true;
  }
  return settle_on_shell<K>(rule.neighbours, rn, tie, radius, found, h, shell);
}

/// The N-th and (N+1)-th neighbours lie on one shell (equal distances, as on a lattice, or
/// coincident particles at r = 0).  No radius gives exactly N; put 2h in the gap just inside or
/// just outside the shell, whichever count is nearer N (outside on a tie, and always outside a
/// shell at r = 0, so h > 0), and record that count in `count`.  False when the candidates end
/// at the shell (widen the search).
template <class K>
inline bool settle_on_shell(double target, double shell, double tie, double radius,
                            const CandidateSpan& found, double& h, int& count) {
  // Counts below and up to the shell, and the nearest distances on either side, in one pass
  // (no sort: on a lattice every particle lands here every step).
  const double below = shell - tie;  // negative for a shell at r = 0: nothing is inside it
  const double below2 = below > 0 ? below * below : -1.0, above2 = (shell + tie) * (shell + tie);
  std::size_t inside = 0, through = 0;  // counts with r below the shell, and up to its outer edge
  double r_in2 = 0, r_out2 = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < found.size; ++k) {
    const double r2 = found.r2[k];
    if (r2 < below2) {
      ++inside;
      r_in2 = std::max(r_in2, r2);
    }
    if (r2 <= above2) {
      ++through;
    } else {
      r_out2 = std::min(r_out2, r2);
    }
  }
  if (through == found.size || std::sqrt(r_out2) > radius) return false;
  const bool take_inside = inside > 0 && std::abs(static_cast<double>(inside) - target) <
                                             std::abs(static_cast<double>(through) - target);
  const double r_gap = std::sqrt(take_inside ? r_in2 : r_out2);
  h = 0.5 * (shell + r_gap) / K::support;
  count = static_cast<int>(take_inside ? inside : through);
  return true;
}

/// Density rule: Newton iteration on f(h) = rho(h) h^D - N m / (V_D 2^D) = 0, with the gather
/// density rho(h) = sum_j m_j W(r_ij, h) + m_i W(0, h).  False when 2h leaves the candidates.
template <class K, int D>
inline bool settle_by_density(const Particles<D>& p, const SmoothingLengthRule& rule, std::size_t i,
                              double radius, const CandidateSpan& found, double& h) {
  const double target =
      rule.neighbours * p.mass[i] / (unit_ball_volume<D>() * power<D>(K::support));
  double h_new = h;
  for (int iteration = 0; iteration < rule.max_iterations; ++iteration) {
    if (K::support * h_new > radius) {
      h = h_new;
      return false;
    }
    // rho h^D = sum m_j sigma w(q_j): its derivative in h is sum m_j sigma dw/dq (-q_j/h).
    double sum = p.mass[i] * K::sigma * K::shape::evaluate(0.0).w, dsum = 0;
    const double inv_h = 1.0 / h_new;
    for (std::size_t k = 0; k < found.size; ++k) {
      const double q = std::sqrt(found.r2[k]) * inv_h;
      if (q >= K::support) continue;
      const KernelShape s = K::shape::evaluate(q);
      sum += p.mass[found.index[k]] * K::sigma * s.w;
      dsum -= p.mass[found.index[k]] * K::sigma * s.dw_dq * q * inv_h;
    }
    // f(h) = sum(h) - target * ... with rho h^D = sum: solve sum(h) = target.
    const double f = sum - target;
    double step = dsum > 0 ? f / dsum : 0.0;
    if (!(dsum > 0) || std::abs(step) > 0.5 * h_new) step = f > 0 ? 0.3 * h_new : -0.3 * h_new;
    h_new = h_new - step;
    if (std::abs(step) < rule.density_tolerance * h_new) {
      h = h_new;
      return K::support * h <= radius;
    }
  }
  throw Error("particle " + show(i) + " at " + to_string<D>(p.position[i]) +
              ": smoothing length from density did not converge in " + show(rule.max_iterations) +
              " iterations (last h = " + show(h_new) + ")");
}

}  // namespace sph
