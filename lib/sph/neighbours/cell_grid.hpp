#pragma once
/// \file
/// \brief A uniform cell grid for finding the particles within a radius of a point.
///
/// The particles are counting-sorted into cells of a chosen size, and a copy of their
/// positions is kept in cell order so that the candidates of one cell are contiguous in
/// memory.  A query visits every cell that overlaps the cube of half-width R around the
/// point, and reports each particle closer than R.
///
/// **Periodic axes.**  On a periodic axis the cell range of a query may run past either face;
/// a raw cell coordinate c then stands for cell c mod n of the periodic image k = floor(c/n)
/// of the box, and the candidate is the particle shifted by k box lengths.  When the query
/// radius exceeds the box width (a narrow tube), the range wraps more than once and the same
/// particle is reported once per image that lies within R -- which is exactly what the SPH sums
/// need.  The image is returned packed in one integer (see pack_image).

#include "sph/box.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace sph {

/// A periodic image: the shift in box lengths along each axis, packed one signed byte per
/// axis.  Image 0 is the particle itself.
using Image = std::uint32_t;

/// Pack per-axis shifts k_a (each in [-127, 127]) into an Image.
template <int D>
inline Image pack_image(const std::array<int, D>& shift) {
  Image image = 0;
  for (int a = 0; a < D; ++a) {
    image |= static_cast<Image>(static_cast<std::uint8_t>(static_cast<std::int8_t>(shift[a])))
             << (8 * a);
  }
  return image;
}

/// The shift of axis a of a packed image, in box lengths.
inline int image_shift(Image image, int axis) {
  // Move the byte to the top and shift it back down arithmetically, which sign-extends it
  // (all in 32-bit integers, so SIMD loops over pairs keep 32-bit lanes).
  return static_cast<std::int32_t>(image << (24 - 8 * axis)) >> 24;
}

/// The image whose shifts are those of a plus those of b, axis by axis (the sums must fit in a
/// signed byte).  Computed on all bytes at once, without a branch, so SIMD loops can use it:
/// the low seven bits of each byte are added, and the top bit set by exclusive or, so no
/// carry crosses into the next byte.
inline Image add_images(Image a, Image b) {
  constexpr Image low = 0x7f7f7f7fu, high = 0x80808080u;
  return ((a & low) + (b & low)) ^ ((a ^ b) & high);
}

/// The image whose shifts are those of a minus those of b, axis by axis.
inline Image subtract_images(Image a, Image b) {
  constexpr Image low = 0x7f7f7f7fu, high = 0x80808080u;
  return ((a | high) - (b & low)) ^ ((a ^ ~b) & high);
}

/// The image seen from the other particle of the pair: all shifts negated.
template <int D>
inline Image mirror_image(Image image) {
  return subtract_images(0, image);
}

/// Where a packed image puts a particle relative to itself: the shift of each periodic axis
/// times the box length there (open axes have no images).
template <int D>
Vec<D> image_offset(Image image, const Box<D>& box) {
  Vec<D> offset = Vec<D>::Zero();
  for (int a = 0; a < D; ++a) {
    if (box.periodic[a]) offset[a] = image_shift(image, a) * box.length(a);
  }
  return offset;
}

/// Particles counting-sorted into uniform cells, with sorted copies of their positions, for
/// the search of all particles within a radius of a point.
template <int D>
class CellGrid {
 public:
  /// Sort the positions into cells of (about) `cell_size` on every axis.  Periodic axes get a
  /// whole number of cells across the box; positions must already be wrapped into the box on
  /// those axes.  Open axes span the particles' bounding box.  The total number of cells is
  /// kept below a few times the particle number, so a tiny cell size cannot exhaust memory.
  void build(const std::vector<Vec<D>>& x, const Box<D>& box, double cell_size) {
    require(!x.empty(), "cell grid: no particles");
    require(std::isfinite(cell_size) && cell_size > 0,
            "cell grid: the cell size must be positive and finite");
    box_ = box;
    set_geometry(x, cell_size);
    sort_into_cells(x);
  }

  /// Call f(j, image, r_ij, r2) for every particle j (or periodic image of it) with
  /// |r_ij| < radius, where r_ij = point - (x_j + image offset).  The point itself, if it is a
  /// particle, is reported too (with r2 = 0, image 0): callers skip it when they need to.
  template <class F>
  void for_each_within(const Vec<D>& point, double radius, F&& f) const {
    const double radius2 = radius * radius;
    std::uint32_t hit[scan_block];
    for_each_block_within(
        point, radius,
        [&](const std::uint32_t* index, const double* r2, std::size_t count, Image image) {
          // Compact the hits without a branch: about one candidate in three is one, too irregular
          // for the branch predictor.
          std::uint32_t hits = 0;
          for (std::uint32_t k = 0; k < count; ++k) {
            hit[hits] = k;
            hits += r2[k] < radius2;
          }
          const Vec<D> shifted = point - image_offset<D>(image, box_);
          for (std::uint32_t n = 0; n < hits; ++n) {
            const std::uint32_t k = hit[n];
            f(index[k], image, Vec<D>(shifted - position_of(index + k)), r2[k]);
          }
        });
  }

