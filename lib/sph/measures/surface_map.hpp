#pragma once
/// \file
/// \brief The SPH-interpolated map of a 2D field: the surface density of the particles on a
/// grid of pixels, each particle's kernel integrated over each pixel it touches, as SPLASH
/// renders (Price 2007).
///
/// A map's pixel p shows the mean of the interpolated density over its area \f$ A_p \f$,
/// \f[ \Sigma_p = \frac{1}{A_p}\sum_i m_i \int_{A_p} W(|\mathbf x - \mathbf x_i|, h_i)\,dA, \f]
/// not the density at its centre: a pixel larger than h still receives the mass of every
/// particle in it, and the map's integral, \f$ \sum_p \Sigma_p A_p \f$, is the mass of the
/// particles it covers.  The integral over a pixel is taken by the midpoint rule on
/// \f$ s \times s \f$ sub-cells, \f$ s \ge 2 \f$ and fine enough for a sub-cell to be at most
/// h/4 wide (at most 16), and each particle's weights over all the pixels its kernel reaches
/// -- inside the map or not -- are scaled to sum to one, so that its mass is conserved exactly
/// however coarse the sampling: what falls outside the map is lost, nothing else.  A particle
/// whose kernel no sample sees (h far below a pixel) puts all its mass into its own pixel.
///
/// This is a measure, not a drawing: it returns the grid, which lib/plot draws as an image
/// (plot::Axes::image) -- so that lib/plot knows nothing of kernels.  Tested in
/// tests/sph/test_surface_map.cpp: a uniform sheet gives its density, the integral is the
/// mass, one particle gives the kernel's shape, a pixel much larger than h keeps the mass.

#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/kernel.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

namespace sph {

/// The pixels of a map: nx x ny over \f$ [x_0, x_1] \times [y_0, y_1] \f$.
struct MapGrid {
  int nx = 200, ny = 200;
  double x0 = -1, x1 = 1, y0 = -1, y1 = 1;

  double dx() const { return (x1 - x0) / nx; }
  double dy() const { return (y1 - y0) / ny; }
  void validate() const {
    require(nx > 0 && ny > 0 && nx <= 20000 && ny <= 20000,
            "map: 1 to 20000 pixels on each side (got " + show(nx) + " x " + show(ny) + ")");
    require(std::isfinite(x0) && std::isfinite(x1) && std::isfinite(y0) && std::isfinite(y1) &&
                x1 > x0 && y1 > y0,
            "map: the extent needs x0 < x1 and y0 < y1, all finite");
  }
};

/// The surface density of the particles at \p x with masses \p m and smoothing lengths \p h on
/// the pixels of \p grid: grid(i, j) is pixel i along x, j along y (file comment).  Throws
/// sph::Error for arrays of different lengths, or a position, mass or h that is not finite
/// (h must be positive), naming the particle.
template <class K = Kernel<2>>
Eigen::ArrayXXd surface_density_map(std::span<const Vec<2>> x, std::span<const double> m,
                                    std::span<const double> h, const MapGrid& grid) {
  grid.validate();
  require(x.size() == m.size() && x.size() == h.size(),
          "map: positions, masses and smoothing lengths differ in number");
  Eigen::ArrayXXd map = Eigen::ArrayXXd::Zero(grid.nx, grid.ny);
  const double dx = grid.dx(), dy = grid.dy(), area = dx * dy;
  std::vector<double> weights;
  for (std::size_t i = 0; i < x.size(); ++i) {
    require(x[i].allFinite() && std::isfinite(m[i]) && std::isfinite(h[i]) && h[i] > 0,
            "map: particle " + std::to_string(i) +
                " has a position, mass or smoothing length that is not finite (h must be "
                "positive)");
    const double reach = K::support * h[i];
    const int s = std::clamp(static_cast<int>(std::ceil(4 * std::max(dx, dy) / h[i])), 2, 16);
    // the pixels the kernel reaches, inside the map or not
    const int i0 = static_cast<int>(std::floor((x[i][0] - reach - grid.x0) / dx));
    const int i1 = static_cast<int>(std::floor((x[i][0] + reach - grid.x0) / dx));
    const int j0 = static_cast<int>(std::floor((x[i][1] - reach - grid.y0) / dy));
    const int j1 = static_cast<int>(std::floor((x[i][1] + reach - grid.y0) / dy));
    if (i1 < 0 || j1 < 0 || i0 >= grid.nx || j0 >= grid.ny) continue;  // wholly outside
    const int wi = i1 - i0 + 1, wj = j1 - j0 + 1;
    weights.assign(static_cast<std::size_t>(wi) * wj, 0.0);
    double total = 0;
    for (int a = 0; a < wi; ++a) {
      for (int b = 0; b < wj; ++b) {
        double w = 0;
        for (int u = 0; u < s; ++u) {
          for (int v = 0; v < s; ++v) {
            const double px = grid.x0 + (i0 + a + (u + 0.5) / s) * dx;
            const double py = grid.y0 + (j0 + b + (v + 0.5) / s) * dy;
            w += K::value(std::hypot(px - x[i][0], py - x[i][1]), h[i]);
          }
        }
        weights[static_cast<std::size_t>(a) * wj + b] = w;
        total += w;
      }
    }
    if (!(total > 0)) {  // no sample saw the kernel: all the mass into the particle's pixel
      const int pi = static_cast<int>(std::floor((x[i][0] - grid.x0) / dx));
      const int pj = static_cast<int>(std::floor((x[i][1] - grid.y0) / dy));
      if (pi >= 0 && pj >= 0 && pi < grid.nx && pj < grid.ny) map(pi, pj) += m[i] / area;
      continue;
    }
    for (int a = std::max(0, -i0); a < wi && i0 + a < grid.nx; ++a) {
      for (int b = std::max(0, -j0); b < wj && j0 + b < grid.ny; ++b) {
        map(i0 + a, j0 + b) += m[i] * weights[static_cast<std::size_t>(a) * wj + b] / total / area;
      }
    }
  }
  return map;
}

}  // namespace sph
