#pragma once
/// \file
/// \brief Smoothing lengths and the neighbour list, built once per step and shared by every pass.
///
/// The list holds, for each particle i, every particle j (or periodic image of j) with
/// \f$ r_{ij} < 2\max(h_i, h_j) \f$.  That one symmetric list serves all the sums of the
/// toolkit: the gather form \f$ W(r_{ij}, h_i) \f$ (Watkins et al. 1996 eq A1), the
/// pair-averaged form \f$ W(r_{ij}, \bar h_{ij}) \f$ (Selhammar 1997 eqs 1, 5) and the
/// scatter form \f$ W(r_{ij}, h_j) \f$.  Pairs are stored once per side, so every pass is a
/// gather loop over i: each particle writes only its own sums, the passes run in parallel
/// without locks, and the result does not depend on the number of threads.
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
/// **From step to step** a particle keeps its candidates (every particle within a margin
/// beyond 2h, found by the grid) for as long as its neighbourhood has moved little relative to
/// it; only the particles where the flow shears or compresses are searched again.  See
/// try_reuse below and LocalMotion (local_motion.hpp); docs/design.md has the measurements.

#include "sph/box.hpp"
#include "sph/cell_grid.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/kernel.hpp"
#include "sph/local_motion.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <omp.h>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <array>
#include <limits>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sph {

/// One neighbour of a particle: its index and which periodic image of it.
struct Neighbour {
  std::uint32_t index;
  Image image;
};

namespace detail {

/// Append to `out` the entries k < n of (index, image) with r2[k] < limit2, in order, and
/// return how many; `farthest2` gets the largest r2 among them (0 if none).  When `wrapped`
/// is given, each image is translated to image - own + wrapped[index]: from the frame of the
/// unwrapped positions, in which the search keeps candidates, to the frame of the stored ones
/// (own = wrapped[i] for the particle whose pairs these are; see NeighbourSearch::try_reuse).
/// `out` must have room for n entries: entries past the kept ones may be overwritten.
///
/// The plain loop writes every entry and advances the end past the kept ones only (no
/// branch to mispredict), but still moves one entry per iteration.  With AVX-512 the entries
/// go eight at a time: a mask of the kept ones, compressed to the front of the register and
/// stored whole (compressing in the register, not into memory: on some processors the store
/// form is microcoded and slow).  `portable` forces the plain loop, so tests can compare both.
template <bool portable = false>
inline std::size_t keep_closer(const std::uint32_t* index, const Image* image, const double* r2, std::size_t n,
                               double limit2, const Image* wrapped, Image own, Neighbour* out, double& farthest2) {
  static_assert(sizeof(Neighbour) == 8, "a Neighbour must pack into one 64-bit lane");
  std::size_t end = 0, k = 0;
  double farthest = 0;
#if defined(__AVX512F__) && defined(__AVX512VL__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // (GCC 12, inside its own AVX-512 headers)
  if constexpr (!portable) {
    const __m512d limit = _mm512_set1_pd(limit2);
    const __m256i low = _mm256_set1_epi32(0x7f7f7f7f), high = _mm256_set1_epi32(static_cast<int>(0x80808080u));
    const __m256i own_image = _mm256_set1_epi32(static_cast<int>(own));
    __m512d far = _mm512_setzero_pd();
    for (; k + 8 <= n; k += 8) {
      const __m512d d = _mm512_loadu_pd(r2 + k);
      const __mmask8 kept = _mm512_cmp_pd_mask(d, limit, _CMP_LT_OQ);
      const __m256i j = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(index + k));
      __m256i img = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(image + k));
      if (wrapped) {
        // subtract_images(img, own), then add_images(., wrapped[j]), eight lanes at once.
        const __m256i diff = _mm256_xor_si256(
            _mm256_sub_epi32(_mm256_or_si256(img, high), _mm256_and_si256(own_image, low)),
            _mm256_andnot_si256(_mm256_xor_si256(img, own_image), high));
        const __m256i w = _mm256_i32gather_epi32(reinterpret_cast<const int*>(wrapped), j, 4);
        img = _mm256_xor_si256(_mm256_add_epi32(_mm256_and_si256(diff, low), _mm256_and_si256(w, low)),
                               _mm256_and_si256(_mm256_xor_si256(diff, w), high));
      }
      const __m512i pair = _mm512_or_si512(_mm512_cvtepu32_epi64(j), _mm512_slli_epi64(_mm512_cvtepu32_epi64(img), 32));
      _mm512_storeu_si512(out + end, _mm512_maskz_compress_epi64(kept, pair));
      far = _mm512_max_pd(far, _mm512_maskz_mov_pd(kept, d));
      end += static_cast<std::size_t>(__builtin_popcount(kept));
    }
    farthest = _mm512_reduce_max_pd(far);
  }
