// The reflecting sphere (Watkins et al. 1996, sect. 4.4): a bounce that is exactly a mirror
// image, conserves what an elastic wall must conserve, holds a hot gas, and stops with a
// message -- never a crash -- when a particle cannot be brought back.
#include "sph/boundaries/reflecting_sphere.hpp"
#include "sph/measures/diagnostics.hpp"
#include "sph/setups/initial_conditions.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/pressure.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>

namespace {

// Free particles inside a unit sphere: no terms, no forces, only the wall.
struct FreeInSphere : sph::Scene<3> {
  using Boundaries = sph::ReflectingSphere<3>;
};

// A gas inside the sphere.
struct GasInSphere : sph::Scene<3> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983>;
  using Boundaries = sph::ReflectingSphere<3>;
};

sph::Settings fixed_step(double dt) {
  sph::Settings s;
  s.fixed_timestep = dt;
  return s;
}

}  // namespace

TEST_CASE("a particle bounces off the reflecting sphere as its mirror image", "[boundaries]") {
  sph::Particles<3> p;
  p.add(sph::Vec<3>::Zero(), sph::Vec<3>(1.0, 0.0, 0.0), 1.0);
  const sph::ReflectingSphere<3> wall(sph::Vec<3>::Zero(), 1.0);
  sph::Simulation<FreeInSphere> sim(p, sph::Box<3>::open(), wall, fixed_step(0.1));
  sim.run_until(1.55);
  // It reached the wall at t = 1 and has come back 0.55: at x = 0.45, moving at -1.  The
  // bounce is exact up to the round-off of sixteen steps of 0.1 (a few ulps).
  const sph::Vec<3> x = sim.particles().position[0], v = sim.particles().velocity[0];
  INFO("x = " << x.transpose() << ", v = " << v.transpose());
  CHECK(std::abs(x[0] - 0.45) <= 1e-14);
  CHECK(std::abs(v[0] + 1.0) == 0.0);
  CHECK(x.tail<2>().norm() == 0.0);
}

TEST_CASE("bounces off the sphere keep the speed and the angular momentum about its centre",
          "[boundaries]") {
  // Oblique paths that hit the wall many times.  The wall's kick is radial, at the point where
  // the path crossed it, so |v| and r x v are kept exactly in exact arithmetic; we allow the
  // round-off of a thousand steps (measured 2e-15).
  sph::Particles<3> p;
  p.add(sph::Vec<3>(0.1, -0.2, 0.3), sph::Vec<3>(0.7, 0.4, -0.2), 1.0);
  p.add(sph::Vec<3>(-0.5, 0.1, 0.0), sph::Vec<3>(-0.3, 0.9, 0.5), 2.0);
  sph::Simulation<FreeInSphere> sim(
      p, sph::Box<3>::open(), sph::ReflectingSphere<3>(sph::Vec<3>::Zero(), 1.0), fixed_step(0.01));
  const auto L = [&](std::size_t i) {
    return sim.particles().position[i].cross(sim.particles().velocity[i]).eval();
  };
  const sph::Vec<3> L0 = L(0), L1 = L(1);
  const double e0 = sph::kinetic_energy(sim.particles());
  double farthest = 0;
  sim.run_until(10.0, [&](const auto& s) {
    for (const auto& x : s.particles().position) farthest = std::max(farthest, x.norm());
  });
  const double de = std::abs(sph::kinetic_energy(sim.particles()) - e0) / e0;
  const double dl = std::max((L(0) - L0).norm() / L0.norm(), (L(1) - L1).norm() / L1.norm());
  INFO("relative change of kinetic energy " << de << ", of angular momentum " << dl << ", farthest "
                                            << farthest);
  CHECK(de <= 1e-13);
  CHECK(dl <= 1e-12);
  CHECK(farthest <= 1.0);
}

TEST_CASE("a hot gas stays inside the reflecting sphere and keeps its energy", "[boundaries]") {
  // A hot ball of gas, radius 0.5, expands into the empty sphere of radius 1 and bounces off
  // its wall.  Every particle must stay inside; energy is conserved to the integrator's
  // accuracy (the wall does no work): measured 2.4e-3 at t = 1 (the gas has met the wall and
  // come back), allowed 1e-2.
  auto points = sph::cut_sphere<3>(
      sph::lattice<3>(sph::LatticeType::body_centred, sph::Vec<3>::Constant(-0.5),
                      sph::Vec<3>::Constant(0.5), 0.1),
      sph::Vec<3>::Zero(), 0.5);
  const auto particles =
      sph::make_particles<3>(points, 1.0 / static_cast<double>(points.size()), 1.0);
  sph::Settings settings;
  settings.smoothing = sph::SmoothingLengthRule::neighbour_number(40, 2);
  sph::Simulation<GasInSphere> sim(particles, sph::Box<3>::open(), sph::IdealGas(5.0 / 3.0),
                                   sph::MonaghanGingold1983{1.0, 2.0},
                                   sph::ReflectingSphere<3>(sph::Vec<3>::Zero(), 1.0), settings);
  const auto energy = [](const sph::Particles<3>& q) {
    return sph::kinetic_energy(q) + sph::thermal_energy(q);
  };
  const double e0 = energy(sim.particles());
  double farthest = 0;
  sim.run_until(1.0, [&](const auto& s) {
    for (const auto& x : s.particles().position) farthest = std::max(farthest, x.norm());
  });
  const double de = std::abs(energy(sim.particles()) - e0) / e0;
  INFO(points.size() << " particles, " << sim.steps() << " steps, energy change " << de
                     << ", farthest " << farthest);
  CHECK(farthest <= 1.0);
  CHECK(farthest > 0.9);  // the gas did reach the wall
  CHECK(de <= 1e-2);
}

TEST_CASE("the reflecting sphere stops with a message, not a crash", "[boundaries]") {
  SECTION("a particle that starts outside") {
    sph::Particles<3> p;
    p.add(sph::Vec<3>(0.0, 0.0, 1.5), sph::Vec<3>::Zero(), 1.0);
    CHECK_THROWS_WITH((sph::Simulation<FreeInSphere>(
                          p, sph::Box<3>::open(),
                          sph::ReflectingSphere<3>(sph::Vec<3>::Zero(), 1.0), fixed_step(0.1))),
                      Catch::Contains("particle 0") && Catch::Contains("outside"));
  }
  SECTION("a step that carries a particle more than the radius past the wall") {
    sph::Particles<3> p;
    p.add(sph::Vec<3>::Zero(), sph::Vec<3>(100.0, 0.0, 0.0), 1.0);
    sph::Simulation<FreeInSphere> sim(p, sph::Box<3>::open(),
                                      sph::ReflectingSphere<3>(sph::Vec<3>::Zero(), 1.0),
                                      fixed_step(0.1));
    CHECK_THROWS_WITH(sim.step(), Catch::Contains("particle 0") && Catch::Contains("too long"));
  }
  SECTION("an impossible radius") {
    CHECK_THROWS_WITH(sph::ReflectingSphere<3>(sph::Vec<3>::Zero(), -1.0),
                      Catch::Contains("radius"));
  }
}
