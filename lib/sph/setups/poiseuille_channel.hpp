#pragma once
/// \file
/// \brief The channel of Watkins et al.'s (1996, sect. 4.1) Poiseuille flow: a square lattice of
/// unit side centred on the origin, periodic in x, fluid particles where \f$ |y| \le a \f$ and
/// fixed wall particles beyond, one constant smoothing length for all.
///
/// Their numbers: 70 x 70 = 4900 particles, a = 0.4, density 1, h giving 30 neighbours.  With
/// 70 rows of spacing \f$ \Delta = 1/70 \f$ centred on the origin, the rows nearest the plates
/// sit at \f$ y = \pm 0.393 \f$ (fluid) and \f$ \pm 0.407 \f$ (wall): the plate \f$ y = a \f$
/// lies half-way between them, 56 rows are fluid and 7 rows on each side are wall.
///
/// **The smoothing length.**  In 2D a particle at number density n has
/// \f$ N = \pi (2h)^2 n \f$ neighbours within its support 2h, so
/// \f$ h = \Delta\sqrt{N/4\pi} \f$: 1.545 \f$ \Delta \f$ for N = 30 (on the square lattice the
/// support then holds 28 neighbours, the lattice's nearest count to 30).

#include "sph/box.hpp"
#include "sph/error.hpp"
#include "sph/kernel.hpp"
#include "sph/particles.hpp"
#include "sph/setups/initial_conditions.hpp"

#include <cmath>
#include <numbers>
#include <vector>

namespace sph::setups {

/// What makes the channel.
struct PoiseuilleChannel {
  int side = 70;            ///< particles along each side of the unit square (Watkins: 70)
  double half_width = 0.4;  ///< a: fluid where \f$ |y| \le a \f$ (Watkins: 0.4)
  double neighbours = 30;   ///< N: the constant h is \f$ \Delta\sqrt{N/4\pi} \f$ (Watkins: 30)
  double density = 1;       ///< of fluid and wall alike (Watkins: 1)
  int wall_rows = 0;        ///< rows of wall particles on each side; 0: out to \f$ |y| = 1/2 \f$

  double spacing() const { return 1.0 / side; }
  double smoothing_length() const {
    return spacing() * std::sqrt(neighbours / (4 * std::numbers::pi));
  }

  /// The density the gather sum gives a particle of the lattice at rest far from the edges,
  /// with kernel K (the self term included): the rest density \f$ \rho_0 \f$ of a weakly
  /// compressible fluid on this lattice (1.0034 for Watkins' lattice and M4).
  template <class K>
  double lattice_density() const {
    const double dx = spacing(), h = smoothing_length();
    const int reach = static_cast<int>(std::ceil(K::support * h / dx));
    double sum = 0;
    for (int i = -reach; i <= reach; ++i)
      for (int j = -reach; j <= reach; ++j) sum += K::value(std::hypot(i * dx, j * dx), h);
    return density * dx * dx * sum;
  }

  /// The refusals: a channel too narrow for one fluid row, or walls that do not reach.
  void validate() const {
    require(side >= 4 && side <= 4000,
            "Poiseuille channel: the side must hold 4 to 4000 particles "
            "(got " +
                show(side) + ")");
    require(
        std::isfinite(half_width) && half_width > 0 && half_width < 0.5,
        "Poiseuille channel: the half-width a must lie in (0, 0.5) (got " + show(half_width) + ")");
    require(half_width >= spacing(), "Poiseuille channel: a = " + show(half_width) +
                                         " holds no fluid row at spacing " + show(spacing()));
    require(std::isfinite(neighbours) && neighbours >= 4 && neighbours <= 400,
            "Poiseuille channel: the neighbour number must lie in [4, 400] (got " +
                show(neighbours) + ")");
    require(std::isfinite(density) && density > 0,
            "Poiseuille channel: the density must be positive");
    for (int k = 0; k < side; ++k) {
      const double y = (k + 0.5) * spacing() - 0.5;
      require(std::abs(std::abs(y) - half_width) > 1e-9,
              "Poiseuille channel: a row of particles lies on the plate y = " + show(y) +
                  " (eq 17 of the walls has no answer there): choose another side or half-width");
    }
    require(wall_rows >= 0, "Poiseuille channel: the wall rows must be 0 (all) or more");
    require(wall_rows > 0 || 0.5 - half_width >= 2 * smoothing_length(),
            "Poiseuille channel: the walls (" + show(0.5 - half_width) +
                " thick) do not reach as far as the kernel (2h = " + show(2 * smoothing_length()) +
                "): use more particles a side, fewer neighbours or a narrower channel");
  }

  /// The particles at rest: fluid where \f$ |y| \le a \f$, fixed beyond (all of them, or
  /// `wall_rows` rows on each side).
  Particles<2> particles() const {
    validate();
    const double dx = spacing();
    const auto points = lattice<2>(LatticeType::cubic, Vec<2>(-0.5, -0.5), Vec<2>(0.5, 0.5),
                                   std::array<int, 2>{side, side});
    std::vector<Vec<2>> kept;
    std::vector<ParticleKind> kinds;
    for (const Vec<2>& x : points) {
      const double y = std::abs(x[1]);
      if (y <= half_width) {
        kept.push_back(x);
        kinds.push_back(ParticleKind::fluid);
      } else if (wall_rows == 0 || y <= half_width + wall_rows * dx) {
        kept.push_back(x);
        kinds.push_back(ParticleKind::fixed);
      }
    }
    Particles<2> p = make_particles<2>(kept, density * dx * dx);
    p.kind = kinds;
    for (double& h : p.smoothing_length) h = smoothing_length();
    return p;
  }

  /// Periodic in x over the unit square's width; open in y (the walls hold the fluid).
  static Box<2> box() {
    Box<2> b = Box<2>::periodic_box(Vec<2>(-0.5, -0.5), Vec<2>(0.5, 0.5));
    b.periodic[1] = false;
    return b;
  }
};

}  // namespace sph::setups
