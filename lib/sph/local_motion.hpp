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
  void build(const std::vector<Vec<D>>& x, const Box<D>& box, const std::array<const double*, D>& d,
             double cell_size) {
    require(!x.empty(), "local motion: no particles");
    require(std::isfinite(cell_size) && cell_size > 0,
            "local motion: the cell size must be positive and finite");
    const std::size_t n = x.size();
    set_geometry(x, box, cell_size);
    const std::size_t cells = total_cells();
    constexpr double inf = std::numeric_limits<double>::infinity();
    for (int a = 0; a < D; ++a) {
      lo_[a].assign(cells, inf);
      hi_[a].assign(cells, -inf);
    }
    cell_of_.resize(n);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
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
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t cell = cell_of_[i];
      for (int a = 0; a < D; ++a) {
        lo_[a][cell] = std::min(lo_[a][cell], d[a][i]);
        hi_[a][cell] = std::max(hi_[a][cell], d[a][i]);
      }
    }
    for (int a = 0; a < D; ++a) periodic_[a] = box.periodic[a];
    for (int axis = 0; axis < D; ++axis) {
      for (int a = 0; a < D; ++a) {
        widen_along(lo_[a], axis, [](double u, double v) { return std::min(u, v); });
        widen_along(hi_[a], axis, [](double u, double v) { return std::max(u, v); });
      }
    }
    bound_.resize(n);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t cell = cell_of_[i];
      double off2 = 0, half2 = 0;
      for (int a = 0; a < D; ++a) {
        const double centre = 0.5 * (lo_[a][cell] + hi_[a][cell]);
        const double half = 0.5 * (hi_[a][cell] - lo_[a][cell]);
        off2 += (d[a][i] - centre) * (d[a][i] - centre);
        half2 += half * half;
      }
      bound_[i] = std::sqrt(off2) + std::sqrt(half2);
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
    std::vector<double> least(total_cells(), std::numeric_limits<double>::infinity());
    const std::size_t n = cell_of_.size();
    for (std::size_t i = 0; i < n; ++i) least[cell_of_[i]] = std::min(least[cell_of_[i]], value[i]);
    for (int axis = 0; axis < D; ++axis)
      widen_along(least, axis, [](double u, double v) { return std::min(u, v); });
    out.resize(n);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) out[i] = least[cell_of_[i]];
  }

 private:
  std::size_t total_cells() const {
    std::size_t total = 1;
    for (int a = 0; a < D; ++a) total *= static_cast<std::size_t>(cells_[a]);
    return total;
  }

  void set_geometry(const std::vector<Vec<D>>& x, const Box<D>& box, double target) {
    const auto [lo, hi] = bounds<D>(x);
    require(lo.allFinite() && hi.allFinite(), "local motion: a particle position is not finite");
    const double max_cells = 2.0 * static_cast<double>(x.size()) + 64.0;
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

  // Replace every cell's value by `pick` (the min or the max) of it and its two neighbours
  // along `axis` (periodically wrapped, or cut at the ends of an open axis); done along each
  // axis in turn, this covers the 3^D neighbourhood.
  template <class Pick>
  void widen_along(std::vector<double>& value, int axis, Pick pick) const {
    const int n = cells_[axis];
    if (n == 1) return;
    std::size_t stride = 1;
    for (int a = 0; a < axis; ++a) stride *= static_cast<std::size_t>(cells_[a]);
    const std::size_t cells = total_cells();
    const std::size_t line = stride * static_cast<std::size_t>(n);
    std::vector<double> row(static_cast<std::size_t>(n));
    for (std::size_t outer = 0; outer < cells; outer += line) {
      for (std::size_t inner = 0; inner < stride; ++inner) {
        const std::size_t base = outer + inner;
        for (int k = 0; k < n; ++k)
          row[static_cast<std::size_t>(k)] = value[base + static_cast<std::size_t>(k) * stride];
        for (int k = 0; k < n; ++k) {
          double v = row[static_cast<std::size_t>(k)];
          for (int s : {-1, 1}) {
            int m = k + s;
            if (periodic_[axis]) m = (m + n) % n;
            if (m < 0 || m >= n) continue;
            v = pick(v, row[static_cast<std::size_t>(m)]);
          }
          value[base + static_cast<std::size_t>(k) * stride] = v;
        }
      }
    }
  }

  std::array<int, D> cells_{};
  std::array<bool, D> periodic_{};
  Vec<D> origin_ = Vec<D>::Zero();
  Vec<D> size_ = Vec<D>::Ones();
  std::array<std::vector<double>, D> lo_, hi_;  // per cell and axis: the displacements' range
  std::vector<std::uint32_t> cell_of_;
  std::vector<double> bound_;
};

}  // namespace sph
