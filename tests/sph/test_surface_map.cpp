// The SPH-interpolated map (lib/sph/measures/surface_map.hpp): a uniform sheet gives its
// density, the map's integral is the mass, one particle gives the kernel's shape, a pixel much
// larger than h keeps the mass, and bad input is refused naming the particle.
#include "sph/measures/surface_map.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

namespace {
struct Sheet {
  std::vector<sph::Vec<2>> x;
  std::vector<double> m, h;
};
// A square lattice of spacing d over [-L, L]^2 with surface density 1 and h = 1.2 d.
Sheet lattice(double L, double d) {
  Sheet s;
  const int n = static_cast<int>(std::lround(2 * L / d));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      s.x.emplace_back(-L + (i + 0.5) * d, -L + (j + 0.5) * d);
      s.m.push_back(d * d);
      s.h.push_back(1.2 * d);
    }
  return s;
}
double integral(const Eigen::ArrayXXd& map, const sph::MapGrid& g) {
  return map.sum() * g.dx() * g.dy();
}
}  // namespace

TEST_CASE("surface map: a uniform sheet gives its density, and the integral its mass", "[map]") {
  const Sheet s = lattice(1.0, 0.02);
  // pixels smaller than h, equal to it, and larger than the kernel's support
  for (const int pixels : {400, 100, 20}) {
    const sph::MapGrid g{pixels, pixels, -1.2, 1.2, -1.2, 1.2};
    const Eigen::ArrayXXd map = sph::surface_density_map(s.x, s.m, s.h, g);
    INFO(pixels << " pixels a side");
    CHECK(integral(map, g) == Approx(4.0).epsilon(1e-12));
    // the interior, two smoothing lengths from the sheet's edge, and clear of partial pixels
    double worst = 0;
    for (int i = 0; i < pixels; ++i)
      for (int j = 0; j < pixels; ++j) {
        const double x0 = g.x0 + i * g.dx(), y0 = g.y0 + j * g.dy();
        if (x0 < -0.9 || x0 + g.dx() > 0.9 || y0 < -0.9 || y0 + g.dy() > 0.9) continue;
        worst = std::max(worst, std::abs(map(i, j) - 1));
      }
    // (the SPH field of a square lattice at h = 1.2 d itself ripples between lattice points,
    // from +3.7e-3 at a point of the lattice to -1.4e-3 midway between two: a pixel smaller
    // than the spacing shows the ripple, a larger one averages it away)
    CHECK(worst < (pixels > 100 ? 4e-3 : 1e-3));
  }
}

TEST_CASE("surface map: one particle gives the kernel's shape, a big pixel keeps its mass",
          "[map]") {
  const std::vector<sph::Vec<2>> x{{0.013, -0.007}};
  const std::vector<double> m{2.0}, h{0.1};
  const sph::MapGrid fine{200, 200, -0.25, 0.25, -0.25, 0.25};  // pixels h/40
  const Eigen::ArrayXXd map = sph::surface_density_map(x, m, h, fine);
  CHECK(integral(map, fine) == Approx(2.0).epsilon(1e-12));
  for (int i = 0; i < 200; i += 7)
    for (int j = 0; j < 200; j += 7) {
      const double px = fine.x0 + (i + 0.5) * fine.dx(), py = fine.y0 + (j + 0.5) * fine.dy();
      const double r = std::hypot(px - x[0][0], py - x[0][1]);
      if (r > 1.5 * h[0]) continue;  // (near the edge of the support W is small and steep)
      INFO("r / h = " << r / h[0]);
      CHECK(map(i, j) == Approx(2.0 * sph::Kernel<2>::value(r, h[0])).epsilon(2e-3));
    }
  // pixels 100 times h: the whole mass in the particle's own pixel
  const std::vector<double> tiny{0.001};
  const sph::MapGrid coarse{4, 4, -0.2, 0.2, -0.2, 0.2};
  const Eigen::ArrayXXd big = sph::surface_density_map(x, m, tiny, coarse);
  CHECK(integral(big, coarse) == Approx(2.0).epsilon(1e-12));
  CHECK(big(2, 1) * coarse.dx() * coarse.dy() == Approx(2.0).epsilon(1e-12));
  // a particle half outside the map keeps only what falls inside
  const std::vector<sph::Vec<2>> edge{{0.25, 0.0}};
  CHECK(integral(sph::surface_density_map(edge, m, h, fine), fine) == Approx(1.0).epsilon(2e-3));
}

TEST_CASE("surface map: bad input is refused", "[map]") {
  std::vector<sph::Vec<2>> x{{0, 0}, {0.1, 0}};
  std::vector<double> m{1, 1}, h{0.1, 0.1};
  const sph::MapGrid g{10, 10, -1, 1, -1, 1};
  CHECK_THROWS_WITH(sph::surface_density_map(x, m, h, sph::MapGrid{0, 10, -1, 1, -1, 1}),
                    Catch::Contains("pixels"));
  CHECK_THROWS_WITH(sph::surface_density_map(x, m, h, sph::MapGrid{10, 10, 1, -1, -1, 1}),
                    Catch::Contains("extent"));
  h[1] = std::nan("");
  CHECK_THROWS_WITH(sph::surface_density_map(x, m, h, g), Catch::Contains("particle 1"));
  h[1] = 0.1;
  m.pop_back();
  CHECK_THROWS_WITH(sph::surface_density_map(x, m, h, g), Catch::Contains("differ in number"));
}
