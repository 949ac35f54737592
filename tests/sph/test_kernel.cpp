// Kernel property tests (after Phantom's test_kernel.f90 and pbrt-v4's filters_test.cpp):
// W(0), W >= 0, W = 0 past the support exactly, unit integral in 1D/2D/3D by quadrature,
// analytic gradient against finite differences, symmetry.
#include "sph/kernel.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

namespace {

using std::numbers::pi;

// Integral of W over all space by the radial quadrature: int W dV = S_D int_0^{2h} W(r) r^{D-1} dr,
// with S_D the surface of the unit sphere (2, 2 pi, 4 pi).  Composite Simpson on a fine grid,
// split at the kernel's knots q = 1, 2 where the shape changes polynomial piece.
template <int D, class K>
double integral(double h) {
  const double surface = D == 1 ? 2.0 : (D == 2 ? 2.0 * pi : 4.0 * pi);
  auto f = [&](double r) { return K::value(r, h) * std::pow(r, D - 1); };
  double total = 0;
  const int n = 20000;  // intervals per piece (even)
  for (int piece = 0; piece < 2; ++piece) {
    const double a = piece * h, b = (piece + 1) * h, dr = (b - a) / n;
    double s = f(a) + f(b);
    for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * f(a + k * dr);
    total += s * dr / 3.0;
  }
  return surface * total;
}

template <int D, class K>
void check_kernel_properties() {
  const double h = 0.37;
  // Normalisation: exact to quadrature error (Simpson is exact for cubics on each piece).
  CHECK(integral<D, K>(h) == Approx(1.0).epsilon(1e-10));
  // Non-negative inside, exactly zero at and past the support.
  for (int k = 0; k <= 1000; ++k) {
    const double r = 2.0 * h * k / 1000.0;
    CHECK(K::value(r, h) >= 0.0);
  }
  CHECK(K::value(2.0 * h, h) == 0.0);
  CHECK(K::value(2.0 * h * (1 + 1e-12), h) == 0.0);
  CHECK(K::derivative(2.0 * h, h) == 0.0);
  // Gradient against a centred finite difference (relative error with an absolute floor).
  for (double q : {0.05, 0.3, 0.9, 0.999, 1.001, 1.5, 1.9}) {
    const double r = q * h, dr = 1e-6 * h;
    const double fd = (K::value(r + dr, h) - K::value(r - dr, h)) / (2 * dr);
    const double floor = 1e-8 * K::value(0, h) / h;
    CHECK(std::abs(K::derivative(r, h) - fd) <= 1e-6 * std::abs(fd) + floor);
    CHECK(K::gradient_factor(r, h) * r == Approx(K::derivative(r, h)).epsilon(1e-12));
  }
  // The gradient vector is antisymmetric in the pair and finite for coincident particles.
  sph::Vec<D> r_ij = sph::Vec<D>::Constant(0.1 * h);
  CHECK((K::gradient(r_ij, h) + K::gradient(sph::Vec<D>(-r_ij), h)).norm() == 0.0);
  CHECK(K::gradient(sph::Vec<D>::Zero(), h).norm() == 0.0);
}

}  // namespace

TEST_CASE("M4 cubic spline: W(0) equals the tabulated normalisation", "[kernel]") {
  const double h = 0.5;
  CHECK(sph::Kernel<1>::value(0, h) == Approx(2.0 / 3.0 / h));
  CHECK(sph::Kernel<2>::value(0, h) == Approx(10.0 / (7.0 * pi) / (h * h)));
  CHECK(sph::Kernel<3>::value(0, h) == Approx(1.0 / (pi * h * h * h)));
  // Continuity of W and dW/dq at the knot q = 1.
  const auto below = sph::CubicSpline::evaluate(1.0 - 1e-12),
             above = sph::CubicSpline::evaluate(1.0);
  CHECK(below.w == Approx(above.w));
  CHECK(below.dw_dq == Approx(above.dw_dq));
}

TEST_CASE("M4 cubic spline properties in 1D, 2D, 3D", "[kernel]") {
  check_kernel_properties<1, sph::Kernel<1>>();
  check_kernel_properties<2, sph::Kernel<2>>();
  check_kernel_properties<3, sph::Kernel<3>>();
}

TEST_CASE("Wendland C2 properties in 1D, 2D, 3D", "[kernel]") {
  check_kernel_properties<1, sph::Kernel<1, sph::WendlandC2<1>>>();
  check_kernel_properties<2, sph::Kernel<2, sph::WendlandC2<2>>>();
  check_kernel_properties<3, sph::Kernel<3, sph::WendlandC2<3>>>();
}
