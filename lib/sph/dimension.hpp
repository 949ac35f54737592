#pragma once
/// \file
/// \brief The dimension D = 1, 2, 3 as a compile-time parameter, and the vector type it implies.
///
/// Every physics routine is a template on `int D`.  A 1D scene therefore compiles a 1D vector
/// type (one double, no loops over unused components) and pays nothing for 3D.

#include "sph/error.hpp"

#include <Eigen/Core>

#include <cmath>
#include <string>
#include <vector>

namespace sph {

/// A position, velocity or acceleration in D dimensions.
template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

/// True for the three dimensions the toolkit supports.
template <int D>
concept SupportedDimension = (D >= 1 && D <= 3);

/// x^D without std::pow (exact for the small integer powers used in kernel normalisations).
template <int D>
constexpr double power(double x) {
  if constexpr (D == 0) {
    return 1.0;
  } else {
    return x * power<D - 1>(x);
  }
}

/// x^(1/D): the inverse of power<D>.
template <int D>
inline double root(double x) {
  if constexpr (D == 1) return x;
  if constexpr (D == 2) return std::sqrt(x);
  if constexpr (D == 3) return std::cbrt(x);
}

/// Volume of the unit ball in D dimensions: 2, pi, 4 pi / 3.
template <int D>
constexpr double unit_ball_volume() {
  if constexpr (D == 1) return 2.0;
  if constexpr (D == 2) return 3.14159265358979323846;
  if constexpr (D == 3) return 4.0 / 3.0 * 3.14159265358979323846;
}

/// "x", "y", "z" for axis a, used in labels and error messages.
inline const char* axis_name(int a) {
  static const char* names[] = {"x", "y", "z"};
  return (a >= 0 && a < 3) ? names[a] : "?";
}

/// The smallest and the largest coordinate of a set of points on each axis.
template <int D>
struct Bounds {
  Vec<D> lo, hi;
};

/// The bounds of `points` (which must not be empty).
template <int D>
Bounds<D> bounds(const std::vector<Vec<D>>& points) {
  Bounds<D> b{points[0], points[0]};
  for (const Vec<D>& x : points) {
    b.lo = b.lo.cwiseMin(x);
    b.hi = b.hi.cwiseMax(x);
  }
  return b;
}

/// A vector printed as "(x, y, z)" for error messages.
template <int D>
std::string to_string(const Vec<D>& v) {
  std::string s = "(";
  for (int a = 0; a < D; ++a) {
    if (a) s += ", ";
    s += show(v[a]);
  }
  return s + ")";
}

}  // namespace sph