#pragma GCC diagnostic pop
#endif
  for (; k < n; ++k) {
    const Image img = wrapped ? add_images(subtract_images(image[k], own), wrapped[index[k]]) : image[k];
    out[end] = {index[k], img};
    farthest = std::max(farthest, r2[k] < limit2 ? r2[k] : 0.0);
    end += r2[k] < limit2;
  }
  farthest2 = farthest;
  return end;
}

}  // namespace detail

/// How smoothing lengths are chosen.
struct SmoothingLengthRule {
  enum class Mode { fixed, neighbour_number, density };
  Mode mode = Mode::neighbour_number;
  double neighbours = 64;  ///< target neighbour number N
  double tolerance = 0;    ///< neighbour_number: accepted deviation ±ΔN (absolute count)
  double density_tolerance = 1e-8;  ///< density: relative tolerance on h
  int max_iterations = 100;         ///< density: Newton iterations before giving up

  static SmoothingLengthRule fixed() { return {Mode::fixed}; }
  static SmoothingLengthRule neighbour_number(double n, double tolerance = 0) {
    return {Mode::neighbour_number, n, tolerance};
  }
  static SmoothingLengthRule from_density(double n) { return {Mode::density, n}; }
};

/// Positions one array per axis, with the box lengths the periodic images of a neighbour list
/// refer to: what a pass's SIMD loop over pairs reads (one lane per pair).  A plain view
/// (pointers and numbers), to be copied into a local before such a loop, so the compiler keeps
/// it in registers.  PositionArrays owns the arrays.
template <int D>
struct PositionView {
  std::array<const double*, D> x;  ///< x[a][i]: coordinate a of particle i
  std::array<double, D> period;    ///< box length on periodic axes, 0 on open ones

  /// The view of arrays x[a] with the periodic images of `box`.
  static PositionView of(const std::array<const double*, D>& x, const Box<D>& box) {
    PositionView v{x, {}};
    for (int a = 0; a < D; ++a) v.period[a] = box.periodic[a] ? box.length(a) : 0.0;
    return v;
  }
  /// Component a of r_ij = x_i - x_j - (image offset), without a branch.
  double separation(int a, std::size_t i, const Neighbour& n) const {
    return x[a][i] - x[a][n.index] - image_shift(n.image, a) * period[a];
  }
  /// |r_ij|^2.
  double distance2(std::size_t i, const Neighbour& n) const {
    double r2 = 0;
#pragma GCC unroll 3
    for (int a = 0; a < D; ++a) {
      const double d = separation(a, i, n);
      r2 += d * d;
    }
    return r2;
  }
  /// |r_ij|.
  double distance(std::size_t i, const Neighbour& n) const { return std::sqrt(distance2(i, n)); }
};

/// The positions (or velocities) one array per axis, for PositionView.  In 1D a vector of
/// Vec<1> already is that array: nothing is copied, the view points at the original (which
/// must then outlive it).
template <int D>
class PositionArrays {
 public:
  void assign(const std::vector<Vec<D>>& values) {
    const std::size_t n = values.size();
    if constexpr (D == 1) {
      data_[0] = values.data()->data();
    } else {
      for (int a = 0; a < D; ++a) {
        copy_[a].resize(n);
        data_[a] = copy_[a].data();
      }
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
      for (std::size_t i = 0; i < n; ++i)
        for (int a = 0; a < D; ++a) copy_[a][i] = values[i][a];
    }
  }
  /// Component a of every particle.
  const double* axis(int a) const { return data_[a]; }
  PositionView<D> view(const Box<D>& box) const { return PositionView<D>::of(data_, box); }

 private:
  std::array<std::vector<double>, D> copy_;
  std::array<const double*, D> data_{};
};

/// The symmetric neighbour list: for each particle, its neighbours one after another.  The
/// entries live in the buffers of the NeighbourSearch that wrote the list (it keeps them
/// particle after particle, so a pass reads them in order): a list is valid until that
/// search's next update, and is used by reference, not copied.
template <int D>
class NeighbourList {
 public:
  /// The neighbours of particle i.
  std::span<const Neighbour> of(std::size_t i) const { return {first_[i], count_[i]}; }
  /// r_ij = x_i - x_j - (image offset): the separation from neighbour n of particle i.
  Vec<D> separation(const std::vector<Vec<D>>& x, std::size_t i, const Neighbour& n) const {
    Vec<D> r = x[i] - x[n.index];
    if (n.image != 0) r -= image_offset<D>(n.image, box_);
    return r;
  }
  std::size_t particles() const { return first_.size(); }
  /// Total number of (i, j) entries: every interacting pair counts twice.
  std::size_t entries() const { return entries_; }
  /// The box the periodic images refer to.
  const Box<D>& box() const { return box_; }

 private:
  template <int, class>
  friend class NeighbourSearch;
  std::vector<const Neighbour*> first_;
  std::vector<std::uint32_t> count_;
  std::size_t entries_ = 0;
  Box<D> box_;  // the box the images refer to
};

