// The Sedov-Taylor solution (sph/reference/sedov_solution.hpp) and the blast's set-up
// (sph/setups/sedov.hpp).
//
// The solution is integrated from the shock inwards; nothing in it imposes the mass of the
// shocked region, or the values of xi_0 that Sedov tabulated, so both check the integration.
#include "sph/measures/diagnostics.hpp"
#include "sph/reference/sedov_solution.hpp"
#include "sph/setups/sedov.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

namespace {

// The integral over the ball of radius R(t) of f(state, r) dV, by the midpoint rule in r (the
// profile is smooth inside the shock; 20000 shells resolve its steep front).
template <class F>
double ball_integral(const sph::SedovSolution& s, double t, F&& f) {
  const double R = s.shock_radius(t);
  const int shells = 20000;
  double sum = 0;
  for (int k = 0; k < shells; ++k) {
    const double r = R * (k + 0.5) / shells;
    sum += f(s.sample(r, t)) * s.surface() * std::pow(r, s.dimension() - 1) * R / shells;
  }
  return sum;
}

}  // namespace

TEST_CASE("Sedov: xi_0 from the energy integral matches the published constants", "[sedov]") {
  // Kamm & Timmes (2007) give the constant of E = alpha rho_0 R^(j+2) / t^2, that is
  // alpha = xi_0^-(j+2): 0.851072 for the spherical blast with gamma = 1.4, 0.493590 with
  // gamma = 5/3 (xi_0 = 1.0328 and 1.1517), 0.984074 for the cylindrical one with gamma = 1.4.
  const auto alpha = [](int j, double gamma) {
    return std::pow(sph::SedovSolution(j, gamma).xi0(), -(j + 2));
  };
  CHECK(alpha(3, 1.4) == Approx(0.851072).epsilon(1e-5));
  CHECK(alpha(3, 5.0 / 3.0) == Approx(0.493590).epsilon(1e-5));
  CHECK(alpha(2, 1.4) == Approx(0.984074).epsilon(1e-5));
}

TEST_CASE("Sedov: the shocked region holds the swept-up mass and the energy E", "[sedov]") {
  for (int j = 1; j <= 3; ++j) {
    for (double gamma : {1.2, 1.4, 5.0 / 3.0, 3.0}) {
      const double E = 2.5, rho0 = 0.7, t = 0.3;
      const sph::SedovSolution s(j, gamma, E, rho0);
      const double R = s.shock_radius(t);
      const double swept = rho0 * s.surface() * std::pow(R, j) / j;
      const double mass = ball_integral(s, t, [](const auto& w) { return w.density; });
      const double energy = ball_integral(s, t, [&](const auto& w) {
        return 0.5 * w.density * w.velocity * w.velocity + w.pressure / (gamma - 1);
      });
      INFO("j = " << j << ", gamma = " << gamma << ": mass " << mass << " against " << swept
                  << ", energy " << energy << " against " << E);
      CHECK(mass == Approx(swept).epsilon(1e-4));
      CHECK(energy == Approx(E).epsilon(1e-4));
      CHECK(s.mass_integral() * j == Approx(1.0).epsilon(1e-7));
    }
  }
}

TEST_CASE("Sedov: the strong-shock jump at the shock and the centre's behaviour", "[sedov]") {
  for (double gamma : {1.4, 5.0 / 3.0}) {
    const sph::SedovSolution s(3, gamma);
    const double t = 0.05, R = s.shock_radius(t), U = s.shock_speed(t);
    const auto behind = s.sample(R * (1 - 1e-9), t);
    CHECK(behind.density == Approx((gamma + 1) / (gamma - 1)).epsilon(1e-6));
    CHECK(behind.velocity == Approx(2 * U / (gamma + 1)).epsilon(1e-6));
    CHECK(behind.pressure == Approx(2 * U * U / (gamma + 1)).epsilon(1e-6));
    const auto ahead = s.sample(R * (1 + 1e-9), t);
    CHECK(ahead.density == 1.0);
    CHECK(ahead.velocity == 0.0);
    // Near the centre the gas moves homologously, f = lambda / gamma, so v = U f = alpha r /
    // (gamma t) with alpha = 2/5, and the density falls to zero.
    const double r = 0.05 * R;
    CHECK(s.sample(r, t).velocity == Approx(0.4 * r / (gamma * t)).epsilon(1e-3));
    CHECK(s.sample(r, t).density < 1e-3);
    // R(t) and the time it takes to reach a radius are inverse to each other.
    CHECK(s.time_at_radius(R) == Approx(t).epsilon(1e-12));
  }
}

TEST_CASE("Sedov: impossible parameters are refused with a message", "[sedov]") {
  CHECK_THROWS_WITH(sph::SedovSolution(4, 1.4), Catch::Contains("dimension"));
  CHECK_THROWS_WITH(sph::SedovSolution(3, 1.0), Catch::Contains("gamma"));
  CHECK_THROWS_WITH(sph::SedovSolution(3, 8.0), Catch::Contains("gamma"));
  CHECK_THROWS_WITH(sph::SedovSolution(3, 1.4, -1.0), Catch::Contains("energy"));
  sph::SedovSetup setup;
  setup.background_energy = 0;
  CHECK_THROWS_WITH(sph::make_sedov_blast<3>(setup, sph::SmoothingLengthRule::neighbour_number(40)),
                    Catch::Contains("u_0"));
}

TEST_CASE("Sedov blast set-up: uniform density, and E in the central particles", "[sedov]") {
  sph::SedovSetup setup;
  setup.cells = 10;
  setup.energy = 2.0;
  const auto blast =
      sph::make_sedov_blast<3>(setup, sph::SmoothingLengthRule::neighbour_number(40));
  const auto& p = blast.particles;
  CHECK(p.size() == 1000);
  CHECK(sph::total_mass(p) == Approx(1.0).epsilon(0.05));  // calibrated: the lattice sum's bias
  const double background = setup.background_energy * sph::total_mass(p);
  CHECK(sph::thermal_energy(p) - background == Approx(2.0).epsilon(1e-12));
  // Only particles within 2 h_E of the centre are heated, the nearest the most.
  CHECK(blast.heated >= 8);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.position[i].norm() >= 2 * blast.deposit_h)
      CHECK(p.internal_energy[i] == setup.background_energy);
  }
}
