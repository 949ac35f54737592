// The ends of a shock tube: periodic (the far interface at x = ±L) or closed by walls of fixed
// particles.  A walled tube of the window's length gives the same answer in the window as the
// periodic tube twice its length, and the exact solution's validity is known for both.
#include "sph/boundaries/fixed_particles.hpp"
#include "sph/setups/shock_tube.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/pressure.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace {

struct PeriodicGas : sph::Scene<1> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983>;
};
struct WalledGas : PeriodicGas {
  using Boundaries = sph::FixedParticles;
};

template <class Scene>
std::pair<std::vector<sph::ErrorNorms>, long> run(const sph::ShockTubeSetup& setup) {
  const auto smoothing = sph::SmoothingLengthRule::from_density(4);
  const sph::ShockTube<1> tube = sph::make_shock_tube<1>(setup, smoothing);
  sph::Settings settings;
  settings.smoothing = smoothing;
  settings.timestep_rule = sph::Settings::TimestepRule::signal_velocity;
  settings.courant = 0.6;
  sph::Simulation<Scene> sim(tube.particles, tube.box, sph::IdealGas(1.4),
                             sph::MonaghanGingold1983(1, 2), settings);
  sim.run_until(0.2);
  return {sph::shock_tube_errors(sim.particles(), tube.exact, 0.2), sim.steps()};
}

}  // namespace

TEST_CASE("a tube closed by walls holds only the window and gives the same answer in it",
          "[shock_tube]") {
  sph::ShockTubeSetup periodic = sph::ShockTubeSetup::sod();
  periodic.left_spacing = 1.0 / 800;
  sph::ShockTubeSetup walled = periodic;
  walled.ends = sph::ShockTubeSetup::Ends::walls;
  walled.half_length = 0.5;
  const auto tube = sph::make_shock_tube<1>(walled, sph::SmoothingLengthRule::from_density(4));
  std::size_t fluid = 0, fixed = 0;
  for (std::size_t i = 0; i < tube.particles.size(); ++i) {
    const bool is_fixed = tube.particles.kind[i] == sph::ParticleKind::fixed;
    fixed += is_fixed;
    fluid += !is_fixed;
    CHECK(is_fixed == (std::abs(tube.particles.position[i][0]) > 0.5));
  }
  CHECK(fluid == 450);  // 400 on the dense side, 50 on the thin
  CHECK(fixed == 2u * walled.wall_cells);
  CHECK_FALSE(tube.box.periodic[0]);

  const auto [with_period, steps_period] = run<PeriodicGas>(periodic);
  const auto [with_walls, steps_walls] = run<WalledGas>(walled);
  CHECK(with_walls[0].count == with_period[0].count);
  CHECK(steps_walls == steps_period);
  for (int q = 0; q < 3; ++q) {
    INFO(with_walls[q].quantity);
    CHECK(with_walls[q].L1 == Approx(with_period[q].L1).epsilon(1e-4));
  }
}

TEST_CASE("a walled tube refuses moving gas and a scene without fixed particles", "[shock_tube]") {
  sph::ShockTubeSetup walled = sph::ShockTubeSetup::sod();
  walled.left_spacing = 1.0 / 200;
  walled.ends = sph::ShockTubeSetup::Ends::walls;
  walled.half_length = 0.5;
  walled.left.velocity = 0.5;
  const auto rule = sph::SmoothingLengthRule::from_density(4);
  CHECK_THROWS_WITH(sph::make_shock_tube<1>(walled, rule), Catch::Contains("at rest"));
  walled.left.velocity = 0;
  const auto tube = sph::make_shock_tube<1>(walled, rule);
  CHECK_THROWS_WITH((sph::Simulation<PeriodicGas>(tube.particles, tube.box)),
                    Catch::Contains("FixedParticles"));
}

TEST_CASE("how long the exact solution describes the window", "[shock_tube]") {
  sph::ShockTubeSetup sod = sph::ShockTubeSetup::sod();
  const double shock = sph::RiemannSolution(sod.left, sod.right, 1.4).right_wave().head_speed;
  // Periodic, L = 1: the far interface's shock (the same speed, mirrored) reaches x = 0.5, and
  // meets the central shock there, at 0.5 / 1.75.
  const sph::ExactValidity periodic = sph::exact_solution_validity(sod);
  CHECK(periodic.until == Approx(0.5 / shock));
  CHECK(periodic.end_reached == Approx(1.0 / shock));
  CHECK(periodic.frame_velocity == 0);
  CHECK_THAT(periodic.reason, Catch::Contains("periodic end"));
  // Boosted as a whole: the same, in the moving frame.
  sph::ShockTubeSetup boosted = sod;
  boosted.left.velocity = boosted.right.velocity = 10;
  const sph::ExactValidity moving = sph::exact_solution_validity(boosted);
  CHECK(moving.frame_velocity == 10);
  CHECK(moving.until == Approx(periodic.until));
  // Walls at |x| = 0.5: the shock reaches the wall at the same time.
  sph::ShockTubeSetup walled = sod;
  walled.ends = sph::ShockTubeSetup::Ends::walls;
  walled.half_length = 0.5;
  const sph::ExactValidity wall = sph::exact_solution_validity(walled);
  CHECK(wall.until == Approx(0.5 / shock));
  CHECK_THAT(wall.reason, Catch::Contains("wall"));
  // A pressure ratio of 1e5: the rarefaction's head (sound speed 374) crosses the tube in
  // milliseconds.
  sph::ShockTubeSetup strong = sod;
  strong.left.pressure = 1e5;
  strong.right.pressure = 1;
  const sph::ExactValidity fast = sph::exact_solution_validity(strong);
  CHECK(fast.until < 0.005);
  CHECK(fast.end_reached < 0.005);
  // Colliding gases: the far interface opens a vacuum (no star state), its fans' heads count.
  sph::ShockTubeSetup colliding = sod;
  colliding.right = colliding.left;
  // (at 7 each way they separate faster than 2(c_L + c_R)/(gamma - 1) = 11.8)
  colliding.left.velocity = 7;
  colliding.right.velocity = -7;
  CHECK_THROWS(sph::RiemannSolution(colliding.right, colliding.left, 1.4));
  const sph::ExactValidity collide = sph::exact_solution_validity(colliding);
  CHECK(collide.until > 0);
  CHECK(collide.until == Approx(0.5 / (7 + std::sqrt(1.4))));
}
