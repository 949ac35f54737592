// Tests of the exact Riemann solver (lib/sph/reference/riemann.hpp) against Toro (2009) Table 4.2,
// the two shock tubes of the papers, and the physics every solution must obey: Rankine-Hugoniot
// jumps across shocks, isentropy and the Riemann invariant through fans, continuity, conservation,
// symmetry and Galilean invariance.
//
// Tolerance policy: relative error with an absolute floor (Catch's Approx epsilon + margin);
// a NaN never compares equal.  The reference values of Toro's Table 4.2 are printed to 5-6
// significant figures, hence 1e-5.

#include "sph/reference/riemann.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

using sph::GasState;
using sph::RiemannSolution;
using sph::WaveKind;

namespace {

/// Relative 1e-5 with an absolute floor of 1e-5: the precision of the published tables.
Approx table_value(double expected) { return Approx(expected).epsilon(1e-5).margin(1e-5); }

/// Conserved densities (mass, momentum, energy) and their fluxes of a state.
struct Conserved {
  double mass, momentum, energy;
};
Conserved densities(const GasState& w, double gamma) {
  const double E = w.pressure / (gamma - 1.0) + 0.5 * w.density * w.velocity * w.velocity;
  return {w.density, w.density * w.velocity, E};
}
Conserved fluxes(const GasState& w, double gamma) {
  const Conserved U = densities(w, gamma);
  return {U.momentum, U.momentum * w.velocity + w.pressure, (U.energy + w.pressure) * w.velocity};
}

/// Largest relative Rankine-Hugoniot residual across a discontinuity moving at speed S:
/// F(b) - F(a) = S (U(b) - U(a)) for mass, momentum and energy.
double rankine_hugoniot_residual(const GasState& a, const GasState& b, double S, double gamma) {
  const Conserved Ua = densities(a, gamma), Ub = densities(b, gamma);
  const Conserved Fa = fluxes(a, gamma), Fb = fluxes(b, gamma);
  const auto residual = [](double dF, double dU, double S_, double scale) {
    return std::abs(dF - S_ * dU) / scale;
  };
  const double scale_mass = std::abs(Fa.mass) + std::abs(S * Ua.mass) + 1e-300;
  const double scale_momentum =
      std::abs(Fa.momentum) + std::abs(S * Ua.momentum) + a.pressure + 1e-300;
  const double scale_energy =
      std::abs(Fa.energy) + std::abs(S * Ua.energy) + std::abs(Fb.energy) + 1e-300;
  return std::max(
      {residual(Fb.mass - Fa.mass, Ub.mass - Ua.mass, S, scale_mass),
       residual(Fb.momentum - Fa.momentum, Ub.momentum - Ua.momentum, S, scale_momentum),
       residual(Fb.energy - Fa.energy, Ub.energy - Ua.energy, S, scale_energy)});
}

/// Toro's five tests (Table 4.1) with his exact star states (Table 4.2), gamma = 1.4.
struct ToroTest {
  const char* name;
  GasState left, right;
  double p_star, u_star, rho_star_left, rho_star_right;
  WaveKind left_kind, right_kind;
};
const std::vector<ToroTest> toro_tests = {
    {"Test 1 (Sod)",
     {1.0, 0.0, 1.0},
     {0.125, 0.0, 0.1},
     0.30313,
     0.92745,
     0.42632,
     0.26557,
     WaveKind::rarefaction,
     WaveKind::shock},
    {"Test 2 (123 problem, near vacuum)",
     {1.0, -2.0, 0.4},
     {1.0, 2.0, 0.4},
     0.00189,
     0.00000,
     0.02185,
     0.02185,
     WaveKind::rarefaction,
     WaveKind::rarefaction},
    {"Test 3 (strong right shock)",
     {1.0, 0.0, 1000.0},
     {1.0, 0.0, 0.01},
     460.894,
     19.5975,
     0.57506,
     5.99924,
     WaveKind::rarefaction,
     WaveKind::shock},
    {"Test 4 (strong left shock)",
     {1.0, 0.0, 0.01},
     {1.0, 0.0, 100.0},
     46.0950,
     -6.19633,
     5.99242,
     0.57511,
     WaveKind::shock,
     WaveKind::rarefaction},
    {"Test 5 (two colliding shocks)",
     {5.99924, 19.5975, 460.894},
     {5.99242, -6.19633, 46.0950},
     1691.64,
     8.68975,
     14.2823,
     31.0426,
     WaveKind::shock,
     WaveKind::shock},
};

/// Midpoint-rule integral of g(x) over [a, b] with n cells.
template <class G>
double integrate(G g, double a, double b, int n) {
  const double dx = (b - a) / n;
  double sum = 0;
  for (int k = 0; k < n; ++k) sum += g(a + (k + 0.5) * dx);
  return sum * dx;
}

}  // namespace

