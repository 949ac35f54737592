#pragma once
/// \file
/// \brief Two cold streams that collide head on: the test of particle penetration.
///
/// Two slabs of the same cold gas, each of length L, fill \f$ -L \le x < 0 \f$ and
/// \f$ 0 \le x < L \f$ and move towards each other at \f$ \pm v_0 \f$.  The gas is cold: its
/// sound speed is \f$ c_0 = v_0/\mathcal M \f$ with a Mach number \f$ \mathcal M \gg 1 \f$.  The
/// exact solution is the Riemann problem with \f$ u_L = +v_0 \f$, \f$ u_R = -v_0 \f$: two shocks
/// run outwards from x = 0 and leave the gas at rest between them; for a strong shock the
/// compression is \f$ (\gamma + 1)/(\gamma - 1) \f$ (4 for \f$ \gamma = 5/3 \f$) and the shocks
/// move at \f$ v_0 (\gamma - 1)/2 \f$.
///
/// This is the problem for which Monaghan & Gingold (1983) and Lattanzio et al. (1986) needed
/// the quadratic term of the artificial viscosity: without it, nothing but the tiny pressure of
/// the cold gas stands between the streams, and SPH particles can stream through each other.
///
/// The box is open along x (free ends: a cold gas barely expands in the time we run) and, in
/// 2D and 3D, periodic across the streams with the given width.  Particles sit on a cubic
/// lattice of equal masses \f$ \rho\,\Delta x^D \f$; the masses are not calibrated (the ends
/// are free, so there is no uniform interior to calibrate against far from them; the streams'
/// interiors have the nominal density to the accuracy of the kernel's lattice sum).

#include "sph/box.hpp"
#include "sph/eos.hpp"
#include "sph/particles.hpp"
#include "sph/reference/riemann.hpp"
#include "sph/setups/initial_conditions.hpp"

#include <cmath>
#include <string>

namespace sph {

/// What the two streams are made of.
struct CollidingStreamsSetup {
  double density = 1.0;        ///< rho of both streams
  double speed = 1.0;          ///< v0: each stream moves at this speed towards x = 0
  double mach = 10.0;          ///< v0 / c0 of the cold gas
  double gamma = 5.0 / 3.0;    ///< adiabatic index
  double spacing = 1.0 / 200;  ///< lattice spacing
  double length = 1.0;         ///< L, the length of each stream
  double width = 0.125;        ///< cross-section in 2D/3D (periodic)

  /// The sound speed c0 = v0 / Mach.
  double sound_speed() const { return speed / mach; }
  /// The pressure rho c0^2 / gamma that gives that sound speed.
  double pressure() const { return density * sound_speed() * sound_speed() / gamma; }
};

/// The particles, box and inflow parameters of two cold streams colliding head on (the
/// penetration test of chapters 3 and 5).
template <int D>
struct CollidingStreams {
  Particles<D> particles;
  Box<D> box;
  RiemannSolution exact;  ///< two shocks running out from x = 0
  int left_count = 0;     ///< particles 0 .. left_count-1 form the stream moving right
};

/// Build the two streams: the right-moving stream first (x < 0), then the left-moving one.
template <int D>
CollidingStreams<D> make_colliding_streams(const CollidingStreamsSetup& s) {
  require(s.density > 0 && s.speed > 0 && s.mach > 0 && std::isfinite(s.mach),
          "colliding streams: density, speed and Mach number must be positive and finite");
  require(s.spacing > 0 && s.length > 0 && s.width > 0,
          "colliding streams: spacing, length and width must be positive");
  require(s.spacing <= 0.1 * s.length,
          "colliding streams: the spacing must be at most a tenth of the stream length");
  const GasState left{s.density, s.speed, s.pressure()}, right{s.density, -s.speed, s.pressure()};
  CollidingStreams<D> streams{Particles<D>{}, Box<D>{}, RiemannSolution(left, right, s.gamma), 0};
  // Open along x, periodic across.
  Vec<D> lower = Vec<D>::Zero(), upper = Vec<D>::Constant(s.width);
  lower[0] = -s.length;
  upper[0] = s.length;
  streams.box = Box<D>{lower, upper, {}};
  for (int a = 1; a < D; ++a) streams.box.periodic[a] = true;
  // Two mirror-image lattices (the spacing rounded so that whole cells fill each stream) of
  // equal masses: each particle carries the stream's mass divided by its particle number.
  Vec<D> middle_low = lower, middle_high = upper;
  middle_low[0] = middle_high[0] = 0.0;
  const auto left_points = lattice<D>(LatticeType::cubic, lower, middle_high, s.spacing);
  const auto right_points = lattice<D>(LatticeType::cubic, middle_low, upper, s.spacing);
  double volume = s.length;
  for (int a = 1; a < D; ++a) volume *= s.width;
  const double mass = s.density * volume / static_cast<double>(left_points.size());
  const double u = IdealGas(s.gamma).internal_energy(s.density, s.pressure());
  for (const auto& x : left_points) streams.particles.add(x, s.speed * Vec<D>::Unit(0), mass, u);
  streams.left_count = static_cast<int>(left_points.size());
  for (const auto& x : right_points) streams.particles.add(x, -s.speed * Vec<D>::Unit(0), mass, u);
  return streams;
}

}  // namespace sph
