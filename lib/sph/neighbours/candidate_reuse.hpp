#pragma once
/// \file
/// \brief Candidates kept from step to step: the members of NeighbourSearch that reuse them.
///
/// **From step to step** a particle keeps its candidates (every particle within a margin
/// beyond 2h, found by the grid) for as long as its neighbourhood has moved little relative to
/// it; only the particles where the flow shears or compresses are searched again.  See
/// try_reuse below and LocalMotion (local_motion.hpp); docs/design.md has the measurements.
///
/// The class, its state and the grid search are in neighbour_search.hpp, which includes this
/// file at its end.

#include "sph/neighbours/neighbour_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

namespace sph {

// --- Reusing candidates ---------------------------------------------------------------
//
// A search keeps, for particle i, every j within R_i = (1 + margin) 2h_i: the candidates are
// complete within the "reach" R_i of the positions at that time, the epoch.  Let d_j be the
// displacement of j since the epoch.  A j that is not a candidate was at least R_i from i
// then, so now it is at least R_i - |d_i - d_j| away.  LocalMotion bounds |d_i - d_j| over
// the particles now near i by b_i, from the displacements in the cells around i; so the
// candidates are still complete within covered_i = R_i - b_i, and while 2h_i fits in it a
// step needs only their new distances -- no grid, no search.
//
// The cells must hold the reach, but the larger they are, the more motion a bound takes in.
// Where h spans a wide range -- a collapsed centre inside a sphere fifty times more spread
// out -- cells sized for the largest reach would bound a central particle's neighbourhood by
// the motion of the whole core, and it would be searched again at nearly every step.  So the
// bound is taken on levels of cells, each half the size of the last, from the largest reach
// down to the least, and each particle reads it on the finest level whose cells hold its
// reach (`motions_`, at most max_motion_levels).  The bound looks at
// differences of motion only, and only nearby: the plateau behind a shock, moving as one,
// keeps its candidates, and so does the gas at rest ahead of it.
//
// Particles whose 2h_i no longer fits are searched again; so, in the same update, are those
// that have used up half their margin (so that searches come in batches rather than a few
// every step).  The update then starts a new epoch: the others keep their candidates, now
// complete within covered_i, which becomes their reach.  Distances are taken between
// "unwrapped" positions (position at the full search plus the displacements of every update
// since, each by the nearest periodic image), in which the images of a candidate stay valid;
// a particle that has since crossed a periodic face gets its images translated when the list
// is written.  Everything is decided per particle, so the outcome (and every result) is the
// same for any number of threads.  A new set, box or rule falls back to a full search.
template <int D, class K>
inline bool NeighbourSearch<D, K>::try_reuse(Particles<D>& p, const Box<D>& box,
                                             const SmoothingLengthRule& rule) {
  const std::size_t n = p.size();
  if (!reusable_ || n != first_.size() || rule.mode != built_mode_ || !same_box(box, built_box_))
    return false;
  double largest_h = 0;
  if (!advance_frame(p, box, largest_h)) return false;
  // How far each particle's neighbourhood has moved relative to it, on cells about as large
  // as its reach (see the note above).
  std::array<const double*, D> moved;
  for (int a = 0; a < D; ++a) moved[a] = moved_[a].data();
  const double largest_reach = K::support * largest_h * (1.0 + search_margin);
  const double least_reach = *std::min_element(reach_.begin(), reach_.end());
  int levels = 1;
  while (levels < max_motion_levels && std::ldexp(largest_reach, -levels) >= least_reach) ++levels;
  if (motions_.size() < static_cast<std::size_t>(levels))
    motions_.resize(static_cast<std::size_t>(levels));
  const Bounds<D> extent = bounds<D>(p.position);
  for (int l = 0; l < levels; ++l)
    motions_[static_cast<std::size_t>(l)].build(p.position, box, moved,
                                                std::ldexp(largest_reach, -l), &extent);
  covered_.resize(n);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
  for (std::size_t i = 0; i < n; ++i) {
    int l = levels - 1;  // the finest level whose cells hold the reach (else the coarsest)
    while (l > 0 && motions_[l].cell_size() < reach_[i]) --l;
    covered_[i] = std::min(reach_[i], motions_[l].cell_size()) - motions_[l].bound(i);
  }
  // Settle every particle from its candidates; flag the ones to search again.
  const PositionView<D> unwrapped = unwrapped_view();
  search_again_.resize(n);
  int failed = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(| : failed) if (blocks_.size() > 1)
  for (std::size_t t = 0; t < blocks_.size(); ++t) {
    Block& block = blocks_[t];
    block.kept.clear(block.end - block.begin);
    for (std::size_t i = block.begin; i < block.end; ++i) {
      if (partial_ && !partial_[i]) {
        // A partial update (see update): a particle that is not active keeps its h.  Its
        // candidates hold every particle within 2h_i if they still cover 2h_i (else it is
        // searched again, with its h); then it refreshes its pairs only if it may hand one to
        // an active particle, i.e. if one is among its candidates.
        block.kept.first[i - block.begin] = block.kept.used;
        farthest2_[i] = 0;
        search_again_[i] = covered_[i] < K::support * p.smoothing_length[i];
        if (search_again_[i]) {
          failed = 1;
          continue;
        }
        const CandidateSpan candidates = block.span(first_[i], last_[i]);
        int near = 0;
        for (std::size_t k = 0; k < candidates.size; ++k) near |= partial_[candidates.index[k]];
        if (near) keep_own(block, i, refreshed(block, i, unwrapped), p.smoothing_length[i]);
        continue;
      }
      const bool settled = settle_from_candidates(p, rule, block, i, covered_[i], unwrapped);
      failed |= !settled;
      search_again_[i] = !settled || covered_[i] < K::support * p.smoothing_length[i] *
                                                       (1.0 + 0.5 * search_margin);
      // (a particle that failed keeps nothing now: it is kept after its search)
    }
  }
  if (failed) {
    // Search again where needed (from the h the failed settling left, which does not depend
    // on the thread count either), and start a new epoch.
    search_flagged(p, box, rule);
    for (std::size_t i = 0; i < n; ++i) {
      if (!search_again_[i]) reach_[i] = covered_[i];
    }
    for (int a = 0; a < D; ++a) epoch_[a] = unwrapped_[a];
  } else {
    ++reuses_;
  }
  // (every h is final now: the smallest near each particle tells which may hand pairs over)
  motions_[0].neighbourhood_min(p.smoothing_length.data(), h_floor_);
  finish_list(p, box, failed ? Kept::all_but_searched : Kept::all, &h_floor_);
  return true;
}

// Unwrapped positions and the epoch start at the stored positions: no particle has wrapped.
template <int D, class K>
inline void NeighbourSearch<D, K>::start_frame(const Particles<D>& p) {
  const std::size_t n = p.size();
  previous_position_ = p.position;
  for (int a = 0; a < D; ++a) {
    unwrapped_[a].resize(n);
    for (std::size_t i = 0; i < n; ++i) unwrapped_[a][i] = p.position[i][a];
    epoch_[a] = unwrapped_[a];
  }
  wrapped_.assign(n, 0);
  any_wrapped_ = false;
}

// Follow each particle since the last update by the nearest image (no particle crosses a
// quarter of a periodic box in one step: if one seems to, return false for a full search),
// accumulate its unwrapped position and its displacement since the epoch, and note how many
// periods it lies from its stored, wrapped position.  Also returns the largest h.
template <int D, class K>
inline bool NeighbourSearch<D, K>::advance_frame(const Particles<D>& p, const Box<D>& box,
                                                 double& largest_h) {
  const std::size_t n = p.size();
  for (int a = 0; a < D; ++a) moved_[a].resize(n);
  int bad = 0, any = 0;
  double h_max = 0;
#pragma omp parallel for schedule(static) reduction(|           \
                                                    : bad, any) \
    reduction(max                                               \
              : h_max) if (n >= parallel_threshold)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<D> step = box.separation(p.position[i], previous_position_[i]);
    previous_position_[i] = p.position[i];
    std::array<int, D> periods{};
    for (int a = 0; a < D; ++a) {
      if (box.periodic[a] && std::abs(step[a]) > 0.25 * box.length(a)) bad = 1;
      double& u = unwrapped_[a][i];
      u += step[a];
      moved_[a][i] = u - epoch_[a][i];
      if (box.periodic[a])
        periods[a] = static_cast<int>(std::floor((u - p.position[i][a]) / box.length(a) + 0.5));
      // (image shifts are kept in a signed byte; after 50 periods, start afresh)
      if (std::abs(periods[a]) > 50) bad = 1;
    }
    wrapped_[i] = pack_image<D>(periods);
    any |= wrapped_[i] != 0;
    h_max = std::max(h_max, p.smoothing_length[i]);
  }
  any_wrapped_ = any != 0;
  largest_h = h_max;
  return bad == 0;
}

