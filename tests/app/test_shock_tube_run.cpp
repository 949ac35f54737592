// The shock-tube runner: a boosted tube is compared in the frame that moves with it, and an end
// time past the exact solution's validity is refused with a message that names the times.
#include "app/shock_tube_run.hpp"
#include "sph/terms/pressure.hpp"
#include "sph/viscosity/monaghan_gingold_1983.hpp"

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
