#pragma once
/// \file
/// \brief The neighbour search: smoothing lengths by a rule and the neighbour list, built once
/// per step and shared by every pass.
///
/// NeighbourSearch::update chooses each h by a SmoothingLengthRule (smoothing_length.hpp) from
/// the candidates a cell grid finds within a margin beyond 2h, keeps each particle's pairs
/// within 2h_i (detail::keep_closer, keep_closer.hpp), hands every one-sided pair
/// (r_ij < 2h_i but >= 2h_j) to j as well, and writes the NeighbourList (neighbour_list.hpp).
/// From step to step it reuses each particle's candidates while its neighbourhood has moved
/// little relative to it: those members are in candidate_reuse.hpp, which this file includes
/// at its end.

#include "sph/box.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/integration/active_set.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours/cell_grid.hpp"
#include "sph/neighbours/keep_closer.hpp"
#include "sph/neighbours/local_motion.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/neighbours/search_blocks.hpp"
#include "sph/neighbours/smoothing_length.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace sph {

/// Updates smoothing lengths by a rule and builds the neighbour list (the first pass of every
/// step).  Keep one instance per scene: it reuses its buffers from step to step.
template <int D, class K = Kernel<D>>
class NeighbourSearch {
 public:
  /// Update p.smoothing_length and p.neighbour_count by `rule`, then rebuild the list.
  /// Positions on periodic axes must lie in the box (the integrator wraps them).
  ///
  /// With an ActiveSet that is not all (individual time steps), only the active particles get
  /// a new h and a list; the others keep their h, and their lists are left empty.  An active
  /// particle's list is still complete -- its pairs within 2 max(h_i, h_j) at the present
  /// positions, with the present h_j of the others: the particles that hand it one-sided pairs
  /// (those with an active particle among their candidates) refresh their pairs with their own
  /// h; the rest do nothing at all.  Should the candidates not serve (a new box or rule), the
  /// update falls back to a full search, which settles every h.
  void update(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule,
              ActiveSet active = {}) {
    const std::size_t n = p.size();
    require(n > 0, "neighbour search: no particles");
    require(n < (std::size_t{1} << 31), "neighbour search: too many particles");
    validate_rule(rule);
    if (rule.mode == SmoothingLengthRule::Mode::density)
      require_positive_masses(p, "smoothing length from density");
    // A shell count is remembered only for the set and the rule that forced it.
    if (shell_count_.size() != n || rule.neighbours != shell_rule_.neighbours ||
        rule.tolerance != shell_rule_.tolerance) {
      shell_count_.assign(n, -1);
      shell_rule_ = rule;
    }
    partial_ = nullptr;
    if (!active.all()) {
      active_flag_.assign(n, 0);
      for (std::size_t k = 0; k < active.size(n); ++k) active_flag_[active[k]] = 1;
      partial_ = active_flag_.data();
    }
    const bool reused = try_reuse(p, box, rule);
    if (!reused) {
      partial_ = nullptr;
      full_search(p, box, rule);
    }
    partial_ = nullptr;
  }

  /// Make the next update a full search (the reuse test covers motion, not particles moved or
  /// replaced by hand; it is safe to call this after such a change).
  void forget_candidates() {
    reusable_ = false;
    shell_count_.clear();
  }

  /// Updates that searched the grid (for every particle or for some), of which full searches
  /// (every particle); updates that searched for none (all reused their candidates); and the
  /// particle searches done in all.
  long searches() const { return searches_; }
  long full_searches() const { return full_searches_; }
  long reuses() const { return reuses_; }
  long particle_searches() const { return particle_searches_; }
  /// Finer grids built for particles of small h (see build_fine_grids), over all updates; and
  /// the searches whose sphere did not fit in their level's grid and went to a coarser one.
  long fine_grids_built() const { return fine_grids_built_; }
  long fine_grid_fallbacks() const { return fine_fallbacks_; }

