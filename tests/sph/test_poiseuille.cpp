// Plane Poiseuille flow (sph/reference/poiseuille.hpp): the steady profile of Watkins et al.
// (1996) eq 15, and the flow from rest checked against what defines it -- the diffusion
// equation with a source, the walls, the start at rest and the end at eq 15 -- rather than
// against numbers copied from elsewhere.
#include "sph/error.hpp"
#include "sph/reference/poiseuille.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace {

// Watkins et al.'s flow: a = 0.4, g = 3.6, mu_s = 0.15 with rho = 1.
sph::PoiseuilleFlow watkins() { return sph::PoiseuilleFlow(0.4, 3.6, 0.15); }

}  // namespace

TEST_CASE("Poiseuille: the steady profile is eq 15, 1.92 on the axis of Watkins' flow",
          "[poiseuille]") {
  const auto flow = watkins();
  CHECK(flow.axis_speed() == Approx(1.92).epsilon(1e-14));
  CHECK(flow.steady(0.0) == Approx(1.92).epsilon(1e-14));
  CHECK(flow.steady(0.4) == 0.0);
  CHECK(flow.steady(-0.4) == 0.0);
  CHECK(flow.steady(0.5) == 0.0);  // beyond the plates: the walls' rest
  CHECK(flow.steady(0.2) == Approx(3.6 * (0.16 - 0.04) / 0.3).epsilon(1e-14));
  CHECK(flow.steady(-0.3) == flow.steady(0.3));
  CHECK(flow.settling_time() == Approx(4 * 0.16 / (std::numbers::pi * std::numbers::pi * 0.15)));
}

TEST_CASE("Poiseuille: the flow from rest starts at rest and ends at eq 15", "[poiseuille]") {
  const auto flow = watkins();
  // At t = 0 the series is the cosine series of the parabola: it must cancel it everywhere.
  // The terms fall as 1/k^3 and the sum stops at a term of 1e-10 of the axis speed; the tail
  // it leaves, of changing signs, stays below 1e-8 of it (measured: 1e-9).
  double worst_start = 0, worst_end = 0;
  for (int k = -40; k <= 40; ++k) {
    const double y = 0.4 * k / 40.0;
    worst_start = std::max(worst_start, std::abs(flow.from_rest(y, 0.0)));
    worst_end = std::max(worst_end,
                         std::abs(flow.from_rest(y, 30 * flow.settling_time()) - flow.steady(y)));
  }
  INFO("largest |v| at t = 0: " << worst_start << "; from eq 15 at 30 t_nu: " << worst_end);
  CHECK(worst_start < 1e-8 * flow.axis_speed());
  // After 30 t_nu the slowest mode is down by e^-30, 1e-13.
  CHECK(worst_end < 1e-12 * flow.axis_speed());
}

TEST_CASE("Poiseuille: the flow from rest solves dv/dt = g + nu d2v/dy2 with v = 0 at the walls",
          "[poiseuille]") {
  const auto flow = watkins();
  const double nu = flow.kinematic_viscosity(), g = flow.acceleration();
  // Central differences of the series, at times when every mode still matters and later.
  // Their own errors are about step^2 times the fourth derivatives, 1e-6 of g with these steps
  // (the steps are far above the series' rounding, 1e-15 of the axis speed / step^2 = 1e-9 of g).
  const double dt = 1e-4, dy = 1e-3;
  double worst = 0;
  for (double t : {0.05, 0.2, 0.5, 1.5}) {
    for (double y : {-0.35, -0.2, 0.0, 0.1, 0.3}) {
      const double dvdt =
          (flow.from_rest(y, t + dt, 1e-14) - flow.from_rest(y, t - dt, 1e-14)) / (2 * dt);
      const double d2vdy2 = (flow.from_rest(y + dy, t, 1e-14) - 2 * flow.from_rest(y, t, 1e-14) +
                             flow.from_rest(y - dy, t, 1e-14)) /
                            (dy * dy);
      worst = std::max(worst, std::abs(dvdt - g - nu * d2vdy2));
    }
  }
  INFO("largest |dv/dt - g - nu v''| = " << worst << " (g = " << g << ")");
  CHECK(worst < 1e-4 * g);
  // The walls hold: v = 0 at y = +-a at every time, and just inside it is small.
  CHECK(flow.from_rest(0.4, 0.3) == 0.0);
  CHECK(std::abs(flow.from_rest(0.4 - 1e-9, 0.3)) < 1e-7);
}

TEST_CASE("Poiseuille: late in the start-up one mode is left, decaying over t_nu", "[poiseuille]") {
  const auto flow = watkins();
  const double t_nu = flow.settling_time(), pi = std::numbers::pi;
  // v_inf - v on the axis -> (32/pi^3) v_axis exp(-t/t_nu); the next mode is exp(-9 t/t_nu)/27,
  // below 1e-8 of it from t = 2 t_nu.
  for (double t : {2 * t_nu, 3 * t_nu, 5 * t_nu}) {
    const double lag = flow.axis_speed() - flow.from_rest(0.0, t);
    const double one_mode = 32 / (pi * pi * pi) * flow.axis_speed() * std::exp(-t / t_nu);
    CHECK(lag == Approx(one_mode).epsilon(1e-6));
  }
  // After 5 t_nu the axis is within 0.7 % of its final speed, as the header says.
  CHECK(flow.from_rest(0.0, 5 * t_nu) > 0.993 * flow.axis_speed());
  CHECK(flow.from_rest(0.0, 5 * t_nu) < flow.axis_speed());
}

TEST_CASE("Poiseuille: impossible parameters are refused by name", "[poiseuille]") {
  CHECK_THROWS_WITH(sph::PoiseuilleFlow(0.0, 3.6, 0.15), Catch::Contains("half-width"));
  CHECK_THROWS_WITH(sph::PoiseuilleFlow(0.4, 3.6, -1.0), Catch::Contains("kinematic viscosity"));
  CHECK_THROWS_WITH(sph::PoiseuilleFlow(0.4, NAN, 0.15), Catch::Contains("acceleration"));
  const auto flow = watkins();
  CHECK_THROWS_WITH(flow.from_rest(0.0, -1.0), Catch::Contains("starts at t = 0"));
  CHECK_THROWS_WITH(flow.from_rest(NAN, 1.0), Catch::Contains("must be finite"));
  CHECK_THROWS_AS(flow.steady(INFINITY), sph::Error);
}