// Refresh particle i's candidate distances and settle its h within the radius they still
// cover; false if that radius is not enough.  `unwrapped` views the unwrapped positions, in
// whose frame the images of the candidates hold.
template <int D, class K>
inline bool NeighbourSearch<D, K>::settle_from_candidates(Particles<D>& p,
                                                          const SmoothingLengthRule& rule,
                                                          Block& block, std::size_t i,
                                                          double covered,
                                                          const PositionView<D>& unwrapped) {
  const CandidateSpan found = refreshed(block, i, unwrapped);
  double& h = p.smoothing_length[i];
  bool settled = true;
  if (rule.mode == SmoothingLengthRule::Mode::neighbour_number)
    settled = settle_by_count<K>(rule, covered, found, h, shell_count_[i]);
  if (rule.mode == SmoothingLengthRule::Mode::density)
    settled = settle_by_density<K>(p, rule, i, covered, found, h);
  if (!settled || K::support * h > covered) return false;
  p.neighbour_count[i] = keep_own(block, i, found, h);
  return true;
}

// The unwrapped positions, in whose frame the candidates' images hold.
template <int D, class K>
inline PositionView<D> NeighbourSearch<D, K>::unwrapped_view() const {
  std::array<const double*, D> axes;
  for (int a = 0; a < D; ++a) axes[a] = unwrapped_[a].data();
  return PositionView<D>::of(axes, built_box_);
}

