#pragma once
/// \file
/// \brief The Sedov-Taylor blast: an energy E put into the few particles at the centre of a
/// cold, uniform gas, and the self-similar solution it should follow (sedov_solution.hpp).
///
/// **The gas.**  A cubic lattice of equal masses fills the periodic box
/// \f$ [-L, L]^D \f$ at density \f$ \rho_0 \f$ (a lattice rather than a glass: the blast is
/// strong enough to sweep the lattice's order away, and a glass of \f$ 32^3 \f$ particles costs
/// more to settle than the blast costs to run; the imprint of the lattice's axes on the shock
/// is visible as a scatter of the particles about the curve).  With an even number of cells the
/// centre falls between \f$ 2^D \f$ particles.  The masses are calibrated so that the SPH
/// density of the lattice is \f$ \rho_0 \f$ (the kernel sum over a lattice is biased by a few
/// per cent, chapter 2).  The gas is cold: a specific internal energy
/// \f$ u_0 \f$ so small that its pressure is \f$ 10^{-6} \f$ of the shock's by the end.
///
/// **The explosion.**  The energy E is shared among the particles within \f$ 2h_E \f$ of the
/// centre, in proportion to the kernel \f$ W(|\mathbf r_i|, h_E) \f$, with \f$ h_E \f$ the
/// smoothing length the lattice has at the scene's neighbour number (its \f$ 2h_E \f$ sphere
/// holds that many particles):
/// \f$ m_i \Delta u_i = E\, W(|\mathbf r_i|, h_E) / \sum_k W(|\mathbf r_k|, h_E) \f$.  The
/// explosion is then as point-like as the resolution allows, and the total energy is exactly
/// E plus the tiny thermal energy of the cold gas.  The solution forgets the size of the
/// region once the shock has swept a mass much larger than that of the heated particles.

#include "sph/box.hpp"
#include "sph/density.hpp"
#include "sph/eos.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/reference/sedov_solution.hpp"
#include "sph/setups/initial_conditions.hpp"

#include <cmath>

namespace sph {

/// What a Sedov blast is made of.
struct SedovSetup {
  double energy = 1.0;              ///< E, put into the central particles
  double density = 1.0;             ///< rho_0 of the uniform gas
  double gamma = 5.0 / 3.0;         ///< adiabatic index
  double background_energy = 1e-7;  ///< u_0, the cold gas's specific internal energy
  int cells = 32;                   ///< lattice cells along each axis
  double half_width = 0.5;          ///< the box is [-L, L]^D, periodic
};

/// A Sedov-Taylor blast ready to run: the particles, the box, and the solution it should
/// follow.
template <int D>
struct SedovBlast {
  Particles<D> particles;
  Box<D> box;
  SedovSolution exact;
  int heated = 0;        ///< particles that received a share of E
  double deposit_h = 0;  ///< h_E
  double spacing = 0;    ///< the lattice spacing
};

/// Build the blast of \p s for the smoothing-length rule \p rule (its neighbour number sets
/// h_E; the rule also calibrates the masses).
template <int D, class K = Kernel<D>>
SedovBlast<D> make_sedov_blast(const SedovSetup& s, const SmoothingLengthRule& rule,
                               DensityForm form = DensityForm::selhammar()) {
  require(s.cells >= 4, "Sedov blast: at least 4 lattice cells along each axis");
  require(s.half_width > 0 && std::isfinite(s.half_width),
          "Sedov blast: the box half-width must be positive");
  require(std::isfinite(s.background_energy) && s.background_energy > 0,
          "Sedov blast: the cold gas needs a positive internal energy u_0 (got " +
              show(s.background_energy) + ")");
  SedovBlast<D> blast{
      Particles<D>{}, Box<D>{}, SedovSolution(D, s.gamma, s.energy, s.density), 0, 0.0, 0.0};
  const Vec<D> lower = Vec<D>::Constant(-s.half_width), upper = Vec<D>::Constant(s.half_width);
  blast.box = Box<D>::periodic_box(lower, upper);
  std::array<int, D> cells{};
  cells.fill(s.cells);
  const auto points = lattice<D>(LatticeType::cubic, lower, upper, cells);
  blast.spacing = 2 * s.half_width / s.cells;
  double volume = 1;
  for (int a = 0; a < D; ++a) volume *= 2 * s.half_width;
  blast.particles =
      make_particles<D>(points, equal_mass(s.density, volume, points.size()), s.background_energy);
  Particles<D>& p = blast.particles;

  // The masses: the SPH density of the (uniform, periodic) lattice is rho_0.
  NeighbourSearch<D, K> search;
  search.update(p, blast.box, rule);
  compute_density<D, K>(p, search.list(), form);
  double mean = 0;
  for (double rho : p.density) mean += rho;
  mean /= static_cast<double>(p.size());
  for (double& m : p.mass) m *= s.density / mean;

  // The explosion: E shared in proportion to W(|r_i|, h_E).
  const double neighbours = rule.mode == SmoothingLengthRule::Mode::fixed ? 0 : rule.neighbours;
  blast.deposit_h =
      neighbours > 0
          ? 0.5 * root<D>(neighbours * std::pow(blast.spacing, D) / unit_ball_volume<D>())
          : p.smoothing_length[0];
  double weight_sum = 0;
  for (const auto& x : p.position) weight_sum += K::value(x.norm(), blast.deposit_h);
  require(weight_sum > 0, "Sedov blast: no particle within 2 h_E of the centre");
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double w = K::value(p.position[i].norm(), blast.deposit_h);
    if (w <= 0) continue;
    p.internal_energy[i] += s.energy * w / weight_sum / p.mass[i];
    ++blast.heated;
  }
  return blast;
}

}  // namespace sph
