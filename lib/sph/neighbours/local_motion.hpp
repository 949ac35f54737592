#pragma once
/// \file
/// \brief How far nearby particles can have moved relative to each other: the bound that lets
/// a neighbour search keep a particle's old candidates while its neighbourhood moves little.
///
/// Given the current positions x_j and displacements d_j (since some earlier time), sort the
/// particles into cells of at least a chosen size s and take, for each cell, the bounding box
/// of the displacements of its particles; then widen every cell's box to cover its 3^D
/// neighbouring cells as well.  A particle j within s of particle i lies in one of the cells
/// next to i's, so both d_i and d_j lie in the widened box B of i's cell, and with c the
/// centre of B
/// \f[ |d_i - d_j| \le |d_i - c| + |d_j - c| \le |d_i - c| + \tfrac12\,\mathrm{diag}(B). \f]
/// That right-hand side is bound(i).  A region that moves as a whole -- the plateau behind a
/// shock -- has a small box however far it has travelled: only differences of motion count.

#include "sph/box.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/parallel.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace sph {

/// The displacement of every particle since the last full neighbour search, and the bound
/// it gives on how far any two nearby particles can have moved relative to each other.
template <int D>
class LocalMotion {
 public:
  /// Bound |d_i - d_j| for every pair closer than (at least) `cell_size` now.  `x` are the
  /// current positions (wrapped into the box on periodic axes), d[a][i] the displacements.
  /// `extent`: the bounds of x, when the caller has them (several builds on the same
  /// positions, at several cell sizes, need them once).
  void build(const std::vector<Vec<D>>& x, const Box<D>& box, const std::array<const double*, D>& d,
             double cell_size, const Bounds<D>* extent = nullptr) {
    require(!x.empty(), "local motion: no particles");
    require(std::isfinite(cell_size) && cell_size > 0,
            "local motion: the cell size must be positive and finite");
    const std::size_t n = x.size();
    set_geometry(extent ? *extent : bounds<D>(x), box, cell_size, n);
    const std::size_t cells = total_cells();
    for (int a = 0; a < D; ++a) periodic_[a] = box.periodic[a];
    range_.resize(cells * width);
    cell_of_.resize(n);
    bound_.resize(n);
    // One parallel region for the whole build (a region per loop would cost more, in waking
    // the threads, than the loops): each loop is split among the threads, and every result
    // is the same for any thread count (minima, each cell's taken by one thread).
#pragma omp parallel if (n >= parallel_threshold)
    {
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        std::size_t cell = 0, stride = 1;
        for (int a = 0; a < D; ++a) {
          const double c = std::floor((x[i][a] - origin_[a]) / size_[a]);
          const int k = static_cast<int>(std::clamp(c, 0.0, static_cast<double>(cells_[a] - 1)));
          cell += static_cast<std::size_t>(k) * stride;
          stride *= static_cast<std::size_t>(cells_[a]);
        }
        cell_of_[i] = static_cast<std::uint32_t>(cell);
      }
      neighbourhood_minima<width>(range_, n, [&](std::size_t i, double* r) {
        for (int a = 0; a < D; ++a) {
          r[a] = std::min(r[a], d[a][i]);
          r[D + a] = std::min(r[D + a], -d[a][i]);
        }
      });
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        const double* r = range_.data() + std::size_t{cell_of_[i]} * width;
        double off2 = 0, half2 = 0;
        for (int a = 0; a < D; ++a) {
          const double lo = r[a], hi = -r[D + a];
          const double centre = 0.5 * (lo + hi);
          const double half = 0.5 * (hi - lo);
          off2 += (d[a][i] - centre) * (d[a][i] - centre);
          half2 += half * half;
        }
        bound_[i] = std::sqrt(off2) + std::sqrt(half2);
      }
    }
  }

  /// The cell size used: at least the one asked for (larger when the cells would be too many).
  double cell_size() const {
    double s = size_[0];
    for (int a = 1; a < D; ++a) s = std::min(s, size_[a]);
    return s;
  }
  /// An upper bound of |d_i - d_j| over every particle j (or periodic image of j) now closer
  /// than cell_size() to particle i.
  double bound(std::size_t i) const { return bound_[i]; }

  /// For every particle i, the smallest value[j] over the particles j (and periodic images)
  /// closer than cell_size() to it, found in the same cells as the bound (for the positions of
  /// the last build).
  void neighbourhood_min(const double* value, std::vector<double>& out) const {
    const std::size_t n = cell_of_.size();
    std::vector<double> least(total_cells());
    out.resize(n);
#pragma omp parallel if (n >= parallel_threshold)
    {
      neighbourhood_minima<1>(least, n,
                              [&](std::size_t i, double* r) { r[0] = std::min(r[0], value[i]); });
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) out[i] = least[cell_of_[i]];
    }
  }

 private:
  std::size_t total_cells() const {
    std::size_t total = 1;
    for (int a = 0; a < D; ++a) total *= static_cast<std::size_t>(cells_[a]);
    return total;
  }

  // Every cell's `Width` minima over its particles (lower(i, r) lowers r, the minima of
  // particle i's cell, by its values), then over the cell's 3^D neighbourhood (widen_along).
  // Called by every thread of a parallel region after cell_of_ is set.  The threads split the
  // cells into ranges, and each reads every particle's cell but lowers only its own cells': a
  // cell's minima are taken by one thread, in the particles' order, with no lock, the same for
  // any thread count.  (The ranges hold equal numbers of cells, not of particles: in a
  // collapsed cloud one thread takes most.)
  template <int Width, class Lower>
  void neighbourhood_minima(std::vector<double>& value, std::size_t n, Lower lower) const {
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < value.size(); ++k)
      value[k] = std::numeric_limits<double>::infinity();
    const std::size_t cells = total_cells();
    const auto parts = static_cast<std::size_t>(omp_get_num_threads()),
               part = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t first = cells * part / parts, last = cells * (part + 1) / parts;
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t cell = cell_of_[i];
      if (cell >= first && cell < last) lower(i, value.data() + std::size_t{cell} * Width);
    }