// Particle i's candidates with their present distances (in the frame of the unwrapped positions).
template <int D, class K>
inline CandidateSpan NeighbourSearch<D, K>::refreshed(Block& block, std::size_t i,
                                                      const PositionView<D>& unwrapped) const {
  const CandidateSpan found = block.span(first_[i], last_[i]);
  const PositionView<D> u = unwrapped;  // a private copy: its pointers stay in registers
#pragma omp simd simdlen(8) if (simd : D > 1)
  for (std::size_t k = 0; k < found.size; ++k)
    found.r2[k] = u.distance2(i, {found.index[k], found.image[k]});
  return found;
}

template <int D, class K>
inline bool NeighbourSearch<D, K>::same_box(const Box<D>& a, const Box<D>& b) {
  return a.lower == b.lower && a.upper == b.upper && a.periodic == b.periodic;
}

// Copy the candidates still referred to into the spare buffer, which becomes the block's.
template <int D, class K>
inline void NeighbourSearch<D, K>::compact(Block& block) {
  StoredCandidates& to = block.spare;
  to.clear();
  for (std::size_t i = block.begin; i < block.end; ++i) {
    const std::size_t first = to.size();
    to.append(block.candidates, first_[i], last_[i]);
    first_[i] = first;
    last_[i] = to.size();
  }
  std::swap(block.candidates, block.spare);
}

// The grid reports images in the frame of the stored (wrapped) positions; translate those of
// particle i's candidates to the frame of the unwrapped ones (the inverse of the translation
// in detail::keep_closer).
template <int D, class K>
inline void NeighbourSearch<D, K>::to_unwrapped_frame(Candidates& found, std::size_t i) const {
  for (std::size_t k = 0; k < found.size(); ++k)
    found.image[k] =
        subtract_images(add_images(found.image[k], wrapped_[i]), wrapped_[found.index[k]]);
}

}  // namespace sph