 private:
  // The full search: grid, candidates within (1 + search_margin) 2h of every particle, h by the
  // rule, the list.  It also starts the frame in which later updates reuse the candidates.
  void full_search(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule) {
    const std::size_t n = p.size();
    initial_guess(p, box, rule);
    // Blocks of about 512 particles, handed to the threads as they come free: the work is not
    // even along the particles (the gas that moves needs more), and a fixed number of blocks,
    // whatever the thread count, keeps every result the same for any thread count.  (Blocks of
    // 2048 left four to the two threads of chapter 6's 8192-particle collapse, and the thread
    // that drew its dense centre kept the other waiting: 6 % of the run's samples were threads
    // spinning at barriers, 5 % with 512.  The lists do not depend on the blocks.)
    const std::size_t count =
        n < parallel_threshold ? 1 : std::clamp<std::size_t>(n / block_size, 1, 256);
    blocks_.resize(count);
    for (std::size_t t = 0; t < count; ++t) {
      blocks_[t].begin = n * t / count;
      blocks_[t].end = n * (t + 1) / count;
      blocks_[t].candidates.clear();
      blocks_[t].live = 0;
    }
    first_.assign(n, 0);
    last_.assign(n, 0);
    reach_.assign(n, 0.0);
    farthest2_.assign(n, 0.0);
    start_frame(p);
    built_box_ = box;
    built_mode_ = rule.mode;
    search_again_.assign(n, 1);
    search_flagged(p, box, rule);
    finish_list(p, box, Kept::none);
    reusable_ = true;
    ++full_searches_;
  }