/// Throw sph::Error naming the first particle whose mass is not positive and finite.  A zero or
/// negative mass would not stop the sums: it would silently lower the neighbours' densities (and
/// make the density rule for h chase a negative target), so the passes that use masses check.
template <int D>
void require_positive_masses(const Particles<D>& p, const char* pass) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!(std::isfinite(p.mass[i]) && p.mass[i] > 0)) {
      throw Error(std::string(pass) + ": particle " + std::to_string(i) + " at " + to_string<D>(p.position[i]) +
                  " has mass " + std::to_string(p.mass[i]) + " (must be positive and finite)");
    }
  }
}

/// Updates smoothing lengths by a rule and builds the neighbour list (the first pass of every
/// step).  Keep one instance per scene: it reuses its buffers from step to step.
template <int D, class K = Kernel<D>>
class NeighbourSearch {
 public:
  /// Update p.smoothing_length and p.neighbour_count by `rule`, then rebuild the list.
  /// Positions on periodic axes must lie in the box (the integrator wraps them).
  void update(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule) {
    const std::size_t n = p.size();
    require(n > 0, "neighbour search: no particles");
    require(n < (std::size_t{1} << 31), "neighbour search: too many particles");
    validate_rule(rule);
    if (rule.mode == SmoothingLengthRule::Mode::density) require_positive_masses(p, "smoothing length from density");
    // A shell count is remembered only for the set and the rule that forced it.
    if (shell_count_.size() != n || rule.neighbours != shell_rule_.neighbours || rule.tolerance != shell_rule_.tolerance) {
      shell_count_.assign(n, -1);
      shell_rule_ = rule;
    }
    if (try_reuse(p, box, rule)) return;
    full_search(p, box, rule);
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

 private:
  // The full search: grid, candidates within (1 + search_margin) 2h of every particle, h by the
  // rule, the list.  It also starts the frame in which later updates reuse the candidates.
  void full_search(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule) {
    const std::size_t n = p.size();
    initial_guess(p, box, rule);
    // Blocks of a few thousand particles, handed to the threads as they come free: the work is
    // not even along the particles (the gas that moves needs more), and a fixed number of
    // blocks, whatever the thread count, keeps every result the same for any thread count.
    const std::size_t count = n < parallel_threshold ? 1 : std::clamp<std::size_t>(n / block_size, 1, 256);
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

  // Unwrapped positions and the epoch start at the stored positions: no particle has wrapped.
  void start_frame(const Particles<D>& p) {
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

  // Search the grid for every particle flagged in search_again_ (from its present h), replacing
  // its candidates; count the search.
  void search_flagged(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule) {
    grid_.build(p.position, box, cell_size(p.smoothing_length));
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
  void finish_list(const Particles<D>& p, const Box<D>& box, Kept kept, const std::vector<double>* h_floor = nullptr) {
    const PositionView<D> unwrapped = unwrapped_view();
#pragma omp parallel for schedule(dynamic, 1) if (blocks_.size() > 1)
    for (std::size_t t = 0; t < blocks_.size(); ++t) {
      Block& block = blocks_[t];
      if (kept == Kept::none) block.kept.clear(block.end - block.begin);
      if (kept != Kept::all) {
        // (the pairs of a particle searched again go after the others: the list finds each
        // particle's pairs wherever they are)
        for (std::size_t i = block.begin; i < block.end; ++i) {
          if (kept == Kept::none || search_again_[i]) keep_own(block, i, refreshed(block, i, unwrapped), p.smoothing_length[i]);
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
  // Candidates one array per field, so the refresh of their distances runs in SIMD registers.
  // The arrays only grow; `count` entries are in use.  What a particle keeps from step to step
  // is who its candidates are (index and image: StoredCandidates); their squared distances are
  // worked out afresh each step into a scratch array, and only a search's result carries them
  // (Candidates).
  template <bool with_distance>
  struct CandidateArrays {
    std::vector<std::uint32_t> index;
    std::vector<Image> image;
    std::vector<double> r2;  // (empty without distances)
    std::size_t count = 0;
    std::size_t size() const { return count; }
    void clear() { count = 0; }
    // Room for `more` entries past the used ones.
    void reserve_more(std::size_t more) {
      if (count + more <= index.size()) return;
      const std::size_t n = std::max(count + more, 2 * index.size());
      index.resize(n);
      image.resize(n);
      if constexpr (with_distance) r2.resize(n);
    }
    // Append entries first..last of `other` (who they are; distances only between two
    // arrays that both have them).
    template <bool other_distance>
    void append(const CandidateArrays<other_distance>& other, std::size_t first, std::size_t last) {
      const std::size_t m = last - first;
      reserve_more(m);
      const auto from = static_cast<std::ptrdiff_t>(first), to = static_cast<std::ptrdiff_t>(count);
      std::copy_n(other.index.begin() + from, m, index.begin() + to);
      std::copy_n(other.image.begin() + from, m, image.begin() + to);
      if constexpr (with_distance && other_distance) std::copy_n(other.r2.begin() + from, m, r2.begin() + to);
      count += m;
    }
  };
  using Candidates = CandidateArrays<true>;
  using StoredCandidates = CandidateArrays<false>;
  // The candidates of one particle, with their squared distances.
  struct CandidateSpan {
    const std::uint32_t* index;
    const Image* image;
    double* r2;
    std::size_t size;
  };
  static CandidateSpan span_of(Candidates& c, std::size_t first, std::size_t last) {
    return {c.index.data() + first, c.image.data() + first, c.r2.data() + first, last - first};
  }
  // The pairs (r_ij < 2h_i) of a range of particles: those of the k-th particle are entries
  // first[k] .. first[k] + count[k].  Written particle after particle; the array only grows,
  // `used` entries are in use.  (Their distances are not kept: writing and reading them back
  // cost more memory traffic than measuring the few that are needed again, find_reverse.)
  struct KeptPairs {
    std::vector<std::size_t> first;
    std::vector<std::uint32_t> count;
    std::vector<Neighbour> pairs;
    std::size_t used = 0;
    void clear(std::size_t particles) {
      first.assign(particles, 0);
      count.assign(particles, 0);
      used = 0;
    }
    void reserve_more(std::size_t more) {
      if (used + more <= pairs.size()) return;
      pairs.resize(std::max(used + more, 2 * pairs.size()));
    }
  };
  // A unit of work for one thread: a contiguous range of particles, its candidates and the pairs it
  // keeps.  Particle i's candidates are entries first_[i]..last_[i] of `candidates`; a particle
  // searched again appends its new ones, and the block is compacted when more than half its
  // entries are stale.  The kept pairs (r_ij < 2h_i) go to `kept`, particle after particle;
  // one-sided pairs (r_ij < 2h_i but >= 2h_j) are recorded in `reverse` so that j gets them too.
  struct Block {
    std::size_t begin = 0, end = 0;
    StoredCandidates candidates, spare;  // (spare: the buffer a compaction copies into)
    std::size_t live = 0;                // entries some particle still refers to
    Candidates found;                    // the candidates of the particle being searched
    std::vector<double> r2;              // the distances of the particle being settled (or checked)
    KeptPairs kept;
    std::vector<std::pair<std::uint32_t, Neighbour>> reverse;  // (j, entry for j)
    // The candidates of particle i with room for their distances.
    CandidateSpan span(std::size_t first, std::size_t last) {
      if (r2.size() < last - first) r2.resize(2 * (last - first));
      return {candidates.index.data() + first, candidates.image.data() + first, r2.data(), last - first};
    }
  };

  static void validate_rule(const SmoothingLengthRule& rule) {
    if (rule.mode == SmoothingLengthRule::Mode::fixed) return;
    require(std::isfinite(rule.neighbours) && rule.neighbours >= 1,
            "smoothing length: the target neighbour number must be at least 1 (got " +
                std::to_string(rule.neighbours) + ")");
    require(rule.tolerance >= 0 && rule.tolerance < rule.neighbours,
            "smoothing length: the neighbour tolerance must lie in [0, N)");
  }

  // Particles without a smoothing length get one from the mean volume per particle.
  void initial_guess(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule) {
    const std::size_t n = p.size();
    bool all_set = true;
    for (std::size_t i = 0; i < n; ++i) {
      const double h = p.smoothing_length[i];
      if (rule.mode == SmoothingLengthRule::Mode::fixed && !(std::isfinite(h) && h > 0)) {
        throw Error("particle " + std::to_string(i) + " has smoothing length " + std::to_string(h) +
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
      throw Error("neighbour search: all " + std::to_string(n) + " particles are at one point, " + to_string<D>(lo) +
                  ", so nothing sets a length to start h from (give the particles distinct positions, or h)");
    }
    const double per_particle = volume / static_cast<double>(n);
    const double neighbours = std::max(rule.neighbours, 1.0);
    const double ball = spread == 1 ? unit_ball_volume<1>() : spread == 2 ? unit_ball_volume<2>() : unit_ball_volume<3>();
    const double ratio = neighbours * per_particle / ball;
    const double guess = 0.5 * (spread == D ? root<D>(ratio) : std::pow(ratio, 1.0 / spread));
    for (auto& h : p.smoothing_length) {
      if (!(std::isfinite(h) && h > 0)) h = guess;
    }
  }

  double cell_size(const std::vector<double>& h) const {
    std::vector<double> sample;
    const std::size_t step = std::max<std::size_t>(1, h.size() / 1024);
    for (std::size_t i = 0; i < h.size(); i += step) sample.push_back(h[i]);
    std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
    const double median = sample[sample.size() / 2];
    // A cell of half the search radius visits 4-5 cells per axis but a smaller volume than
    // cells of the full radius (2.5^D vs 3^D times the radius^D); in 1D the full radius wins.
    const double fraction = D == 1 ? 1.0 : 0.5;
    return fraction * K::support * median * (1.0 + search_margin);
  }

  // --- Reusing candidates ---------------------------------------------------------------
  //
  // A search keeps, for particle i, every j within R_i = (1 + margin) 2h_i: the candidates are
  // complete within the "reach" R_i of the positions at that time, the epoch.  Let d_j be the
  // displacement of j since the epoch.  A j that is not a candidate was at least R_i from i
  // then, so now it is at least R_i - |d_i - d_j| away.  LocalMotion bounds |d_i - d_j| over
  // the particles now near i by b_i, from the displacements in the cells around i; so the
  // candidates are still complete within covered_i = R_i - b_i, and while 2h_i fits in it a
  // step needs only their new distances -- no grid, no search.  The bound looks at
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
  bool try_reuse(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule) {
    const std::size_t n = p.size();
    if (!reusable_ || n != first_.size() || rule.mode != built_mode_ || !same_box(box, built_box_)) return false;
    double largest_h = 0;
    if (!advance_frame(p, box, largest_h)) return false;
    // How far each particle's neighbourhood has moved relative to it.
    std::array<const double*, D> moved;
    for (int a = 0; a < D; ++a) moved[a] = moved_[a].data();
    motion_.build(p.position, box, moved, K::support * largest_h * (1.0 + search_margin));
    const double cell = motion_.cell_size();
    covered_.resize(n);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) covered_[i] = std::min(reach_[i], cell) - motion_.bound(i);
    // Settle every particle from its candidates; flag the ones to search again.
    const PositionView<D> unwrapped = unwrapped_view();
    search_again_.resize(n);
    int failed = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(| : failed) if (blocks_.size() > 1)
    for (std::size_t t = 0; t < blocks_.size(); ++t) {
      Block& block = blocks_[t];
      block.kept.clear(block.end - block.begin);
      for (std::size_t i = block.begin; i < block.end; ++i) {
        const bool settled = settle_from_candidates(p, rule, block, i, covered_[i], unwrapped);
        failed |= !settled;
        search_again_[i] = !settled || covered_[i] < K::support * p.smoothing_length[i] * (1.0 + 0.5 * search_margin);
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
    motion_.neighbourhood_min(p.smoothing_length.data(), h_floor_);
    finish_list(p, box, failed ? Kept::all_but_searched : Kept::all, &h_floor_);
    return true;
  }

  // Follow each particle since the last update by the nearest image (no particle crosses a
  // quarter of a periodic box in one step: if one seems to, return false for a full search),
  // accumulate its unwrapped position and its displacement since the epoch, and note how many
  // periods it lies from its stored, wrapped position.  Also returns the largest h.
  bool advance_frame(const Particles<D>& p, const Box<D>& box, double& largest_h) {
    const std::size_t n = p.size();
    for (int a = 0; a < D; ++a) moved_[a].resize(n);
    int bad = 0, any = 0;
    double h_max = 0;
#pragma omp parallel for schedule(static) reduction(| : bad, any) reduction(max : h_max) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec<D> step = box.separation(p.position[i], previous_position_[i]);
      previous_position_[i] = p.position[i];
      std::array<int, D> periods{};
      for (int a = 0; a < D; ++a) {
        if (box.periodic[a] && std::abs(step[a]) > 0.25 * box.length(a)) bad = 1;
        double& u = unwrapped_[a][i];
        u += step[a];
        moved_[a][i] = u - epoch_[a][i];
        if (box.periodic[a]) periods[a] = static_cast<int>(std::floor((u - p.position[i][a]) / box.length(a) + 0.5));
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
  bool settle_from_candidates(Particles<D>& p, const SmoothingLengthRule& rule, Block& block, std::size_t i,
                              double covered, const PositionView<D>& unwrapped) {
    const CandidateSpan found = refreshed(block, i, unwrapped);
    double& h = p.smoothing_length[i];
    bool settled = true;
    if (rule.mode == SmoothingLengthRule::Mode::neighbour_number) settled = settle_by_count(rule, covered, found, h, shell_count_[i]);
    if (rule.mode == SmoothingLengthRule::Mode::density) settled = settle_by_density(p, rule, i, covered, found, h);
    if (!settled || K::support * h > covered) return false;
    p.neighbour_count[i] = keep_own(block, i, found, h);
    return true;
  }

  // The unwrapped positions, in whose frame the candidates' images hold.
  PositionView<D> unwrapped_view() const {
    std::array<const double*, D> axes;
    for (int a = 0; a < D; ++a) axes[a] = unwrapped_[a].data();
    return PositionView<D>::of(axes, built_box_);
  }

  // Particle i's candidates with their present distances (in the frame of the unwrapped positions).
  CandidateSpan refreshed(Block& block, std::size_t i, const PositionView<D>& unwrapped) const {
    const CandidateSpan found = block.span(first_[i], last_[i]);
    const PositionView<D> u = unwrapped;  // a private copy: its pointers stay in registers
#pragma omp simd simdlen(8) if(simd : D > 1)
    for (std::size_t k = 0; k < found.size; ++k) found.r2[k] = u.distance2(i, {found.index[k], found.image[k]});
    return found;
  }

  static bool same_box(const Box<D>& a, const Box<D>& b) {
    return a.lower == b.lower && a.upper == b.upper && a.periodic == b.periodic;
  }

  // Search the grid for the flagged particles of one block: h by the rule, the candidates
  // (appended, their images in the frame of the unwrapped positions) and the radius searched.
  long search_block(Particles<D>& p, const SmoothingLengthRule& rule, Block& block) {
    long searched = 0;
    Candidates& found = block.found;
    for (std::size_t i = block.begin; i < block.end; ++i) {
      if (!search_again_[i]) continue;
      reach_[i] = settle_particle(p, rule, i, found);
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

  // Copy the candidates still referred to into the spare buffer, which becomes the block's.
  void compact(Block& block) {
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
  void to_unwrapped_frame(Candidates& found, std::size_t i) const {
    for (std::size_t k = 0; k < found.size(); ++k)
      found.image[k] = subtract_images(add_images(found.image[k], wrapped_[i]), wrapped_[found.index[k]]);
  }

  // Gather the candidates of particle i within radius (the particle itself excluded).
  // The grid hands over blocks of scanned particles with their distances; the ones within the
  // radius are kept by writing every one and advancing the end only past the hits (about one
  // in three: a branch would be mispredicted too often).
  void gather(const Particles<D>& p, std::size_t i, double radius, Candidates& found) const {
    found.clear();
    const double radius2 = radius * radius;
    const auto self = static_cast<std::uint32_t>(i);
    grid_.for_each_block_within(p.position[i], radius,
                                [&](const std::uint32_t* index, const double* r2, std::size_t count, Image image) {
                                  found.reserve_more(count);
                                  std::size_t end = found.count;
                                  for (std::size_t k = 0; k < count; ++k) {
                                    found.index[end] = index[k];
                                    found.image[end] = image;
                                    found.r2[end] = r2[k];
                                    end += (r2[k] < radius2) & !(index[k] == self && image == 0);
                                  }
                                  found.count = end;
                                });
  }

  // Choose h_i by the rule, growing the search radius until the candidates suffice; returns
  // the radius searched.
  double settle_particle(Particles<D>& p, const SmoothingLengthRule& rule, std::size_t i, Candidates& all) {
    double& h = p.smoothing_length[i];
    double radius = K::support * h * (1.0 + search_margin);
    const double grid_extent = std::max(grid_.extent(), K::support * h);
    for (int attempt = 0; attempt < 64; ++attempt) {
      gather(p, i, radius, all);
      const CandidateSpan found = span_of(all, 0, all.size());
      const bool settled = [&] {
        switch (rule.mode) {
          case SmoothingLengthRule::Mode::fixed: return true;
          case SmoothingLengthRule::Mode::neighbour_number: return settle_by_count(rule, radius, found, h, shell_count_[i]);
          case SmoothingLengthRule::Mode::density: return settle_by_density(p, rule, i, radius, found, h);
        }
        return true;
      }();
      if (settled) {
        p.neighbour_count[i] = count_within(found, h);
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
        throw Error("particle " + std::to_string(i) + ": only " + std::to_string(found.size) +
                    " other particles (periodic images included) within " + std::to_string(radius) +
                    ", cannot reach " + std::to_string(rule.neighbours) + " neighbours");
      }
      radius *= 1.5;
    }
    throw Error("particle " + std::to_string(i) + " at " + to_string<D>(p.position[i]) +
                ": no smoothing length found (search radius grew to " + std::to_string(radius) + ")");
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

  // (2h)^2, written once: the count, the kept pairs and the one-sided test must agree to the
  // last bit on which side of 2h a distance lies, and it grows with h in floating point too.
  static double support2(double h) { return (K::support * h) * (K::support * h); }

  static int count_within(const CandidateSpan& found, double h) {
    const double r2max = support2(h);
    const double* r2 = found.r2;  // a local pointer: the loads are then contiguous, not gathered
    const std::size_t size = found.size;
    int count = 0;
#pragma omp simd reduction(+ : count)
    for (std::size_t k = 0; k < size; ++k) count += r2[k] < r2max;
    return count;
  }

  // Neighbour-number rule: keep h while the count is within tolerance (or is the count a shell
  // forced last time, `shell`), else put 2h half-way between the N-th and (N+1)-th nearest
  // candidate.  False when the candidates do not reach that far (the caller widens the search).
  static bool settle_by_count(const SmoothingLengthRule& rule, double radius, const CandidateSpan& found, double& h,
                              int& shell) {
    const int count = count_within(found, h);
    const bool accepted = std::abs(count - rule.neighbours) <= rule.tolerance || count == shell;
    if (accepted && K::support * h <= radius) return true;
    const auto n = static_cast<std::size_t>(std::llround(rule.neighbours));
    if (found.size < n + 1) return false;
    // The N-th and (N+1)-th smallest distances.  `count` of them lie inside the present 2h, so
    // both are found among the distances on one side of 2h only (typically a third of the
    // candidates): select from a copy of that side (the candidates keep their order).
    thread_local std::vector<double> side;
    const double reach2 = support2(h);
    const auto inside = static_cast<std::size_t>(count);
    double rn2, rn12;  // the two squared distances
    if (inside == n) {
      // The N-th is the farthest inside, the (N+1)-th the nearest outside.
      rn2 = 0;
      rn12 = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < found.size; ++k) {
        const double r2 = found.r2[k];
        if (r2 < reach2) rn2 = std::max(rn2, r2);
        else rn12 = std::min(rn12, r2);
      }
    } else {
      const bool below = inside > n;  // both inside 2h, at ranks n and n + 1 there
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
    return settle_on_shell(rule.neighbours, rn, tie, radius, found, h, shell);
  }

  // The N-th and (N+1)-th neighbours lie on one shell (equal distances, as on a lattice, or
  // coincident particles at r = 0).  No radius gives exactly N; put 2h in the gap just inside or
  // just outside the shell, whichever count is nearer N (outside on a tie, and always outside a
  // shell at r = 0, so h > 0), and record that count in `count`.  False when the candidates end
  // at the shell (widen the search).
  static bool settle_on_shell(double target, double shell, double tie, double radius, const CandidateSpan& found,
                              double& h, int& count) {
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

  // Density rule: Newton iteration on f(h) = rho(h) h^D - N m / (V_D 2^D) = 0, with the gather
  // density rho(h) = sum_j m_j W(r_ij, h) + m_i W(0, h).  False when 2h leaves the candidates.
  static bool settle_by_density(const Particles<D>& p, const SmoothingLengthRule& rule, std::size_t i,
                                double radius, const CandidateSpan& found, double& h) {
    const double target = rule.neighbours * p.mass[i] / (unit_ball_volume<D>() * power<D>(K::support));
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
    throw Error("particle " + std::to_string(i) + " at " + to_string<D>(p.position[i]) +
                ": smoothing length from density did not converge in " +
                std::to_string(rule.max_iterations) + " iterations (last h = " + std::to_string(h_new) + ")");
  }

  // Keep particle i's pairs with r_ij < 2h_i (appended to `kept`, images in the frame of the
  // stored positions); returns how many.
  int keep_own(Block& block, std::size_t i, const CandidateSpan& found, double h) {
    KeptPairs& kept = block.kept;
    kept.reserve_more(found.size);
    const std::size_t count =
        detail::keep_closer(found.index, found.image, found.r2, found.size, support2(h), any_wrapped_ ? wrapped_.data() : nullptr,
                            wrapped_[i], kept.pairs.data() + kept.used, farthest2_[i]);
    kept.first[i - block.begin] = kept.used;
    kept.count[i - block.begin] = static_cast<std::uint32_t>(count);
    kept.used += count;
    return static_cast<int>(count);
  }

  // With every h final: the kept pairs (i, j) with r_ij >= 2h_j, which j's own candidates do
  // not give it, are handed to j.
  //
  // A particle whose farthest kept pair is closer than 2h_j for the smallest h_j near it has
  // none; in gas at rest or in uniform flow that is nearly every particle.  When `h_floor` is
  // given (the smallest h near each particle, LocalMotion::neighbourhood_min, valid for the
  // particles not searched again), those are passed over without reading their pairs; the
  // others first compare each 2h_j with their farthest pair.  The rest
  // measure their pairs' distances again: between the same unwrapped positions, with the same
  // images (translated back from the frame of the stored positions), by the same arithmetic as
  // the refresh, so that each distance is the one that kept the pair, to the bit.  Few
  // particles have any one-sided pair (a vectorised count finds them).
  void find_reverse(const Particles<D>& p, Block& block, const PositionView<D>& unwrapped,
                    const std::vector<double>* h_floor) {
    block.reverse.clear();
    const double* h = p.smoothing_length.data();
    const Neighbour* kept = block.kept.pairs.data();
    const PositionView<D> u = unwrapped;  // a private copy: its pointers stay in registers
    const Image* wrapped = any_wrapped_ ? wrapped_.data() : nullptr;
    for (std::size_t i = block.begin; i < block.end; ++i) {
      if (h_floor && !search_again_[i] && farthest2_[i] < support2((*h_floor)[i])) continue;
      const std::size_t first = block.kept.first[i - block.begin], count = block.kept.count[i - block.begin];
      const Neighbour* pairs = kept + first;
      // Only a neighbour whose 2h_j does not reach past i's farthest pair can make a one-sided
      // pair (a load of h_j each, before any position).
      const double farthest2 = farthest2_[i];
      int possible = 0;
#pragma omp simd reduction(+ : possible)
      for (std::size_t e = 0; e < count; ++e) possible += support2(h[pairs[e].index]) <= farthest2;
      if (possible == 0) continue;
      if (block.r2.size() < count) block.r2.resize(2 * count);
      double* r2 = block.r2.data();
      const Image own = wrapped_[i];
#pragma omp simd simdlen(8) if(simd : D > 1)
      for (std::size_t e = 0; e < count; ++e) {
        const Image image = wrapped ? subtract_images(add_images(pairs[e].image, own), wrapped[pairs[e].index]) : pairs[e].image;
        r2[e] = u.distance2(i, {pairs[e].index, image});
      }
      int one_sided = 0;
#pragma omp simd reduction(+ : one_sided)
      for (std::size_t e = 0; e < count; ++e) one_sided += r2[e] >= support2(h[pairs[e].index]);
      if (one_sided == 0) continue;
      for (std::size_t e = 0; e < count; ++e) {
        if (r2[e] >= support2(h[pairs[e].index]))
          block.reverse.push_back({pairs[e].index, {static_cast<std::uint32_t>(i), mirror_image<D>(pairs[e].image)}});
      }
    }
  }

  // A particle with no neighbour at all cannot be part of a fluid: stop and name it.
  void require_neighbours(const Particles<D>& p) const {
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (list_.of(i).empty()) {
        throw Error("particle " + std::to_string(i) + " at " + to_string<D>(p.position[i]) +
                    " has no neighbours within 2h = " + std::to_string(K::support * p.smoothing_length[i]));
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
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : entries) reduction(min : lonely) if (blocks_.size() > 1)
    for (std::size_t t = 0; t < blocks_.size(); ++t) {
      const Block& b = blocks_[t];
      for (std::size_t i = b.begin; i < b.end; ++i) {
        const std::size_t first = b.kept.first[i - b.begin], count = b.kept.count[i - b.begin];
        list_.first_[i] = b.kept.pairs.data() + first;
        list_.count_[i] = static_cast<std::uint32_t>(count);
        entries += count;
        if (count == 0) lonely = std::min(lonely, i);
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
      std::size_t side_size = 0;
      for (std::size_t j = 0; j < n; ++j) {
        if (received[j + 1] > 0) side_size += list_.count_[j] + received[j + 1];
      }
      side_.resize(side_size);
      // Each receiving particle's own pairs first, then room for the ones it receives.
      std::size_t at = 0;
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t extra = received[j + 1];
        if (extra == 0) continue;
        std::copy_n(list_.first_[j], list_.count_[j], side_.data() + at);
        list_.first_[j] = side_.data() + at;
        received[j + 1] = at + list_.count_[j];  // where the next received pair goes
        list_.count_[j] += static_cast<std::uint32_t>(extra);
        at += list_.count_[j];
      }
      for (const auto& b : blocks_)
        for (const auto& r : b.reverse) side_[received[r.first + 1]++] = r.second;
    }
    list_.entries_ = entries + handed;
    list_.box_ = box;
    if (lonely < n) require_neighbours(p);  // (it may have received pairs since)
  }

  static constexpr std::size_t block_size = 2048;  // particles per block (about)
  CellGrid<D> grid_;
  std::vector<Block> blocks_;
  NeighbourList<D> list_;
  // Per particle: its candidates (entries first_..last_ of its block's) and the radius within
  // which they are complete at the epoch (reach_); this update's covered radius (see try_reuse)
  // and whether it is searched again.
  std::vector<std::size_t> first_, last_;
  std::vector<double> reach_, covered_;
  std::vector<std::uint8_t> search_again_;
  // The frame the candidates live in, since the last full search.
  bool reusable_ = false;
  Box<D> built_box_;
  SmoothingLengthRule::Mode built_mode_ = SmoothingLengthRule::Mode::fixed;
  std::vector<Vec<D>> previous_position_;         // positions at the last update
  std::array<std::vector<double>, D> unwrapped_;  // position at the full search + displacements since
  std::array<std::vector<double>, D> epoch_;      // unwrapped position at the start of the epoch
  std::array<std::vector<double>, D> moved_;      // displacement since the epoch
  std::vector<Image> wrapped_;  // periods between unwrapped and stored position, packed like an image
  bool any_wrapped_ = false;
  LocalMotion<D> motion_;
  std::vector<double> h_floor_;    // the smallest h near each particle (find_reverse)
  std::vector<double> farthest2_;  // the largest r_ij^2 among each particle's kept pairs
  long searches_ = 0, full_searches_ = 0, reuses_ = 0, particle_searches_ = 0;
  std::vector<std::size_t> received_;  // assemble_list: one-sided pairs per receiving particle
  std::vector<Neighbour> side_;  // the pairs of particles that receive one-sided ones
  // Neighbour-number rule: the count a lattice shell forced on each particle (-1: none), and
  // the rule it was forced under.
  std::vector<int> shell_count_;
  SmoothingLengthRule shell_rule_;
};

}  // namespace sph