  /// The same query in blocks: call f(index, r2, count, image) for consecutive runs of up to
  /// scan_block sorted particles of the visited cells, with their squared distances from the
  /// point (particle index[k] at r2[k], image `image`); the caller keeps those with r2 < radius^2.
  /// Every particle within the radius is in some block; most block members are not.
  template <class F>
  void for_each_block_within(const Vec<D>& point, double radius, F&& f) const {
    std::array<int, D> first{}, last{};
    for (int a = 0; a < D; ++a) {
      first[a] = cell_coordinate(point[a] - radius, a);
      last[a] = cell_coordinate(point[a] + radius, a);
      if (!box_.periodic[a]) {
        first[a] = std::max(first[a], 0);
        last[a] = std::min(last[a], cells_[a] - 1);
        if (first[a] > last[a]) return;
      }
    }
    // Cells are numbered x-fastest, so for fixed higher coordinates a run of x cells is one
    // contiguous range of sorted particles.  We walk the higher axes with an odometer and
    // each x run in as few pieces as its periodic wrapping allows.
    std::array<int, D> raw = first;
    while (true) {
      int row = 0, stride = cells_[0];
      std::array<int, D> shift{};
      Vec<D> offset = Vec<D>::Zero();
      for (int a = 1; a < D; ++a) {
        const int c = wrap_axis(raw[a], a, shift[a]);
        offset[a] = shift[a] * box_.length(a);
        row += c * stride;
        stride *= cells_[a];
      }
      for_each_in_x_run(point, first[0], last[0], row, shift, offset, f);
      // Advance the odometer over the higher axes.
      int a = 1;
      while (a < D && raw[a] == last[a]) {
        raw[a] = first[a];
        ++a;
      }
      if (a >= D) break;
      ++raw[a];
    }
  }

  int cells(int axis) const { return cells_[axis]; }
  double cell_size(int axis) const { return cell_size_[axis]; }
  /// The largest query radius that stays within the grid on every open axis (any larger
  /// radius finds nothing more there); on a fully periodic box it is unbounded.
  double extent() const {
    double e = 0;
    for (int a = 0; a < D; ++a) e = std::max(e, cells_[a] * cell_size_[a]);
    return e;
  }
  const Box<D>& box() const { return box_; }

 private:
  // Wrap a raw cell coordinate on axis a; the periodic image it lies in goes to `shift`.
  int wrap_axis(int c, int a, int& shift) const {
    shift = 0;
    if (!box_.periodic[a]) return c;
    // A query spans a few cells past either face: add or subtract whole periods (cheaper than
    // an integer division, which this loop would otherwise do for every row).
    const int n = cells_[a];
    while (c < 0) {
      c += n;
      --shift;
    }
    while (c >= n) {
      c -= n;
      ++shift;
    }
    return c;
  }

  // The x cells first..last of one row, split where the periodic wrap changes the image.
  template <class F>
  void for_each_in_x_run(const Vec<D>& point, int first, int last, int row,
                         std::array<int, D> shift, Vec<D> offset, F& f) const {
    int c = first;
    while (c <= last) {
      const int begin = wrap_axis(c, 0, shift[0]);
      const int end = std::min(cells_[0] - 1, begin + (last - c));
      offset[0] = shift[0] * box_.length(0);
      const Image image = pack_image<D>(shift);
      const Vec<D> shifted_point = point - offset;
      scan_range(cell_start_[row + begin], cell_start_[row + end + 1], shifted_point, image, f);
      c += end - begin + 1;
    }
  }

  // The particles sorted_[first..last), in blocks with their squared distances from the point.
  // The distances are computed from per-axis coordinate arrays in a branch-free loop the
  // compiler vectorises.
  template <class F>
  void scan_range(std::uint32_t first, std::uint32_t last, const Vec<D>& point, Image image,
                  F& f) const {
    constexpr std::uint32_t block = scan_block;
    double r2[block];
    for (std::uint32_t start = first; start < last; start += block) {
      const std::uint32_t count = std::min(block, last - start);
      // Pointers to the block first, so the compiler sees contiguous loads (32-bit index
      // arithmetic that might wrap would make it gather element by element).
      std::array<const double*, D> xs;
      for (int a = 0; a < D; ++a) xs[a] = sorted_coordinate_[a].data() + start;
      for (std::size_t k = 0; k < count; ++k) {
        double sum = 0;
#pragma GCC unroll 3
        for (int a = 0; a < D; ++a) {
          const double d = point[a] - xs[a][k];
          sum += d * d;
        }
        r2[k] = sum;
      }
      f(sorted_index_.data() + start, static_cast<const double*>(r2),
        static_cast<std::size_t>(count), image);
    }
  }