#pragma omp barrier
    std::vector<double> row;
    for (int axis = 0; axis < D; ++axis) widen_along<Width>(value, axis, row);
  }

  void set_geometry(const Bounds<D>& extent, const Box<D>& box, double target, std::size_t n) {
    const Vec<D>& lo = extent.lo;
    const Vec<D>& hi = extent.hi;
    require(lo.allFinite() && hi.allFinite(), "local motion: a particle position is not finite");
    const double max_cells = 2.0 * static_cast<double>(n) + 64.0;
    for (int attempt = 0; attempt < 200; ++attempt) {
      double total = 1;
      for (int a = 0; a < D; ++a) {
        // Whole cells of at least `target`: a periodic axis is tiled exactly, an open one
        // spans the particles.
        const double span = box.periodic[a] ? box.length(a) : hi[a] - lo[a];
        cells_[a] = std::max(1, static_cast<int>(std::min(std::floor(span / target), 1e6)));
        size_[a] = std::max(span / cells_[a], target);
        origin_[a] = box.periodic[a] ? box.lower[a] : lo[a];
        total *= cells_[a];
      }
      if (total <= max_cells) return;
      // (far off, jump by the factor that would fit if the cells shrank alike on every axis)
      target *= total > 1e3 * max_cells ? std::pow(total / max_cells, 1.0 / D) : 1.25;
    }
    throw Error("local motion: no cell size fits particles spread from " + to_string<D>(lo) +
                " to " + to_string<D>(hi) + " (a position far from the others?)");
  }

  // Replace every cell's `Width` values by the least of each over the cell and its two
  // neighbours along `axis` (periodically wrapped, or cut at the ends of an open axis); done
  // along each axis in turn, this covers the 3^D neighbourhood.  Called by every thread of a
  // parallel region, which share the lines along the axis (`row`: each thread's room for one).
  template <int Width>
  void widen_along(std::vector<double>& value, int axis, std::vector<double>& row) const {
    const int n = cells_[axis];
    if (n <= 1) return;  // (0: before any build)
    std::size_t stride = 1;
    for (int a = 0; a < axis; ++a) stride *= static_cast<std::size_t>(cells_[a]);
    const std::size_t line = stride * static_cast<std::size_t>(n);
    const std::size_t lines = total_cells() / static_cast<std::size_t>(n);
    const bool periodic = periodic_[axis];
    row.resize(static_cast<std::size_t>(n + 2) * Width);
#pragma omp for schedule(static)
    for (std::size_t l = 0; l < lines; ++l) {
      const std::size_t base = l / stride * line + l % stride;
      // The line with one cell more at each end: the other end's on a periodic axis, else
      // +inf (which changes no minimum).
      double* r = row.data() + Width;
      for (int k = 0; k < n; ++k) {
        const double* v = value.data() + (base + static_cast<std::size_t>(k) * stride) * Width;
        for (int c = 0; c < Width; ++c) r[k * Width + c] = v[c];
      }
      for (int c = 0; c < Width; ++c) {
        r[-Width + c] = periodic ? r[(n - 1) * Width + c] : std::numeric_limits<double>::infinity();
        r[n * Width + c] = periodic ? r[c] : std::numeric_limits<double>::infinity();
      }
      for (int k = 0; k < n; ++k) {
        double* v = value.data() + (base + static_cast<std::size_t>(k) * stride) * Width;
        for (int c = 0; c < Width; ++c) {
          v[c] =
              std::min(std::min(r[k * Width + c], r[(k - 1) * Width + c]), r[(k + 1) * Width + c]);
        }
      }
    }
  }

  std::array<int, D> cells_{};
  std::array<bool, D> periodic_{};
  Vec<D> origin_ = Vec<D>::Zero();
  Vec<D> size_ = Vec<D>::Ones();
  // Per cell, the range of the displacements on each axis as 2D minima side by side: the
  // least d_a, then the least -d_a (minus the largest), so that one pass widens them all.
  static constexpr int width = 2 * D;
  std::vector<double> range_;
  std::vector<std::uint32_t> cell_of_;
  std::vector<double> bound_;
};

}  // namespace sph
