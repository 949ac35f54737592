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

#include "sph/box.hpp"
#include "sph/cell_grid.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/kernel.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <omp.h>

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

/// The symmetric neighbour list in compressed-row form.
template <int D>
class NeighbourList {
 public:
  /// The neighbours of particle i.
  std::span<const Neighbour> of(std::size_t i) const {
    return {entries_.data() + offset_[i], entries_.data() + offset_[i + 1]};
  }
  /// r_ij = x_i - x_j - (image offset): the separation from neighbour n of particle i.
  Vec<D> separation(const std::vector<Vec<D>>& x, std::size_t i, const Neighbour& n) const {
    Vec<D> r = x[i] - x[n.index];
    if (n.image != 0) r -= image_offset<D>(n.image, box_);
    return r;
  }
  std::size_t particles() const { return offset_.empty() ? 0 : offset_.size() - 1; }
  /// Total number of (i, j) entries: every interacting pair counts twice.
  std::size_t entries() const { return entries_.size(); }
  /// The box the periodic images refer to.
  const Box<D>& box() const { return box_; }

 private:
  template <int, class>
  friend class NeighbourSearch;
  std::vector<std::size_t> offset_;
  std::vector<Neighbour> entries_;
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
    if (try_reuse(p, box, rule)) {
      ++reuses_;
      return;
    }
    full_search(p, box, rule);
    ++searches_;
  }

  /// Make the next update a full search (the reuse test covers motion, not particles moved or
  /// replaced by hand; it is safe to call this after such a change).
  void forget_candidates() {
    reusable_ = false;
    shell_count_.clear();
  }

  /// How many updates searched the grid, and how many reused the candidates of the last search.
  long searches() const { return searches_; }
  long reuses() const { return reuses_; }

 private:
  // The full search: grid, candidates within (1 + search_margin) 2h of every particle, h by the
  // rule, the list.  It also records what a later update needs to reuse the candidates.
  void full_search(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule) {
    const std::size_t n = p.size();
    initial_guess(p, box, rule);
    grid_.build(p.position, box, cell_size(p.smoothing_length));
    const int threads = n < parallel_threshold ? 1 : omp_get_max_threads();
    blocks_.resize(static_cast<std::size_t>(threads));
    std::string error;
    std::size_t team = 1;
#pragma omp parallel num_threads(threads)
    {
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      const std::size_t nt = static_cast<std::size_t>(omp_get_num_threads());
      if (t == 0) team = nt;
      Block& block = blocks_[t];
      block.begin = n * t / nt;
      block.end = n * (t + 1) / nt;
      try {
        find_candidates(p, rule, block);
      } catch (const Error& e) {
#pragma omp critical
        if (error.empty()) error = e.what();
      }
#pragma omp barrier
      if (error.empty()) keep_neighbours(p, block);
    }
    if (!error.empty()) throw Error(error);
    blocks_.resize(team);  // the runtime may have given fewer threads than asked for
    assemble_list(box);
    require_neighbours(p);
    built_position_ = p.position;
    previous_position_ = p.position;
    for (int a = 0; a < D; ++a) {
      unwrapped_[a].resize(n);
      for (std::size_t i = 0; i < n; ++i) unwrapped_[a][i] = p.position[i][a];
    }
    wrapped_.assign(n, 0);
    built_box_ = box;
    built_mode_ = rule.mode;
    reusable_ = true;
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
  // The arrays only grow; `count` entries are in use.
  struct Candidates {
    std::vector<std::uint32_t> index;
    std::vector<Image> image;
    std::vector<double> r2;
    std::size_t count = 0;
    std::size_t size() const { return count; }
    void clear() { count = 0; }
    // Room for `more` entries past the used ones.
    void reserve_more(std::size_t more) {
      if (count + more <= index.size()) return;
      const std::size_t n = std::max(count + more, 2 * index.size());
      index.resize(n);
      image.resize(n);
      r2.resize(n);
    }
    void append(const Candidates& other) {
      reserve_more(other.count);
      std::copy_n(other.index.begin(), other.count, index.begin() + static_cast<std::ptrdiff_t>(count));
      std::copy_n(other.image.begin(), other.count, image.begin() + static_cast<std::ptrdiff_t>(count));
      std::copy_n(other.r2.begin(), other.count, r2.begin() + static_cast<std::ptrdiff_t>(count));
      count += other.count;
    }
  };
  // The candidates of one particle.
  struct CandidateSpan {
    const std::uint32_t* index;
    const Image* image;
    double* r2;
    std::size_t size;
  };
  static CandidateSpan span_of(Candidates& c, std::size_t first, std::size_t last) {
    return {c.index.data() + first, c.image.data() + first, c.r2.data() + first, last - first};
  }
  // The work of one thread: a contiguous range of particles, its candidates and the pairs it
  // keeps.  One-sided pairs (r_ij < 2h_i but >= 2h_j) are recorded so j gets them too.
  struct Block {
    std::size_t begin = 0, end = 0;
    std::vector<std::size_t> candidate_start;
    Candidates candidates;
    std::vector<double> reach;  // the radius within which each particle's candidates are complete
    std::vector<std::size_t> kept_start;
    std::vector<Neighbour> kept;
    std::vector<std::pair<std::uint32_t, Neighbour>> reverse;  // (j, entry for j)
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
    Vec<D> lo = p.position[0], hi = p.position[0];
    for (const auto& x : p.position) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    double volume = 1.0;
    for (int a = 0; a < D; ++a) {
      const double extent = box.periodic[a] ? box.length(a) : hi[a] - lo[a];
      volume *= std::max(extent, 1e-300);
    }
    const double per_particle = volume / static_cast<double>(n);
    const double neighbours = std::max(rule.neighbours, 1.0);
    const double guess = 0.5 * root<D>(neighbours * per_particle / unit_ball_volume<D>());
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

  // --- Reusing the candidates of the last full search ------------------------------------
  //
  // A full search keeps, for each particle i, every j within R_i = (1 + margin) 2h_i.  Let d be
  // the largest distance any particle has moved since, measured from the mean displacement of
  // all of them (a common drift does not change any separation, since
  // |D_i - D_j| <= |D_i - c| + |D_j - c| for any c).  A pair that is now closer than 2h_i
  // was at most 2h_i + 2d apart then; so if 2h_i + 2d <= R_i for every i, the old candidates
  // still hold every neighbour, and a step needs only their new distances -- no grid, no
  // search.  The distances are taken between "unwrapped" positions (position at the search
  // plus the displacements of every update since, each by the nearest periodic image), in which the images recorded
  // at the search stay valid; a particle that has since crossed a periodic face gets its images
  // translated when the list is written.  When the test fails for any particle, or the set,
  // box or rule changed, the update falls back to a full search.  The outcome (and so every
  // result) is the same for any number of threads.
  bool try_reuse(Particles<D>& p, const Box<D>& box, const SmoothingLengthRule& rule) {
    const std::size_t n = p.size();
    if (!reusable_ || n != built_position_.size() || rule.mode != built_mode_ || !same_box(box, built_box_)) return false;
    // Displacements since the search, and the whole periods between unwrapped and stored positions.
    // Follow each particle since the last update by the nearest image (no particle crosses a
    // quarter of a periodic box in one step: if one seems to, search again), and accumulate its
    // unwrapped position; note how many periods it lies from its stored, wrapped position.
    Vec<D> mean = Vec<D>::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec<D> step = box.separation(p.position[i], previous_position_[i]);
      for (int a = 0; a < D; ++a) {
        if (box.periodic[a] && std::abs(step[a]) > 0.25 * box.length(a)) return false;
      }
      previous_position_[i] = p.position[i];
      std::array<int, D> periods{};
      for (int a = 0; a < D; ++a) {
        double& u = unwrapped_[a][i];
        u += step[a];
        mean[a] += u - built_position_[i][a];
        if (box.periodic[a]) periods[a] = static_cast<int>(std::lround((u - p.position[i][a]) / box.length(a)));
        if (std::abs(periods[a]) > 100) return false;  // (an image shift must fit in a byte)
      }
      wrapped_[i] = pack_image<D>(periods);
    }
    mean /= static_cast<double>(n);
    double moved2 = 0;
    for (std::size_t i = 0; i < n; ++i) {
      double d2 = 0;
      for (int a = 0; a < D; ++a) {
        const double d = unwrapped_[a][i] - built_position_[i][a] - mean[a];
        d2 += d * d;
      }
      moved2 = std::max(moved2, d2);
    }
    const double moved = std::sqrt(moved2);
    std::array<const double*, D> unwrapped_axes;
    for (int a = 0; a < D; ++a) unwrapped_axes[a] = unwrapped_[a].data();
    const PositionView<D> unwrapped = PositionView<D>::of(unwrapped_axes, built_box_);
    int failed = 0;
#pragma omp parallel num_threads(static_cast<int>(blocks_.size()))
    {
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      if (static_cast<std::size_t>(omp_get_num_threads()) != blocks_.size()) {
#pragma omp atomic write
        failed = 1;
      } else {
        // Every particle is settled, even after one has failed: the h a failed attempt leaves
        // behind is the start of the full search, and must not depend on the thread count.
        Block& block = blocks_[t];
        bool ok = true;
        for (std::size_t i = block.begin; i < block.end; ++i) ok = settle_from_candidates(p, rule, block, i, moved, unwrapped) && ok;
        if (!ok) {
#pragma omp atomic write
          failed = 1;
        }
      }
#pragma omp barrier
      if (!failed) keep_neighbours(p, blocks_[t], true);
    }
    if (failed) return false;
    assemble_list(box);
    require_neighbours(p);
    return true;
  }

  // Refresh particle i's candidate distances and settle its h within the radius they still
  // cover; false if that radius is not enough.
  // `unwrapped` views the unwrapped positions, in whose frame the images recorded at the search
  // still hold.
  bool settle_from_candidates(Particles<D>& p, const SmoothingLengthRule& rule, Block& block, std::size_t i,
                              double moved, const PositionView<D>& unwrapped) {
    const std::size_t first = block.candidate_start[i - block.begin], last = block.candidate_start[i - block.begin + 1];
    const CandidateSpan found = span_of(block.candidates, first, last);
    const PositionView<D> u = unwrapped;  // a private copy: its pointers stay in registers
#pragma omp simd simdlen(8) if(simd : D > 1)
    for (std::size_t k = 0; k < found.size; ++k) found.r2[k] = u.distance2(i, {found.index[k], found.image[k]});
    const double covered = block.reach[i - block.begin] - 2.0 * moved;
    double& h = p.smoothing_length[i];
    bool settled = true;
    if (rule.mode == SmoothingLengthRule::Mode::neighbour_number) settled = settle_by_count(rule, covered, found, h, shell_count_[i]);
    if (rule.mode == SmoothingLengthRule::Mode::density) settled = settle_by_density(p, rule, i, covered, found, h);
    if (!settled || K::support * h > covered) return false;
    p.neighbour_count[i] = count_within(found, K::support * h);
    return true;
  }

  static bool same_box(const Box<D>& a, const Box<D>& b) {
    return a.lower == b.lower && a.upper == b.upper && a.periodic == b.periodic;
  }

  // The image of candidate j of i in the frame of the stored (wrapped) positions.
  Image current_image(Image built, std::size_t i, std::size_t j) const {
    if ((wrapped_[i] | wrapped_[j]) == 0) return built;  // neither has crossed a periodic face
    std::array<int, D> shift{};
    for (int a = 0; a < D; ++a) shift[a] = image_shift(built, a) - image_shift(wrapped_[i], a) + image_shift(wrapped_[j], a);
    return pack_image<D>(shift);
  }

  // Phase 1 (per thread): gather candidates of each particle and settle its h.
  void find_candidates(Particles<D>& p, const SmoothingLengthRule& rule, Block& block) {
    block.candidate_start.clear();
    block.candidates.clear();
    block.reach.clear();
    Candidates found;
    for (std::size_t i = block.begin; i < block.end; ++i) {
      block.reach.push_back(settle_particle(p, rule, i, found));
      block.candidate_start.push_back(block.candidates.size());
      block.candidates.append(found);
    }
    block.candidate_start.push_back(block.candidates.size());
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
        p.neighbour_count[i] = count_within(found, K::support * h);
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

  static int count_within(const CandidateSpan& found, double radius) {
    const double r2max = radius * radius;
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
    const int count = count_within(found, K::support * h);
    const bool accepted = std::abs(count - rule.neighbours) <= rule.tolerance || count == shell;
    if (accepted && K::support * h <= radius) return true;
    const auto n = static_cast<std::size_t>(std::llround(rule.neighbours));
    if (found.size < n + 1) return false;
    // The N-th and (N+1)-th smallest distances.  `count` of them lie inside the present 2h, so
    // both are found among the distances on one side of 2h only (typically a third of the
    // candidates): select from a copy of that side (the candidates keep their order).
    thread_local std::vector<double> side;
    const double reach2 = K::support * h * K::support * h;
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

  // Phase 2 (per thread, all h final): keep pairs with r_ij < 2 max(h_i, h_j).  A candidate
  // list covers r < 2h_i; a pair with 2h_i <= r < 2h_j is found from j's side and handed to i.
  void keep_neighbours(const Particles<D>& p, Block& block, bool reused = false) const {
    block.kept_start.clear();
    block.kept.clear();
    block.reverse.clear();
    const auto& h = p.smoothing_length;
    for (std::size_t i = block.begin; i < block.end; ++i) {
      block.kept_start.push_back(block.kept.size());
      const double reach_i = K::support * h[i];
      const Candidates& cand = block.candidates;
      for (std::size_t c = block.candidate_start[i - block.begin]; c < block.candidate_start[i - block.begin + 1]; ++c) {
        const double r2 = cand.r2[c];
        if (r2 >= reach_i * reach_i) continue;
        const std::uint32_t j = cand.index[c];
        const Image image = reused ? current_image(cand.image[c], i, j) : cand.image[c];
        block.kept.push_back({j, image});
        const double reach_j = K::support * h[j];
        if (r2 >= reach_j * reach_j) {
          block.reverse.push_back({j, {static_cast<std::uint32_t>(i), mirror_image<D>(image)}});
        }
      }
    }
    block.kept_start.push_back(block.kept.size());
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

  // Join the blocks into one list, in particle order; reverse pairs go after each particle's
  // own (in the order of the particle that found them), so the list is the same for any
  // number of threads.
  void assemble_list(const Box<D>& box) {
    std::size_t n = 0;
    for (const auto& b : blocks_) n = std::max(n, b.end);
    std::vector<std::uint32_t>& extra = extra_;  // kept between updates: no allocation per step
    extra.assign(n, 0);
    for (const auto& b : blocks_)
      for (const auto& r : b.reverse) ++extra[r.first];
    list_.offset_.assign(n + 1, 0);
    for (const auto& b : blocks_)
      for (std::size_t i = b.begin; i < b.end; ++i)
        list_.offset_[i + 1] = b.kept_start[i - b.begin + 1] - b.kept_start[i - b.begin] + extra[i];
    for (std::size_t i = 0; i < n; ++i) list_.offset_[i + 1] += list_.offset_[i];
    list_.entries_.resize(list_.offset_[n]);
    std::vector<std::size_t>& fill = fill_;
    fill.resize(n);
#pragma omp parallel for schedule(static) if (blocks_.size() > 1)
    for (std::size_t t = 0; t < blocks_.size(); ++t) {
      const Block& b = blocks_[t];
      for (std::size_t i = b.begin; i < b.end; ++i) {
        const auto first = b.kept.begin() + static_cast<std::ptrdiff_t>(b.kept_start[i - b.begin]);
        const auto last = b.kept.begin() + static_cast<std::ptrdiff_t>(b.kept_start[i - b.begin + 1]);
        std::copy(first, last, list_.entries_.begin() + static_cast<std::ptrdiff_t>(list_.offset_[i]));
        fill[i] = list_.offset_[i] + static_cast<std::size_t>(last - first);
      }
    }
    for (const auto& b : blocks_)
      for (const auto& r : b.reverse) list_.entries_[fill[r.first]++] = r.second;
    list_.box_ = box;
  }

  CellGrid<D> grid_;
  std::vector<Block> blocks_;
  NeighbourList<D> list_;
  // What the last full search saw, for reusing its candidates.
  bool reusable_ = false;
  std::vector<Vec<D>> built_position_;
  Box<D> built_box_;
  SmoothingLengthRule::Mode built_mode_ = SmoothingLengthRule::Mode::fixed;
  std::vector<Vec<D>> previous_position_;   // positions at the last update
  std::array<std::vector<double>, D> unwrapped_;  // built position + displacement since, per axis
  std::vector<Image> wrapped_;  // periods between unwrapped and stored position, packed like an image
  long searches_ = 0, reuses_ = 0;
  std::vector<std::uint32_t> extra_;  // assemble_list: reverse pairs per particle
  std::vector<std::size_t> fill_;     // assemble_list: where each particle's next entry goes
  // Neighbour-number rule: the count a lattice shell forced on each particle (-1: none), and
  // the rule it was forced under.
  std::vector<int> shell_count_;
  SmoothingLengthRule shell_rule_;
};

}  // namespace sph
