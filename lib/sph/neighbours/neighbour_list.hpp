#pragma once
/// \file
/// \brief The neighbour list, and the positions one array per axis that the passes read with it.
///
/// The list holds, for each particle i, every particle j (or periodic image of j) with
/// \f$ r_{ij} < 2\max(h_i, h_j) \f$.  That one symmetric list serves all the sums of the
/// toolkit: the gather form \f$ W(r_{ij}, h_i) \f$ (Watkins et al. 1996 eq A1), the
/// pair-averaged form \f$ W(r_{ij}, \bar h_{ij}) \f$ (Selhammar 1997 eqs 1, 5) and the
/// scatter form \f$ W(r_{ij}, h_j) \f$.  Pairs are stored once per side, so every pass is a
/// gather loop over i: each particle writes only its own sums, the passes run in parallel
/// without locks, and the result does not depend on the number of threads.
///
/// "Neighbours" never include the particle itself (its own periodic images do count).
///
/// NeighbourSearch (neighbour_search.hpp) writes the list; the rules that choose h are in
/// smoothing_length.hpp.

#include "sph/box.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/neighbours/cell_grid.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <array>
#include <cmath>
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
      throw Error(std::string(pass) + ": particle " + show(i) + " at " +
                  to_string<D>(p.position[i]) + " has mass " + show(p.mass[i]) +
                  " (must be positive and finite)");
    }
  }
}

}  // namespace sph