  // Choose origin, number of cells and cell size on each axis.
  void set_geometry(const std::vector<Vec<D>>& x, double target) {
    const auto [lo, hi] = bounds<D>(x);
    require(lo.allFinite() && hi.allFinite(), "cell grid: a particle position is not finite");
    // Keep the number of cells at most ~4 N (+ a floor): enlarge the target until it fits.
    const double max_cells = 4.0 * static_cast<double>(x.size()) + 64.0;
    for (int attempt = 0; attempt < 200; ++attempt) {
      double total = 1.0;
      for (int a = 0; a < D; ++a) {
        if (box_.periodic[a]) {
          const double L = box_.length(a);
          cells_[a] = std::max(1, static_cast<int>(std::min(L / target, 1e6)));
          origin_[a] = box_.lower[a];
          cell_size_[a] = L / cells_[a];
        } else {
          const double span = hi[a] - lo[a];
          cells_[a] = std::max(1, static_cast<int>(std::min(std::ceil(span / target), 1e6)));
          cell_size_[a] = std::max(span / cells_[a], target);
          // Centre the grid on the particles; the outermost ones stay strictly inside.
          origin_[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * cells_[a] * cell_size_[a];
        }
        total *= cells_[a];
      }
      if (total <= max_cells) {
        inverse_cell_size_ = cell_size_.cwiseInverse();
        return;
      }
      // (far off, jump by the factor that would fit if the cells shrank alike on every axis)
      target *= total > 1e3 * max_cells ? std::pow(total / max_cells, 1.0 / D) : 1.25;
    }
    throw Error("cell grid: no cell size fits particles spread from " + to_string<D>(lo) + " to " +
                to_string<D>(hi) + " (a position far from the others?)");
  }

  int cell_coordinate(double xa, int a) const {
    const double c = std::floor((xa - origin_[a]) * inverse_cell_size_[a]);
    // Clamp far-away coordinates so huge radii cannot overflow an int.
    const double limit = 1e8;
    return static_cast<int>(std::clamp(c, -limit, limit));
  }

  // Counting sort of the particles into cells (stable: deterministic order inside a cell).
  void sort_into_cells(const std::vector<Vec<D>>& x) {
    int total = 1;
    for (int a = 0; a < D; ++a) total *= cells_[a];
    std::vector<std::uint32_t> cell_of(x.size());
    cell_start_.assign(static_cast<std::size_t>(total) + 1, 0);
    for (std::size_t i = 0; i < x.size(); ++i) {
      int cell = 0, stride = 1;
      for (int a = 0; a < D; ++a) {
        const int c = std::clamp(cell_coordinate(x[i][a], a), 0, cells_[a] - 1);
        cell += c * stride;
        stride *= cells_[a];
      }
      cell_of[i] = static_cast<std::uint32_t>(cell);
      ++cell_start_[cell + 1];
    }
    for (int c = 0; c < total; ++c) cell_start_[c + 1] += cell_start_[c];
    sorted_position_.resize(x.size());
    sorted_index_.resize(x.size());
    for (auto& coordinate : sorted_coordinate_) coordinate.resize(x.size());
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < x.size(); ++i) {
      const std::uint32_t p = fill[cell_of[i]]++;
      sorted_position_[p] = x[i];
      for (int a = 0; a < D; ++a) sorted_coordinate_[a][p] = x[i][a];
      sorted_index_[p] = static_cast<std::uint32_t>(i);
    }
  }

  static constexpr std::uint32_t scan_block = 32;  // particles per block of a scan
  // The position of the sorted particle whose index entry is at `entry`.
  const Vec<D>& position_of(const std::uint32_t* entry) const {
    return sorted_position_[entry - sorted_index_.data()];
  }

  Box<D> box_;
  Vec<D> origin_ = Vec<D>::Zero();
  Vec<D> cell_size_ = Vec<D>::Ones();
  Vec<D> inverse_cell_size_ = Vec<D>::Ones();  // multiplied rather than divided by, in every query
  std::array<int, D> cells_{};
  std::vector<std::uint32_t> cell_start_;
  std::vector<Vec<D>> sorted_position_;
  std::array<std::vector<double>, D> sorted_coordinate_;  // the same, one array per axis
  std::vector<std::uint32_t> sorted_index_;
};

}  // namespace sph
