#pragma once
/// \file
/// \brief Particle penetration: how many particles have passed one another along an axis.
///
/// In a fluid, two parcels that start one behind the other along a line of flow cannot swap
/// places: the pressure between them grows without bound as they approach.  SPH particles can.
/// The pressure force between two particles is
/// \f$ m_j (P_i/\rho_i^2 + P_j/\rho_j^2)\nabla_i W \f$, and the gradient of the M4 kernel
/// vanishes at \f$ r = 0 \f$: a cold pair that approaches fast enough climbs a *finite* barrier
/// and comes out on the other side.  Monaghan & Gingold (1983) added the quadratic
/// (von Neumann-Richtmyer) term of their artificial viscosity, Selhammar (1997) eq 6, to stop
/// exactly this; Lattanzio et al. (1986, J. Comput. Phys. 62, 1) call it "controlling
/// penetration".
///
/// We measure it by the order of the particles along an axis a.  Sort the particles by their
/// initial coordinate \f$ x_a(0) \f$; a pair (i, j) with \f$ x_{i,a}(0) < x_{j,a}(0) \f$ is
/// *inverted* at time t when \f$ x_{i,a}(t) > x_{j,a}(t) \f$.  We count
///  - **adjacent inversions**: pairs that were consecutive in the initial order (the lattice
///    neighbours along the axis) and are now reversed.  Any local overturning shows here;
///  - **all inversions**: every pair now reversed (the Kendall tau distance between the
///    initial and the present order, counted by merge sort in \f$ O(N\log N) \f$).  Two streams
///    that pass through each other invert every pair of particles that have crossed, while
///    each stream keeps its own order: the adjacent count stays at one (the pair that met
///    first), the total grows like the square of the overlap;
///  - **the deepest penetration**: the largest \f$ x_{i,a}(t) - x_{j,a}(t) \f$ over inverted
///    pairs, i.e. how far a particle has passed one that started ahead of it.
///
/// The order along one axis is a meaningful measure for flows that are planar along it: shock
/// tubes, colliding slabs, 1D problems.  Pairs with the same initial coordinate (lattice planes
/// in 2D and 3D) have no order and are never counted.  On a periodic axis the positions are
/// unwrapped as \f$ x(0) + \f$ (minimum-image displacement), which is right as long as no
/// particle has moved more than half a period; pairs that face each other across the periodic
/// face are not compared.

#include "sph/box.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

namespace sph {

/// The result of order_inversions().
struct OrderInversions {
  std::size_t particles = 0;  ///< N
  std::size_t adjacent = 0;   ///< initially consecutive pairs now reversed
  std::size_t all = 0;        ///< all pairs now reversed
  double deepest = 0;         ///< max x_i - x_j over reversed pairs (i started behind j); 0 if none
  std::size_t deepest_behind = 0;  ///< particle i of the deepest pair (it started behind ...)
  std::size_t deepest_ahead = 0;   ///< ... particle j, and has passed it)

  /// The number of ordered pairs that could be inverted, N(N-1)/2.
  std::size_t pairs() const { return particles < 2 ? 0 : particles * (particles - 1) / 2; }

  /// "12738 of 79800 pairs inverted (1 adjacent), deepest 0.81 (particle 12 passed 388)".
  std::string summary() const {
    char text[200];
    std::snprintf(text, sizeof text, "%zu of %zu pairs inverted (%zu adjacent), deepest %.3g", all,
                  pairs(), adjacent, deepest);
    std::string s = text;
    if (all > 0) s += " (particle " + show(deepest_behind) + " passed " + show(deepest_ahead) + ")";
    return s;
  }
};

namespace penetration_detail {

/// Sort s[lo, hi) ascending and return the number of pairs k < l with s[k] > s[l].
inline std::size_t count_inversions(std::vector<double>& s, std::vector<double>& buffer,
                                    std::size_t lo, std::size_t hi) {
  if (hi - lo < 2) return 0;
  const std::size_t mid = lo + (hi - lo) / 2;
  std::size_t count = count_inversions(s, buffer, lo, mid) + count_inversions(s, buffer, mid, hi);
  // Merge: every element taken from the right half jumps over what is left of the left half.
  std::size_t a = lo, b = mid, out = lo;
  while (a < mid && b < hi) {
    if (s[b] < s[a]) {
      count += mid - a;
      buffer[out++] = s[b++];
    } else {
      buffer[out++] = s[a++];
    }
  }
  while (a < mid) buffer[out++] = s[a++];
  while (b < hi) buffer[out++] = s[b++];
  std::copy(buffer.begin() + static_cast<std::ptrdiff_t>(lo),
            buffer.begin() + static_cast<std::ptrdiff_t>(hi),
            s.begin() + static_cast<std::ptrdiff_t>(lo));
  return count;
}

}  // namespace penetration_detail

/// Count the pairs whose order along `axis` has flipped between `initial` and `now` (same
/// particles, same indices).  sph::Error if the sizes differ, the axis does not exist or a
/// position is not finite.
template <int D>
OrderInversions order_inversions(const std::vector<Vec<D>>& initial, const std::vector<Vec<D>>& now,
                                 const Box<D>& box, int axis = 0) {
  require(initial.size() == now.size(), "order inversions: " + show(initial.size()) +
                                            " initial positions for " + show(now.size()) +
                                            " particles");
  require(axis >= 0 && axis < D,
          "order inversions: axis " + show(axis) + " in " + show(D) + " dimensions");
  const std::size_t n = now.size();
  // Unwrapped present coordinates along the axis.
  std::vector<double> present(n);
  for (std::size_t i = 0; i < n; ++i) {
    require(initial[i].allFinite() && now[i].allFinite(),
            "order inversions: particle " + show(i) + " has a non-finite position");
    present[i] = initial[i][axis] + box.separation(now[i], initial[i])[axis];
  }
  // The initial order; ties (same initial coordinate) in present order, so they never count.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    if (initial[i][axis] != initial[j][axis]) return initial[i][axis] < initial[j][axis];
    return present[i] < present[j];
  });
  OrderInversions result;
  result.particles = n;
  std::vector<double> sequence(n);
  for (std::size_t k = 0; k < n; ++k) sequence[k] = present[order[k]];
  // Adjacent pairs.
  for (std::size_t k = 0; k + 1 < n; ++k) result.adjacent += sequence[k] > sequence[k + 1];
  // The deepest penetration: each particle against the rearmost of those that started ahead.
  std::size_t rearmost = n;  // position in `order` of the smallest present coordinate after k
  for (std::size_t k = n; k-- > 0;) {
    if (rearmost < n && sequence[k] - sequence[rearmost] > result.deepest) {
      result.deepest = sequence[k] - sequence[rearmost];
      result.deepest_behind = order[k];
      result.deepest_ahead = order[rearmost];
    }
    if (rearmost == n || sequence[k] < sequence[rearmost]) rearmost = k;
  }
  // All pairs, by merge sort.
  std::vector<double> buffer(n);
  result.all = penetration_detail::count_inversions(sequence, buffer, 0, n);
  return result;
}

}  // namespace sph
