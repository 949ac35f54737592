#pragma once
/// \file
/// \brief Smoothing kernels: one table of shapes and normalisations, one evaluator.
///
/// A kernel is written \f$ W(r, h) = \frac{\sigma_D}{h^D}\, w(q) \f$ with \f$ q = r/h \f$.
/// The shape \f$ w(q) \f$ is dimension-free; the normalisation \f$ \sigma_D \f$ makes
/// \f$ \int W\, dV = 1 \f$ in D dimensions.  Everything a pass needs comes from one call,
/// `Shape::evaluate(q)`, which returns \f$ w \f$, \f$ dw/dq \f$ and \f$ (dw/dq)/q \f$.  The
/// last one gives the gradient without dividing by \f$ r \f$, so coincident particles
/// (\f$ r = 0 \f$) get a zero gradient rather than a NaN:
/// \f[ \nabla_i W(\mathbf r_{ij}, h) = \frac{\sigma_D}{h^{D+2}}\,
///     \frac{1}{q}\frac{dw}{dq}\; \mathbf r_{ij}. \f]

#include "sph/dimension.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sph {

/// The shape of a kernel at one q: value and derivatives.
struct KernelShape {
  double w = 0;             ///< w(q)
  double dw_dq = 0;         ///< dw/dq
  double dw_dq_over_q = 0;  ///< (dw/dq)/q, finite at q = 0
};

/// The M4 cubic spline of Monaghan & Lattanzio (1985): Selhammar (1997) eq 3, Watkins et al.
/// (1996) eqs A2-A3.  Support 2h; normalisation 2/3, 10/(7 pi), 1/pi in 1D, 2D, 3D:
/// \f[ w(q) = \begin{cases} 1 - \tfrac32 q^2 + \tfrac34 q^3, & 0 \le q < 1,
///     \\ \tfrac14 (2 - q)^3, & 1 \le q < 2, \\ 0, & q \ge 2, \end{cases} \qquad
///     \sigma_D = \tfrac23,\ \tfrac{10}{7\pi},\ \tfrac1\pi . \f]
struct CubicSpline {
  static constexpr const char* name = "M4 cubic spline";
  static constexpr double support = 2.0;  ///< W = 0 for q >= support

  template <int D>
  static constexpr double normalisation() {
    if constexpr (D == 1) return 2.0 / 3.0;
    if constexpr (D == 2) return 10.0 / (7.0 * std::numbers::pi);
    if constexpr (D == 3) return 1.0 / std::numbers::pi;
  }

  /// Written without branches (the passes evaluate it for several pairs at once in SIMD
  /// registers): the two pieces are selected, not branched to.  The outer piece divides by
  /// max(q, 1), which is q wherever it is selected, and never divides by zero.
  static constexpr KernelShape evaluate(double q) {
    const double s = q < 2.0 ? 2.0 - q : 0.0;  // zero past the support
    const bool inner = q < 1.0;
    return {inner ? 1.0 - 1.5 * q * q + 0.75 * q * q * q : 0.25 * s * s * s,
            inner ? -3.0 * q + 2.25 * q * q : -0.75 * s * s,
            inner ? -3.0 + 2.25 * q : -0.75 * s * s / std::max(q, 1.0)};
  }
};

/// The Wendland C2 kernel (Wendland 1995; Dehnen & Aly 2012), scaled to the same support 2h as
/// the M4 so the two can be swapped at equal h.  Given for comparison: it has no pairing
/// instability at large neighbour numbers.  In 1D the C2 function differs from 2D/3D; with
/// \f$ s = q/2 \f$ and \f$ w = 0 \f$ for \f$ s \ge 1 \f$,
/// \f[ w_{1D}(q) = (1 - s)^3 (1 + 3s), \quad w_{2D,3D}(q) = (1 - s)^4 (1 + 4s), \qquad
///     \sigma_D = \frac{5}{8},\ \frac{7}{4\pi},\ \frac{21}{16\pi} . \f]
template <int D>
struct WendlandC2 {
  static constexpr const char* name = "Wendland C2";
  static constexpr double support = 2.0;

  // With s = q/2: 1D phi = (1-s)^3 (1+3s), norm 5/4 / (2h);  2D/3D phi = (1-s)^4 (1+4s), norm
  // 7/pi / (2h)^2 and 21/(2 pi) / (2h)^3.
  template <int Dim>
  static constexpr double normalisation() {
    static_assert(Dim == D, "WendlandC2<D> is defined per dimension");
    if constexpr (D == 1) return 5.0 / 4.0 / 2.0;
    if constexpr (D == 2) return 7.0 / std::numbers::pi / 4.0;
    if constexpr (D == 3) return 21.0 / (2.0 * std::numbers::pi) / 8.0;
  }

  static constexpr KernelShape evaluate(double q) {
    if (q >= 2.0) return {};
    const double s = 0.5 * q, t = 1.0 - s;
    if constexpr (D == 1) {
      return {t * t * t * (1.0 + 3.0 * s), -6.0 * s * t * t, -3.0 * t * t};
    } else {
      return {t * t * t * t * (1.0 + 4.0 * s), -10.0 * s * t * t * t, -5.0 * t * t * t};
    }
  }
};

/// The density of an infinite 1D lattice of unit spacing and unit masses with the M4 kernel at
/// h = eta (times the spacing), by Poisson summation rather than by summing the kernel: the M4
/// is the cubic B-spline of knot spacing h, whose Fourier transform is
/// \f$ (\sin(kh/2)/(kh/2))^4 \f$, so the lattice sum is
/// \f$ 1 + 2\sum_{k \ge 1} \mathrm{sinc}^4(\pi k \eta) \f$.  It shares no code with the density
/// pass, which makes it a check on it (chapter 2, tests/sph/test_density.cpp).
inline double m4_lattice_density_1d(double eta) {
  double sum = 1.0;
  for (int k = 1; k < 200000; ++k) {
    const double x = std::numbers::pi * k * eta;
    const double sinc = std::sin(x) / x;
    sum += 2.0 * sinc * sinc * sinc * sinc;
  }
  return sum;
}

/// A kernel shape with its D-dimensional normalisation: the evaluator the passes call.
template <int D, class Shape = CubicSpline>
struct Kernel {
  using shape = Shape;
  static constexpr double sigma = Shape::template normalisation<D>();
  static constexpr double support = Shape::support;

  /// W(r, h).
  static double value(double r, double h) {
    const double inv_h = 1.0 / h;
    return sigma * power<D>(inv_h) * Shape::evaluate(r * inv_h).w;
  }

  /// dW/dr (a scalar; negative inside the support).
  static double derivative(double r, double h) {
    const double inv_h = 1.0 / h;
    return sigma * power<D + 1>(inv_h) * Shape::evaluate(r * inv_h).dw_dq;
  }

  /// The factor g with \f$ \nabla_i W(\mathbf r_{ij}, h) = g\, \mathbf r_{ij} \f$.
  static double gradient_factor(double r, double h) {
    const double inv_h = 1.0 / h;
    return sigma * power<D + 2>(inv_h) * Shape::evaluate(r * inv_h).dw_dq_over_q;
  }

  /// \f$ \nabla_i W(\mathbf r_{ij}, h) \f$ for \f$ \mathbf r_{ij} = \mathbf r_i - \mathbf r_j \f$.
  static Vec<D> gradient(const Vec<D>& r_ij, double h) {
    return gradient_factor(r_ij.norm(), h) * r_ij;
  }
};

}  // namespace sph