TEST_CASE("Sod shock tube: star state", "[riemann]") {
  const RiemannSolution sod({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
  CHECK(sod.star_pressure() == table_value(0.30313));
  CHECK(sod.star_velocity() == table_value(0.92745));
  CHECK(sod.star_density_left() == table_value(0.42632));
  CHECK(sod.star_density_right() == table_value(0.26557));
  CHECK(sod.left_wave().kind == WaveKind::rarefaction);
  CHECK(sod.right_wave().kind == WaveKind::shock);
  // The positions at t = 0.2 that every Sod plot shows.
  CHECK(sod.shock_position(0.2) == Approx(1.75216 * 0.2).epsilon(1e-5));
  CHECK(sod.contact_position(0.2) == Approx(0.92745 * 0.2).epsilon(1e-5));
  CHECK(sod.rarefaction_head_position(0.2) == Approx(-std::sqrt(1.4) * 0.2).epsilon(1e-12));
}

TEST_CASE("Monaghan & Gingold (1983) tube of Watkins et al. section 4.3: star state", "[riemann]") {
  const RiemannSolution tube({1.0, 0.0, 1.0}, {0.25, 0.0, 0.1795}, 1.4);
  CHECK(tube.star_pressure() == table_value(0.42935));
  CHECK(tube.star_velocity() == table_value(0.67310));
  CHECK(tube.left_wave().kind == WaveKind::rarefaction);
  CHECK(tube.right_wave().kind == WaveKind::shock);
}

TEST_CASE("Toro's tests 1-5: star states of Table 4.2 and wave patterns", "[riemann]") {
  for (const ToroTest& test : toro_tests) {
    SECTION(test.name) {
      const RiemannSolution s(test.left, test.right, 1.4);
      INFO(s.describe() << " (" << s.iterations() << " iterations)");
      CHECK(s.star_pressure() == table_value(test.p_star));
      CHECK(s.star_velocity() == table_value(test.u_star));
      CHECK(s.star_density_left() == table_value(test.rho_star_left));
      CHECK(s.star_density_right() == table_value(test.rho_star_right));
      CHECK(s.left_wave().kind == test.left_kind);
      CHECK(s.right_wave().kind == test.right_kind);
      CHECK(s.iterations() <= 10);
    }
  }
}

TEST_CASE("Rankine-Hugoniot conditions hold across every shock", "[riemann]") {
  const double gamma = 1.4, t = 0.1, eps = 1e-9;
  double worst = 0;
  for (const ToroTest& test : toro_tests) {
    const RiemannSolution s(test.left, test.right, gamma);
    for (const sph::Wave* wave : {&s.left_wave(), &s.right_wave()}) {
      if (wave->kind != WaveKind::shock) continue;
      const double x = s.position(wave->head_speed, t);
      const GasState before = s.sample(x - eps, t), after = s.sample(x + eps, t);
      worst = std::max(worst, rankine_hugoniot_residual(before, after, wave->head_speed, gamma));
    }
    // The contact: pressure and velocity continuous, density jumps.
    const double xc = s.contact_position(t);
    const GasState l = s.sample(xc - eps, t), r = s.sample(xc + eps, t);
    CHECK(l.pressure == Approx(r.pressure).epsilon(1e-12));
    CHECK(l.velocity == Approx(r.velocity).epsilon(1e-12).margin(1e-12));
  }
  INFO("worst relative Rankine-Hugoniot residual " << worst);
  CHECK(worst < 1e-12);
}

TEST_CASE("Rarefaction fans: continuous edges, u - c = x/t, Riemann invariant, isentrope",
          "[riemann]") {
  const double gamma = 1.4, t = 0.25;
  const RiemannSolution sod({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, gamma);
  const GasState L = sod.left_state();
  const double cL = sph::sound_speed(L, gamma);
  const double invariant = L.velocity + 2.0 * cL / (gamma - 1.0);
  const double entropy = L.pressure / std::pow(L.density, gamma);
  const double head = sod.rarefaction_head_position(t), tail = sod.rarefaction_tail_position(t);

  SECTION("continuous at the head and the tail") {
    for (double edge : {head, tail}) {
      const GasState a = sod.sample(edge - 1e-10, t), b = sod.sample(edge + 1e-10, t);
      CHECK(a.density == Approx(b.density).epsilon(1e-8));
      CHECK(a.velocity == Approx(b.velocity).epsilon(1e-8).margin(1e-8));
      CHECK(a.pressure == Approx(b.pressure).epsilon(1e-8));
    }
  }
  SECTION("inside the fan") {
    for (int k = 1; k < 10; ++k) {
      const double x = head + (tail - head) * k / 10.0;
      const GasState w = sod.sample(x, t);
      const double c = sph::sound_speed(w, gamma);
      // The left fan is made of C- characteristics: dx/dt = u - c = x/t.
      CHECK(w.velocity - c == Approx(x / t).epsilon(1e-12));
      // The C+ Riemann invariant u + 2c/(gamma-1) is carried in from the left state.
      CHECK(w.velocity + 2.0 * c / (gamma - 1.0) == Approx(invariant).epsilon(1e-12));
      // The flow is isentropic.
      CHECK(w.pressure / std::pow(w.density, gamma) == Approx(entropy).epsilon(1e-12));
    }
  }
}

TEST_CASE("Sod: mass, momentum and energy are conserved over the tube", "[riemann]") {
  // On [-1, 1] at t = 0.2 no wave has reached the ends, where u = 0: mass and energy stay as they
  // were, and the momentum grows by the pressure difference of the ends, (p_L - p_R) t.
  const double gamma = 1.4, t = 0.2;
  const RiemannSolution sod({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, gamma);
  const int cells = 400000;  // midpoint rule: a discontinuity costs O(jump * dx) = O(1e-6)
  const double mass = integrate([&](double x) { return sod.sample(x, t).density; }, -1, 1, cells);
  const double momentum = integrate(
      [&](double x) {
        const GasState w = sod.sample(x, t);
        return w.density * w.velocity;
      },
      -1, 1, cells);
  const double energy = integrate(
      [&](double x) {
        const GasState w = sod.sample(x, t);
        return w.pressure / (gamma - 1.0) + 0.5 * w.density * w.velocity * w.velocity;
      },
      -1, 1, cells);
  CHECK(mass == Approx(1.0 + 0.125).epsilon(1e-5));
  CHECK(momentum == Approx((1.0 - 0.1) * t).epsilon(1e-5));
  CHECK(energy == Approx((1.0 + 0.1) / (gamma - 1.0)).epsilon(1e-5));
}

TEST_CASE("Property test: random states, several gamma", "[riemann]") {
  // For any pair of states: the contact velocity agrees from both sides, every shock satisfies
  // Rankine-Hugoniot, every fan tail lies on the isentrope of its side.
  std::mt19937 random(1997);
  std::uniform_real_distribution<double> log_uniform(-3.0, 3.0), speed(-2.0, 2.0);
  double worst = 0;
  int solved = 0;
  for (double gamma : {1.1, 1.4, 5.0 / 3.0, 3.0}) {
    for (int k = 0; k < 200; ++k) {
      const GasState left{std::pow(10.0, log_uniform(random)), speed(random),
                          std::pow(10.0, log_uniform(random))};
      const GasState right{std::pow(10.0, log_uniform(random)), speed(random),
                           std::pow(10.0, log_uniform(random))};
      const double critical =
          2.0 / (gamma - 1.0) * (sph::sound_speed(left, gamma) + sph::sound_speed(right, gamma));
      if (critical <= right.velocity - left.velocity) {
        CHECK_THROWS_AS(RiemannSolution(left, right, gamma), sph::Error);
        continue;
      }
      const RiemannSolution s(left, right, gamma);
      ++solved;
      const double t = 1.0, eps = 1e-9;
      for (const auto& [wave, state, star_density] :
           {std::tuple{s.left_wave(), left, s.star_density_left()},
            std::tuple{s.right_wave(), right, s.star_density_right()}}) {
        if (wave.kind == WaveKind::shock) {
          const GasState a = s.sample(wave.head_speed * t - eps, t),
                         b = s.sample(wave.head_speed * t + eps, t);
          worst = std::max(worst, rankine_hugoniot_residual(a, b, wave.head_speed, gamma));
        } else {
          const double entropy = state.pressure / std::pow(state.density, gamma);
          const double star_entropy = s.star_pressure() / std::pow(star_density, gamma);
          worst = std::max(worst, std::abs(star_entropy / entropy - 1.0));
        }
      }
      const GasState a = s.sample(s.contact_position(t) - eps, t),
                     b = s.sample(s.contact_position(t) + eps, t);
      worst = std::max(worst, std::abs(a.velocity - b.velocity) /
                                  (std::abs(a.velocity) + sph::sound_speed(a, gamma)));
      worst = std::max(worst, std::abs(a.pressure / b.pressure - 1.0));
    }
  }
  INFO("solved " << solved << " random problems; worst relative residual " << worst);
  CHECK(solved > 500);
  CHECK(worst < 1e-9);
}

TEST_CASE("Symmetry, mirror image and Galilean invariance", "[riemann]") {
  const double gamma = 1.4;
  SECTION("a symmetric collision has u* = 0 and equal star densities") {
    const RiemannSolution s({1.0, 1.0, 1.0}, {1.0, -1.0, 1.0}, gamma);
    CHECK(s.star_velocity() == Approx(0.0).margin(1e-14));
    CHECK(s.star_density_left() == Approx(s.star_density_right()).epsilon(1e-14));
    CHECK(s.left_wave().kind == WaveKind::shock);
    CHECK(s.right_wave().kind == WaveKind::shock);
  }
  SECTION("swapping the sides and the sign of u mirrors the solution") {
    const RiemannSolution s({1.0, 0.3, 2.0}, {0.2, -0.1, 0.05}, gamma);
    const RiemannSolution m({0.2, 0.1, 0.05}, {1.0, -0.3, 2.0}, gamma);
    CHECK(m.star_pressure() == Approx(s.star_pressure()).epsilon(1e-13));
    CHECK(m.star_velocity() == Approx(-s.star_velocity()).epsilon(1e-13));
    for (double x : {-0.9, -0.4, -0.05, 0.02, 0.3, 0.7}) {
      const GasState a = s.sample(x, 0.5), b = m.sample(-x, 0.5);
      CHECK(a.density == Approx(b.density).epsilon(1e-12));
      CHECK(a.velocity == Approx(-b.velocity).epsilon(1e-12).margin(1e-14));
    }
  }
  SECTION("a uniform boost moves the pattern and adds to u") {
    const double boost = 3.7, t = 0.2;
    const RiemannSolution s({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, gamma);
    const RiemannSolution b({1.0, boost, 1.0}, {0.125, boost, 0.1}, gamma);
    CHECK(b.star_pressure() == Approx(s.star_pressure()).epsilon(1e-13));
    CHECK(b.star_velocity() == Approx(s.star_velocity() + boost).epsilon(1e-13));
    for (double x : {-0.2, -0.1, 0.05, 0.19, 0.3, 0.4}) {
      const GasState a = s.sample(x, t), c = b.sample(x + boost * t, t);
      CHECK(c.density == Approx(a.density).epsilon(1e-12));
      CHECK(c.velocity == Approx(a.velocity + boost).epsilon(1e-12));
    }
  }
}

TEST_CASE("Extreme cases: near vacuum, strong shocks, cold gas", "[riemann]") {
  SECTION("Toro test 2: the near-vacuum centre is finite and positive") {
    const RiemannSolution s({1.0, -2.0, 0.4}, {1.0, 2.0, 0.4}, 1.4);
    const GasState centre = s.sample(0.0, 0.15);
    CHECK(centre.density == table_value(0.02185));
    CHECK(centre.pressure == table_value(0.00189));
    CHECK(centre.velocity == Approx(0.0).margin(1e-14));
  }
  SECTION("cold gas (P = 0) colliding: strong-shock limits") {
    // Relative speed 1: rho* = rho (gamma+1)/(gamma-1) = 6, p* = rho u (u - S) = 0.3.
    const RiemannSolution s({1.0, 0.0, 0.0}, {1.0, -1.0, 0.0}, 1.4);
    CHECK(s.star_density_left() == Approx(6.0).epsilon(1e-12));
    CHECK(s.star_density_right() == Approx(6.0).epsilon(1e-12));
    CHECK(s.star_pressure() == Approx(0.3).epsilon(1e-12));
    CHECK(s.star_velocity() == Approx(-0.5).epsilon(1e-12));
  }
  SECTION("pressure ratio 1e10") {
    const RiemannSolution s({1.0, 0.0, 1e5}, {1.0, 0.0, 1e-5}, 5.0 / 3.0);
    CHECK(std::isfinite(s.star_pressure()));
    // Behind a very strong shock the density ratio tends to (gamma+1)/(gamma-1) = 4.
    CHECK(s.star_density_right() == Approx(4.0).epsilon(1e-3));
  }
}

TEST_CASE("Sampling at t = 0 gives the initial data, and describe() names the pattern",
          "[riemann]") {
  const RiemannSolution sod({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 0.5);
  CHECK(sod.sample(0.4, 0.0).density == 1.0);
  CHECK(sod.sample(0.6, 0.0).density == 0.125);
  CHECK(sod.sample(0.5, 0.0).density == 0.125);  // x0 itself belongs to the right state
  CHECK(sod.internal_energy(0.0, 0.0) == Approx(1.0 / (0.4 * 1.0)));
  CHECK(sod.contact_position(0.2) == Approx(0.5 + 0.2 * 0.92745).epsilon(1e-5));
  const std::string text = sod.describe();
  CHECK(text.find("left rarefaction") != std::string::npos);
  CHECK(text.find("contact") != std::string::npos);
  CHECK(text.find("right shock") != std::string::npos);
  CHECK(sod.describe(0.2).find("x = ") != std::string::npos);
  CHECK_THROWS_WITH(sod.sample(0.0, -1.0), Catch::Contains("t >= 0"));
  CHECK_THROWS_WITH(sod.sample(std::nan(""), 0.1), Catch::Contains("finite"));
}

TEST_CASE("The default solution is a uniform gas at rest", "[riemann]") {
  RiemannSolution s;
  CHECK(s.star_pressure() == 1.0);
  CHECK(s.star_velocity() == 0.0);
  CHECK(s.sample(0.3, 1.0).density == 1.0);
  s = RiemannSolution({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
  CHECK(s.star_pressure() == table_value(0.30313));
}

TEST_CASE("Bad input is reported with a clear message", "[riemann]") {
  const GasState good{1.0, 0.0, 1.0};
  CHECK_THROWS_WITH(RiemannSolution({-1.0, 0.0, 1.0}, good, 1.4),
                    Catch::Contains("negative density"));
  CHECK_THROWS_WITH(RiemannSolution(good, {0.0, 0.0, 1.0}, 1.4),
                    Catch::Contains("right state has density 0") && Catch::Contains("vacuum"));
  CHECK_THROWS_WITH(RiemannSolution(good, {1.0, 0.0, -0.1}, 1.4),
                    Catch::Contains("negative pressure"));
  CHECK_THROWS_WITH(RiemannSolution({std::nan(""), 0.0, 1.0}, good, 1.4),
                    Catch::Contains("left state is not finite"));
  CHECK_THROWS_WITH(RiemannSolution(good, {1.0, INFINITY, 1.0}, 1.4),
                    Catch::Contains("not finite"));
  CHECK_THROWS_WITH(RiemannSolution(good, good, 1.0), Catch::Contains("gamma"));
  CHECK_THROWS_WITH(RiemannSolution(good, good, 0.5), Catch::Contains("gamma"));
  CHECK_THROWS_WITH(RiemannSolution(good, good, std::nan("")), Catch::Contains("gamma"));
}

TEST_CASE("A vacuum generated by the data is reported by the positivity condition", "[riemann]") {
  // 2/(gamma-1) (c_L + c_R) = 5 * 2 sqrt(1.4 * 0.4) = 7.48 < u_R - u_L = 8.
  CHECK_THROWS_WITH(RiemannSolution({1.0, -4.0, 0.4}, {1.0, 4.0, 0.4}, 1.4),
                    Catch::Contains("vacuum generated") &&
                        Catch::Contains("pressure positivity condition") &&
                        Catch::Contains("eq 4.40"));
  // Just inside the condition a solution exists, with a tiny p*.
  const RiemannSolution s({1.0, -3.7, 0.4}, {1.0, 3.7, 0.4}, 1.4);
  CHECK(s.star_pressure() > 0.0);
  CHECK(s.star_pressure() < 1e-5);
}

TEST_CASE("Non-convergence is reported", "[riemann]") {
  sph::RiemannOptions options;
  options.max_iterations = 1;
  CHECK_THROWS_WITH(RiemannSolution({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 0.0, options),
                    Catch::Contains("did not converge in 1 steps"));
}

TEST_CASE("shock_position() needs exactly one shock", "[riemann]") {
  const RiemannSolution two_shocks({5.99924, 19.5975, 460.894}, {5.99242, -6.19633, 46.0950}, 1.4);
  CHECK_THROWS_WITH(two_shocks.shock_position(0.1), Catch::Contains("two shocks"));
  CHECK_THROWS_WITH(two_shocks.rarefaction_head_position(0.1), Catch::Contains("no rarefactions"));
}
