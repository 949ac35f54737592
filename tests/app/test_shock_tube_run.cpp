// The shock-tube runner: a boosted tube is compared in the frame that moves with it, an end
// time past the exact solution's validity is refused with a message that names the times, and a
// walled tube counts the momentum its walls take up.
#include "app/shock_tube_run.hpp"
#include "sph/boundaries/fixed_particles.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/pressure.hpp"

#include <catch2/catch.hpp>

namespace {

struct Gas : sph::Scene<1> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983>;
};

app::TubeRun<1> run(const sph::ShockTubeSetup& setup, double t_end) {
  return app::run_shock_tube<Gas>(setup, sph::SmoothingLengthRule::from_density(4),
                                  {{}, sph::MonaghanGingold1983(1, 2)},
                                  {.t_end = t_end,
                                   .timestep_rule = sph::Settings::TimestepRule::signal_velocity,
                                   .report = app::RunReport::none});
}

struct WalledGas : Gas {
  using Boundaries = sph::FixedParticles;
};

}  // namespace

TEST_CASE("a boosted tube is measured in the frame moving with it", "[shock_tube_run]") {
  sph::ShockTubeSetup sod = sph::ShockTubeSetup::sod();
  sod.left_spacing = 1.0 / 400;
  sph::ShockTubeSetup boosted = sod;
  boosted.left.velocity = boosted.right.velocity = 10;  // a full period in t = 0.2
  const auto rest = run(sod, 0.2);
  const auto moving = run(boosted, 0.2);
  CHECK(moving.frame_velocity == 10);
  CHECK(moving.exact.left_state().velocity == 0);
  CHECK(moving.steps == rest.steps);
  const auto e_rest = sph::shock_tube_errors(rest.particles, rest.exact, 0.2);
  const auto e_moving = sph::shock_tube_errors(moving.particles, moving.exact, 0.2);
  CHECK(e_moving[0].count == e_rest[0].count);
  CHECK(e_moving[0].L1 == Approx(e_rest[0].L1).epsilon(0.01));
  CHECK(e_moving[1].L1 == Approx(e_rest[1].L1).epsilon(0.01));
  CHECK(e_moving[0].L1 < 0.005);  // not the 0.25 of a comparison in the wrong frame
}

TEST_CASE("an end time past the exact solution's validity is refused", "[shock_tube_run]") {
  sph::ShockTubeSetup strong = sph::ShockTubeSetup::sod();
  strong.left_spacing = 1.0 / 100;
  strong.left.pressure = 1e5;
  strong.right.pressure = 1;
  CHECK_THROWS_WITH(run(strong, 0.2), Catch::Contains("no exact solution") &&
                                          Catch::Contains("periodic end at t = 0.00"));
  // Sod's own tube past t = 0.285, when the far interface's shock reaches the window.
  sph::ShockTubeSetup sod = sph::ShockTubeSetup::sod();
  sod.left_spacing = 1.0 / 100;
  CHECK_THROWS_WITH(run(sod, 0.3), Catch::Contains("t = 0.285"));
  CHECK_NOTHROW(run(sod, 0.28));
}

TEST_CASE("a walled tube conserves momentum with the walls' impulse counted", "[shock_tube_run]") {
  sph::ShockTubeSetup sod = sph::ShockTubeSetup::sod();
  sod.left_spacing = 1.0 / 400;
  sod.ends = sph::ShockTubeSetup::Ends::walls;
  sod.half_length = 0.5;
  const auto walled = app::run_shock_tube<WalledGas>(
      sod, sph::SmoothingLengthRule::from_density(4), {{}, sph::MonaghanGingold1983(1, 2)},
      {.t_end = 0.2, .report = app::RunReport::none});
  // The walls push on the gas with the two pressures while no wave has reached them: at
  // h = dx the lattice's gradient sum is exact, and the push is (p_L - p_R) t (measured: to
  // 2.5e-7 of itself; the count of the walls' own impulse is exact, the next check).
  INFO("walls' impulse " << walled.wall_impulse << ", momentum drift " << walled.momentum_drift);
  CHECK(-walled.wall_impulse == Approx(0.9 * 0.2).epsilon(1e-5));
  CHECK(walled.momentum_drift < 1e-12);
  // A periodic tube has no walls: nothing is counted.
  sph::ShockTubeSetup periodic = sph::ShockTubeSetup::sod();
  periodic.left_spacing = 1.0 / 400;
  const auto open = run(periodic, 0.2);
  CHECK(open.wall_impulse == 0);
  CHECK(open.momentum_drift < 1e-12);
}