  // Search the grid for every particle flagged in search_again_ (from its present h), replacing
  // its candidates; count the search.
  void search_flagged(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule) {
    grid_.build(p.position, box, cell_size(p.smoothing_length));
    build_fine_grids(p, box);
    std::string error;
    long searched = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : searched) if (blocks_.size() > 1)
    for (std::size_t t = 0; t < blocks_.size(); ++t) {
      try {
        searched += search_block(p, rule, blocks_[t]);
      } catch (const Error& e) {
#pragma omp critical
        if (error.empty()) error = e.what();
      }
    }
    if (!error.empty()) throw Error(error);
    ++searches_;
    particle_searches_ += searched;
  }

  // Which pairs within 2h_i are kept already when the list is finished: none (after a full
  // search), all (a reuse keeps them as it settles each particle, while the distances are at
  // hand), or all but those of the particles searched again.
  enum class Kept { none, all, all_but_searched };

  // Keep the pairs within 2 max(h_i, h_j) and write the list.  `h_floor`: see find_reverse.
  void finish_list(const Particles<D>& p, const Box<D>& box, Kept kept,
                   const std::vector<double>* h_floor = nullptr) {
    const PositionView<D> unwrapped = unwrapped_view();
#pragma omp parallel for schedule(dynamic, 1) if (blocks_.size() > 1)
    for (std::size_t t = 0; t < blocks_.size(); ++t) {
      Block& block = blocks_[t];
      if (kept == Kept::none) block.kept.clear(block.end - block.begin);
      if (kept != Kept::all) {
        // (the pairs of a particle searched again go after the others: the list finds each
        // particle's pairs wherever they are)
        for (std::size_t i = block.begin; i < block.end; ++i) {
          if (kept == Kept::none || search_again_[i])
            keep_own(block, i, refreshed(block, i, unwrapped), p.smoothing_length[i]);
        }
      }
      find_reverse(p, block, unwrapped, h_floor);
    }
    assemble_list(p, box);
  }

 public:
  const NeighbourList<D>& list() const { return list_; }
  const CellGrid<D>& grid() const { return grid_; }

  /// Relative margin of the candidate radius over 2h.  Candidates beyond 2h let the
  /// neighbour-number rule move h without a second search, and let later steps reuse the
  /// candidates while the particles have moved less than the margin (see try_reuse).
  double search_margin = 0.2;

 private:
  // The storage of the blocks (search_blocks.hpp).
  using Candidates = detail::Candidates;
  using StoredCandidates = detail::StoredCandidates;
  using KeptPairs = detail::KeptPairs;
  using Block = detail::SearchBlock;

  static CandidateSpan span_of(Candidates& c, std::size_t first, std::size_t last) {
    return {c.index.data() + first, c.image.data() + first, c.r2.data() + first, last - first};
  }

  double cell_size(const std::vector<double>& h) const {
    std::vector<double> sample;
    const std::size_t step = std::max<std::size_t>(1, h.size() / 1024);
    for (std::size_t i = 0; i < h.size(); i += step) sample.push_back(h[i]);
    std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
    const double median = sample[sample.size() / 2];
    return cell_fraction * K::support * median * (1.0 + search_margin);
  }
  // A cell of half the search radius visits 4-5 cells per axis but a smaller volume than
  // cells of the full radius (2.5^D vs 3^D times the radius^D); in 1D the full radius wins.
  static constexpr double cell_fraction = D == 1 ? 1.0 : 0.5;

  // --- Reusing candidates from step to step: defined in candidate_reuse.hpp, which tells when
  // a particle's candidates still serve and how a new epoch starts.
  bool try_reuse(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule);
  void start_frame(const Particles<D>& p);
  bool advance_frame(const Particles<D>& p, const Box<D>& box, double& largest_h);
  bool settle_from_candidates(Particles<D>& p, const SmoothingLengthRule& rule, Block& block,
                              std::size_t i, double covered, const PositionView<D>& unwrapped);
  PositionView<D> unwrapped_view() const;
  CandidateSpan refreshed(Block& block, std::size_t i, const PositionView<D>& unwrapped) const;
  static bool same_box(const Box<D>& a, const Box<D>& b);
  void compact(Block& block);
  void to_unwrapped_frame(Candidates& found, std::size_t i) const;

  // --- Searching the grid ---------------------------------------------------------------

  // Search the grid for the flagged particles of one block: h by the rule, the candidates
  // (appended, their images in the frame of the unwrapped positions) and the radius searched.
  long search_block(Particles<D>& p, const SmoothingLengthRule& rule, Block& block) {
    long searched = 0;
    Candidates& found = block.found;
    for (std::size_t i = block.begin; i < block.end; ++i) {
      if (!search_again_[i]) continue;
      // (in a partial update a particle that is not active keeps its h: its candidates only)
      if (partial_ && !partial_[i]) {
        reach_[i] = K::support * p.smoothing_length[i] * (1.0 + search_margin);
        gather(p, i, reach_[i], found);
      } else {
        reach_[i] = settle_particle(p, rule, i, found);
      }
      if (any_wrapped_) to_unwrapped_frame(found, i);
      block.live -= last_[i] - first_[i];
      first_[i] = block.candidates.size();
      block.candidates.append(found, 0, found.size());
      last_[i] = block.candidates.size();
      block.live += found.size();
      ++searched;
    }
    if (block.candidates.size() > 2 * block.live + 4096) compact(block);
    return searched;
  }

  // Gather the candidates of particle i within radius (the particle itself excluded).
  // The grid hands over blocks of scanned particles with their distances; the ones within the
  // radius are kept by writing every one and advancing the end only past the hits (about one
  // in three: a branch would be mispredicted too often).
  void gather(const Particles<D>& p, std::size_t i, double radius, Candidates& found) const {
    found.clear();
    const FineGrid* fine = fine_grid_for(p.position[i], radius);
    if (fine) {
      gather_in<true>(fine->grid, fine->index.data(), p.position[i], i, radius, found);
    } else {
      gather_in<false>(grid_, nullptr, p.position[i], i, radius, found);
    }
  }

  // The same from one grid; `mapped`: the grid holds a subset, its k-th particle is index[k].
  template <bool mapped>
  static void gather_in(const CellGrid<D>& grid, const std::uint32_t* particle, const Vec<D>& at,
                        std::size_t i, double radius, Candidates& found) {
    const double radius2 = radius * radius;
    const auto self = static_cast<std::uint32_t>(i);
    grid.for_each_block_within(
        at, radius,
        [&](const std::uint32_t* index, const double* r2, std::size_t count, Image image) {
          found.reserve_more(count);
          std::size_t end = found.count;
          for (std::size_t k = 0; k < count; ++k) {
            const std::uint32_t j = mapped ? particle[index[k]] : index[k];
            found.index[end] = j;
            found.image[end] = image;
            found.r2[end] = r2[k];
            end += (r2[k] < radius2) & !(j == self && image == 0);
          }
          found.count = end;
        });
  }

  // --- Finer grids where h is small -----------------------------------------------------
  //
  // grid_'s cells are sized for the median h (half the search radius), and enlarged until there are
  // at most a few per particle.  Where h spans a wide range, a particle of small h scans far more
  // particles than it keeps: in chapter 6's collapse the centre's h is a twentieth of the median,
  // and after the bounce the sphere's outer gas spreads the grid over a box a hundred times the
  // core, so the cells grow larger still -- at t = 3 a search scanned 40 particles for each one it
  // kept.  So the particles searched for which grid_'s cells are more than twice the size
  // cell_size() would choose for them (half the radius, the whole radius in 1D) get grids of their
  // own level, with cells 2^-l of grid_'s (l >= 2) no larger than that size: each covers the box
  // around the particles of its level that search, wide enough for their radius grown once by half,
  // and holds every particle in that box.  A search whose sphere does not fit in its level's box
  // (its radius grew) uses the next coarser grid that holds it, at last grid_.  Only in boxes with
  // no periodic axis (the images would need the box's whole width).  The candidates' order then
  // depends on the grid that found them -- the same for any number of threads.
  struct FineGrid {
    CellGrid<D> grid;
    std::vector<std::uint32_t> index;  // the grid's k-th particle is particle index[k]
    std::vector<Vec<D>> position;      // (room for its positions)
    Vec<D> lo, hi;                     // the box in which it holds every particle
    bool used = false;
  };
  static constexpr int first_fine_level = 2, max_fine_levels = 10;

  // The level of a search radius: the fewest halvings of grid_'s cell that bring it to at most
  // cell_fraction * radius; 0 (grid_ itself) where grid_'s cell is within twice that.
  int fine_level(double radius) const {
    const double ratio = coarse_cell_ / (cell_fraction * radius);
    if (!(ratio > 2.0)) return 0;
    int level = std::ilogb(ratio);
    if (std::ldexp(1.0, level) < ratio) ++level;
    return std::min(level, first_fine_level + max_fine_levels - 1);
  }

  void build_fine_grids(const Particles<D>& p, const Box<D>& box) {
    for (FineGrid& f : fine_) f.used = false;
    any_fine_ = false;
    for (int a = 0; a < D; ++a) {
      if (box.periodic[a]) return;
    }
    coarse_cell_ = grid_.cell_size(0);
    for (int a = 1; a < D; ++a) coarse_cell_ = std::min(coarse_cell_, grid_.cell_size(a));
    const std::size_t n = p.size();
    // The box of each level's searching particles.
    const double inf = std::numeric_limits<double>::infinity();
    std::array<Vec<D>, max_fine_levels> lo, hi;
    lo.fill(Vec<D>::Constant(inf));
    hi.fill(Vec<D>::Constant(-inf));
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (!search_again_[i]) continue;
      const int l = fine_level(K::support * p.smoothing_length[i] * (1.0 + search_margin));
      if (l < first_fine_level) continue;
      const auto k = static_cast<std::size_t>(l - first_fine_level);
      lo[k] = lo[k].cwiseMin(p.position[i]);
      hi[k] = hi[k].cwiseMax(p.position[i]);
      any = true;
    }
    if (!any) return;
    if (fine_.size() < static_cast<std::size_t>(max_fine_levels)) fine_.resize(max_fine_levels);
    for (std::size_t k = 0; k < static_cast<std::size_t>(max_fine_levels); ++k) {
      if (!(lo[k][0] <= hi[k][0])) continue;
      FineGrid& f = fine_[k];
      const double cell = std::ldexp(coarse_cell_, -(static_cast<int>(k) + first_fine_level));
      // (the largest radius of the level is 2 cells / cell_fraction; grown once by half)
      const double margin = 1.5 * 2.0 * cell / cell_fraction;
      f.lo = lo[k].array() - margin;
      f.hi = hi[k].array() + margin;
      f.index.clear();
      f.position.clear();
      for (std::size_t j = 0; j < n; ++j) {
        const Vec<D>& x = p.position[j];
        if ((x.array() >= f.lo.array()).all() && (x.array() <= f.hi.array()).all()) {
          f.index.push_back(static_cast<std::uint32_t>(j));
          f.position.push_back(x);
        }
      }
      f.grid.build(f.position, box, cell);
      f.used = true;
      any_fine_ = true;
      ++fine_grids_built_;
    }
  }

  // The finest grid whose cells suit `radius` and whose box holds the sphere about `at`
  // (null: grid_).
  const FineGrid* fine_grid_for(const Vec<D>& at, double radius) const {
    if (!any_fine_) return nullptr;
    const double reach = 1.01 * radius;  // (a little more: the box test is not the distance's)
    const int level = fine_level(radius);
    for (int l = level; l >= first_fine_level; --l) {
      const FineGrid& f = fine_[static_cast<std::size_t>(l - first_fine_level)];
      if (f.used && ((at.array() - reach) >= f.lo.array()).all() &&
          ((at.array() + reach) <= f.hi.array()).all()) {
        if (l < level) count_fallback();
        return &f;
      }
    }
    if (level >= first_fine_level) count_fallback();
    return nullptr;
  }
  void count_fallback() const {
#pragma omp atomic
    ++fine_fallbacks_;
  }

  // Choose h_i by the rule, growing the search radius until the candidates suffice; returns
  // the radius searched.
  double settle_particle(Particles<D>& p, const SmoothingLengthRule& rule, std::size_t i,
                         Candidates& all) {
    double& h = p.smoothing_length[i];
    double radius = K::support * h * (1.0 + search_margin);
    const double grid_extent = std::max(grid_.extent(), K::support * h);
    for (int attempt = 0; attempt < 64; ++attempt) {
      gather(p, i, radius, all);
      const CandidateSpan found = span_of(all, 0, all.size());
      const bool settled = [&] {
        switch (rule.mode) {
          case SmoothingLengthRule::Mode::fixed:
            return true;
          case SmoothingLengthRule::Mode::neighbour_number:
            return settle_by_count<K>(rule, radius, found, h, shell_count_[i]);
          case SmoothingLengthRule::Mode::density:
            return settle_by_density<K>(p, rule, i, radius, found, h);
        }
        return true;
      }();
      if (settled) {
        p.neighbour_count[i] = count_within<K>(found, h);
        // A widened search (common on a lattice, where the next shell may lie beyond the first
        // radius) keeps only the candidates within the margin of the final h: every later step
        // refreshes each one.
        const double wanted = K::support * h * (1.0 + search_margin);
        if (radius > wanted) {
          keep_within(all, wanted);
          radius = wanted;
        }
        return radius;
      }
      // Past a few times the grid's extent a wider search finds nothing new on open axes, and
      // only more periodic images on periodic ones: the target cannot be met sensibly.
      if (radius > 4.0 * grid_extent) {
        throw Error("particle " + show(i) + ": only " + show(found.size) +
                    " other particles (periodic images included) within " + show(radius) +
                    ", cannot reach " + show(rule.neighbours) + " neighbours");
      }
      radius *= 1.5;
    }
    throw Error("particle " + show(i) + " at " + to_string<D>(p.position[i]) +
                ": no smoothing length found (search radius grew to " + show(radius) + ")");
  }

  // Drop the candidates at or beyond `radius` (keeping the order of the rest).
  static void keep_within(Candidates& c, double radius) {
    const double r2max = radius * radius;
    std::size_t end = 0;
    for (std::size_t k = 0; k < c.count; ++k) {
      c.index[end] = c.index[k];
      c.image[end] = c.image[k];
      c.r2[end] = c.r2[k];
      end += c.r2[k] < r2max;
    }
    c.count = end;
  }

  // --- Writing the list -----------------------------------------------------------------

  // Keep particle i's pairs with r_ij < 2h_i (appended to `kept`, images in the frame of the
  // stored positions); returns how many.
  int keep_own(Block& block, std::size_t i, const CandidateSpan& found, double h) {
    KeptPairs& kept = block.kept;
    kept.reserve_more(found.size);
    const std::size_t count =
        detail::keep_closer(found.index, found.image, found.r2, found.size, support2<K>(h),
                            any_wrapped_ ? wrapped_.data() : nullptr, wrapped_[i],
                            kept.pairs.data() + kept.used, farthest2_[i]);
    kept.first[i - block.begin] = kept.used;
    kept.count[i - block.begin] = static_cast<std::uint32_t>(count);
    kept.used += count;
    return static_cast<int>(count);
  }

  // With every h final: the kept pairs (i, j) with r_ij >= 2h_j, which j's own candidates do
  // not give it, are handed to j.
  //
  // A particle whose farthest kept pair is closer than 2h_j for the smallest h_j near it has none;
  // in gas at rest or in uniform flow that is nearly every particle.  When `h_floor` is given (the
  // smallest h near each particle, LocalMotion::neighbourhood_min, valid for the particles not
  // searched again), those are passed over without reading their pairs; the others first compare
  // each 2h_j with their farthest pair.  The rest measure their pairs' distances again: between the
  // same unwrapped positions, with the same images (translated back from the frame of the stored
  // positions), by the same arithmetic as the refresh, so that each distance is the one that kept
  // the pair, to the bit.  In gas at rest few particles have any one-sided pair (a vectorised count
  // finds them); in a collapse, where h changes by a factor of fifty across the sphere, nearly all
  // have some -- 14 of their 64 pairs, on average, in chapter 6's 8192-particle run to t = 1 -- and
  // the gathered 2h_j, the distances and the hand-over are each one pass over the pairs.
  void find_reverse(const Particles<D>& p, Block& block, const PositionView<D>& unwrapped,
                    const std::vector<double>* h_floor) {
    block.reverse.clear();
    const double* h = p.smoothing_length.data();
    const Neighbour* kept = block.kept.pairs.data();
    const PositionView<D> u = unwrapped;  // a private copy: its pointers stay in registers
    const Image* wrapped = any_wrapped_ ? wrapped_.data() : nullptr;
    for (std::size_t i = block.begin; i < block.end; ++i) {
      if (h_floor && !search_again_[i] && farthest2_[i] < support2<K>((*h_floor)[i])) continue;
      const std::size_t first = block.kept.first[i - block.begin],
                        count = block.kept.count[i - block.begin];
      const Neighbour* pairs = kept + first;
      // Only a neighbour whose 2h_j does not reach past i's farthest pair can make a one-sided
      // pair (a load of h_j each, before any position).  The (2h_j)^2 are kept for the test.
      const double farthest2 = farthest2_[i];
      if (block.r2.size() < 2 * count) block.r2.resize(4 * count);
      double* reach2 = block.r2.data();
      double* r2 = reach2 + count;
      int possible = 0;
#pragma omp simd reduction(+ : possible)
      for (std::size_t e = 0; e < count; ++e) {
        reach2[e] = support2<K>(h[pairs[e].index]);
        possible += reach2[e] <= farthest2;
      }
      if (possible == 0) continue;
      // (in a partial update, only the active particles receive: the others have no list)
      const std::uint8_t* receives = partial_;
      const Image own = wrapped_[i];
      int one_sided = 0;
#pragma omp simd simdlen(8) reduction(+ : one_sided) if (simd : D > 1)
      for (std::size_t e = 0; e < count; ++e) {
        const Image image =
            wrapped ? subtract_images(add_images(pairs[e].image, own), wrapped[pairs[e].index])
                    : pairs[e].image;
        r2[e] = u.distance2(i, {pairs[e].index, image});
        one_sided += r2[e] >= reach2[e];
      }
      if (one_sided == 0) continue;
      // Each pair is written, and the end advanced past the one-sided ones only (a branch on
      // a test true for one pair in four or five would be mispredicted often).
      const std::size_t at = block.reverse.size();
      block.reverse.resize(at + static_cast<std::size_t>(one_sided) + 1);
      auto* out = block.reverse.data() + at;
      std::size_t handed = 0;
      for (std::size_t e = 0; e < count; ++e) {
        out[handed] = {pairs[e].index,
                       {static_cast<std::uint32_t>(i), mirror_image<D>(pairs[e].image)}};
        handed += (r2[e] >= reach2[e]) & (!receives || receives[pairs[e].index] != 0);
      }
      block.reverse.resize(at + handed);
    }
  }

  // A particle with no neighbour at all cannot be part of a fluid: stop and name it.
  void require_neighbours(const Particles<D>& p) const {
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (list_.of(i).empty() && (!partial_ || partial_[i])) {
        throw Error("particle " + show(i) + " at " + to_string<D>(p.position[i]) +
                    " has no neighbours within 2h = " + show(K::support * p.smoothing_length[i]));
      }
    }
  }

  // Point the list at each particle's kept pairs.  A particle that also receives one-sided
  // pairs gets its own pairs copied to a side buffer with those after them (in the order of the
  // particles that found them), so the list is the same for any number of threads.  Stops
  // with an error naming the first particle that has no neighbour at all.
  void assemble_list(const Particles<D>& p, const Box<D>& box) {
    const std::size_t n = p.size();
    list_.first_.resize(n);
    list_.count_.resize(n);
    std::size_t entries = 0, lonely = n;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : entries) reduction(min : lonely) \
    if (blocks_.size() > 1)
    for (std::size_t t = 0; t < blocks_.size(); ++t) {
      const Block& b = blocks_[t];
      for (std::size_t i = b.begin; i < b.end; ++i) {
        // (in a partial update the pairs of a particle that is not active were kept only to
        // hand over the one-sided ones: it has no list)
        const bool listed = !partial_ || partial_[i];
        const std::size_t first = b.kept.first[i - b.begin],
                          count = listed ? b.kept.count[i - b.begin] : 0;
        list_.first_[i] = b.kept.pairs.data() + first;
        list_.count_[i] = static_cast<std::uint32_t>(count);
        entries += count;
        if (count == 0 && listed) lonely = std::min(lonely, i);
      }
    }
    // The one-sided pairs, grouped by the particle that receives them, each group in the
    // order of the particles that found them (a counting sort; blocks are in particle order).
    std::size_t handed = 0;
    for (const auto& b : blocks_) handed += b.reverse.size();
    if (handed > 0) {
      auto& received = received_;  // per particle: how many pairs it receives, then where they go
      received.assign(n + 1, 0);
      for (const auto& b : blocks_)
        for (const auto& r : b.reverse) ++received[r.first + 1];
      // Each receiving particle's own pairs first, then room for the ones it receives: where
      // its part of the side buffer starts, then the copies (by the threads).
      auto& start = side_start_;
      start.resize(n);
      std::size_t side_size = 0;
      for (std::size_t j = 0; j < n; ++j) {
        start[j] = side_size;
        if (received[j + 1] > 0) side_size += list_.count_[j] + received[j + 1];
      }
      side_.resize(side_size);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t extra = received[j + 1];
        if (extra == 0) continue;
        std::copy_n(list_.first_[j], list_.count_[j], side_.data() + start[j]);
        list_.first_[j] = side_.data() + start[j];
        received[j + 1] = start[j] + list_.count_[j];  // where the next received pair goes
        list_.count_[j] += static_cast<std::uint32_t>(extra);
      }
      for (const auto& b : blocks_)
        for (const auto& r : b.reverse) side_[received[r.first + 1]++] = r.second;
    }
    list_.entries_ = entries + handed;
    list_.box_ = box;
    if (lonely < n) require_neighbours(p);  // (it may have received pairs since)
  }

  static constexpr std::size_t block_size = 512;  // particles per block (about)
  CellGrid<D> grid_;
  std::vector<FineGrid> fine_;  // level first_fine_level + k at k (see build_fine_grids)
  bool any_fine_ = false;
  double coarse_cell_ = 0;  // grid_'s smallest cell side
  std::vector<Block> blocks_;
  NeighbourList<D> list_;
  // Per particle: its candidates (entries first_..last_ of its block's) and the radius within
  // which they are complete at the epoch (reach_); this update's covered radius (see try_reuse)
  // and whether it is searched again.
  std::vector<std::size_t> first_, last_;
  std::vector<double> reach_, covered_;
  std::vector<std::uint8_t> search_again_;
  // During a partial update (individual time steps): 1 for the active particles, else null.
  const std::uint8_t* partial_ = nullptr;
  std::vector<std::uint8_t> active_flag_;
  // The frame the candidates live in, since the last full search.
  bool reusable_ = false;
  Box<D> built_box_;
  SmoothingLengthRule::Mode built_mode_ = SmoothingLengthRule::Mode::fixed;
  std::vector<Vec<D>> previous_position_;  // positions at the last update
  std::array<std::vector<double>, D>
      unwrapped_;                             // position at the full search + displacements since
  std::array<std::vector<double>, D> epoch_;  // unwrapped position at the start of the epoch
  std::array<std::vector<double>, D> moved_;  // displacement since the epoch
  std::vector<Image>
      wrapped_;  // periods between unwrapped and stored position, packed like an image
  bool any_wrapped_ = false;
  // The bound of local motion on cells from the largest reach down, each level half the last
  // (see try_reuse); 8 levels span a factor of 128 in h.
  static constexpr int max_motion_levels = 8;
  std::vector<LocalMotion<D>> motions_;
  std::vector<double> h_floor_;    // the smallest h near each particle (find_reverse)
  std::vector<double> farthest2_;  // the largest r_ij^2 among each particle's kept pairs
  long searches_ = 0, full_searches_ = 0, reuses_ = 0, particle_searches_ = 0;
  long fine_grids_built_ = 0;
  mutable long fine_fallbacks_ = 0;      // (counted by the searching threads, atomically)
  std::vector<std::size_t> received_;    // assemble_list: one-sided pairs per receiving particle
  std::vector<std::size_t> side_start_;  // and where each one's pairs start in side_
  std::vector<Neighbour> side_;          // the pairs of particles that receive one-sided ones
  // Neighbour-number rule: the count a lattice shell forced on each particle (-1: none), and
  // the rule it was forced under.
  std::vector<int> shell_count_;
  SmoothingLengthRule shell_rule_;
};

}  // namespace sph

// The members that reuse candidates from step to step (they need the class complete).
#include "sph/neighbours/candidate_reuse.hpp"
