#pragma once
/// \file
/// \brief The domain: an axis-aligned box whose axes are periodic or open.
///
/// On a periodic axis a particle leaving through one face re-enters through the other, and
/// neighbours are found across the face.  An open axis has no walls: particles are free to
/// go anywhere (the shock tubes' free ends).  A periodic axis may be narrower than the kernel
/// support (the papers' tubes are 0.125 and 1 wide): the neighbour search then finds several
/// periodic images of the same particle, each a neighbour in its own right.

#include "sph/dimension.hpp"
#include "sph/error.hpp"

#include <array>

namespace sph {

/// The domain of a D-dimensional scene: its lower and upper corners and which axes are
/// periodic.
template <int D>
struct Box {
  Vec<D> lower = Vec<D>::Zero();   ///< lower corner (used on periodic axes)
  Vec<D> upper = Vec<D>::Ones();   ///< upper corner (used on periodic axes)
  std::array<bool, D> periodic{};  ///< per axis: periodic (true) or open (false)

  /// A box periodic in every axis.
  static Box periodic_box(const Vec<D>& lower, const Vec<D>& upper) {
    Box b{lower, upper, {}};
    b.periodic.fill(true);
    b.validate();
    return b;
  }
  /// A box open in every axis (lower/upper unused).
  static Box open() { return Box{}; }

  double length(int axis) const { return upper[axis] - lower[axis]; }

  /// Wrap a position back into the box on its periodic axes.
  Vec<D> wrap(Vec<D> x) const {
    for (int a = 0; a < D; ++a) {
      if (!periodic[a]) continue;
      const double L = length(a);
      x[a] -= L * std::floor((x[a] - lower[a]) / L);
      if (x[a] >= upper[a]) x[a] = lower[a];  // guard against round-off at the face
    }
    return x;
  }

  /// The separation x_i - x_j by the nearest periodic image (only meaningful when the box is
  /// wider than twice the distance of interest; the neighbour list handles the general case).
  Vec<D> separation(const Vec<D>& xi, const Vec<D>& xj) const {
    Vec<D> d = xi - xj;
    for (int a = 0; a < D; ++a) {
      if (!periodic[a]) continue;
      const double L = length(a);
      d[a] -= L * std::round(d[a] / L);
    }
    return d;
  }

  void validate() const {
    for (int a = 0; a < D; ++a) {
      if (periodic[a]) {
        require(std::isfinite(lower[a]) && std::isfinite(upper[a]) && upper[a] > lower[a],
                std::string("box: periodic axis ") + axis_name(a) +
                    " needs finite bounds with upper > lower");
      }
    }
  }
};

}  // namespace sph
