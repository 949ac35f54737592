// The viscous ring's reference (lib/sph/reference/viscous_ring.hpp): the scaled Bessel function
// against the standard library, its own two branches against each other, and the ring's
// surface density and radial velocity against the conservation laws they must obey.
#include "sph/reference/viscous_ring.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

TEST_CASE("scaled Bessel I: the standard library, where it does not overflow", "[ring]") {
  for (const double nu : {0.0, 0.25, 1.25, 2.0}) {
    for (const double z : {1e-3, 0.1, 1.0, 5.0, 20.0, 39.9, 40.1, 60.0, 125.0, 300.0, 700.0}) {
      const double expected = std::cyl_bessel_i(nu, z) * std::exp(-z);
      INFO("nu = " << nu << ", z = " << z);
      CHECK(sph::scaled_bessel_i(nu, z) == Approx(expected).epsilon(1e-12));
    }
  }
}

TEST_CASE("scaled Bessel I: series and asymptotic series agree where they meet", "[ring]") {
  // The branch point is z = 40; the series is exact for any z, the asymptotic series only for
  // large z.  Sum the series directly just above 40 and compare it with the function there.
  for (const double z : {40.5, 45.0, 60.0}) {
    for (const double nu : {0.25, 1.25}) {
      double term = std::exp(nu * std::log(0.5 * z) - std::lgamma(nu + 1) - z), sum = term;
      for (int k = 0; k < 400; ++k) {
        term *= 0.25 * z * z / ((k + 1) * (k + 1 + nu));
        sum += term;
      }
      INFO("nu = " << nu << ", z = " << z);
      CHECK(sph::scaled_bessel_i(nu, z) == Approx(sum).epsilon(1e-12));
    }
  }
}

TEST_CASE("scaled Bessel I: large arguments, the leading term, and bad input", "[ring]") {
  // Beyond the standard library's range: e^-z I_nu(z) -> (2 pi z)^-1/2 (1 - (4nu^2 - 1)/(8z)).
  for (const double z : {1e3, 1e4, 1e6}) {
    const double leading = (1 - (0.25 - 1) / (8 * z)) / std::sqrt(2 * std::numbers::pi * z);
    CHECK(sph::scaled_bessel_i(0.25, z) == Approx(leading).epsilon(0.1 / (z * z)));
  }
  CHECK(sph::scaled_bessel_i(0.25, 0.0) == 0.0);
  CHECK(sph::scaled_bessel_i(0.0, 0.0) == 1.0);
  CHECK_THROWS_WITH(sph::scaled_bessel_i(0.25, -1.0), Catch::Contains("argument"));
  CHECK_THROWS_WITH(sph::scaled_bessel_i(0.25, std::nan("")), Catch::Contains("argument"));
  CHECK_THROWS_WITH(sph::scaled_bessel_i(-0.5, 1.0), Catch::Contains("order"));
}

namespace {
// The ring's mass inside R at tau, by Simpson's rule on 2 pi R sigma.
double mass_within(const sph::ViscousRing& ring, double r_max, double tau, int n = 20000) {
  const double dr = r_max / n;
  double sum = 0;
  for (int k = 0; k <= n; ++k) {
    const double r = std::max(k * dr, 1e-12);
    const double w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
    sum += w * 2 * std::numbers::pi * r * ring.surface_density(r, tau);
  }
  return sum * dr / 3;
}
}  // namespace

TEST_CASE("viscous ring: eq 20 loses mass only to the centre", "[ring]") {
  // The solution has no torque at R = 0, and mass flows onto the point mass there: the ring's
  // mass starts at m and falls at the rate of the inflow at the centre, -2 pi R sigma v_R as
  // R -> 0.  (By tau = 1 the point mass has taken 7 % of it.)
  const sph::ViscousRing ring(2.5, 1.0, 1.5e-3);
  CHECK(mass_within(ring, 12.0, 0.016) == Approx(2.5).epsilon(1e-7));
  for (const double tau : {0.064, 0.256, 1.0}) {
    const double dtau = 1e-4;
    const double rate =
        (mass_within(ring, 12.0, tau + dtau) - mass_within(ring, 12.0, tau - dtau)) / (2 * dtau) *
        12 * ring.nu;  // dM/dt
    const double r = 1e-4;
    const double inflow =
        2 * std::numbers::pi * r * ring.surface_density(r, tau) * ring.radial_velocity(r, tau);
    INFO("tau = " << tau);
    CHECK(rate < 0);
    CHECK(rate == Approx(inflow).epsilon(1e-3));
  }
  // Finite far out at the earliest time, where I_1/4 alone would overflow (z > 709).
  const double far = ring.surface_density(8.0, 0.016);
  CHECK(std::isfinite(far));
  CHECK(far >= 0);
}

TEST_CASE("viscous ring: eq 21's velocity carries eq 20's mass (continuity)", "[ring]") {
  // d sigma/dt = -(1/R) d(R sigma v_R)/dR, with d tau/dt = 12 nu / R0^2; by central differences.
  const sph::ViscousRing ring(1.0, 1.0, 4.5e-3);
  const double dtau = 1e-6, dr = 1e-5;
  for (const double tau : {0.016, 0.1}) {
    for (const double r : {0.8, 0.95, 1.0, 1.1, 1.3}) {
      const double dsigma_dt =
          (ring.surface_density(r, tau + dtau) - ring.surface_density(r, tau - dtau)) / (2 * dtau) *
          12 * ring.nu;
      const auto flux = [&](double R) {
        return R * ring.surface_density(R, tau) * ring.radial_velocity(R, tau);
      };
      const double divergence = (flux(r + dr) - flux(r - dr)) / (2 * dr) / r;
      INFO("tau = " << tau << ", R = " << r);
      CHECK(dsigma_dt == Approx(-divergence).epsilon(1e-5).margin(1e-9));
    }
  }
  // Inside the ring the gas falls in, outside it moves out.
  CHECK(ring.radial_velocity(0.7, 0.05) < 0);
  CHECK(ring.radial_velocity(1.5, 0.05) > 0);
  CHECK_THROWS_WITH(ring.surface_density(-1.0, 0.1), Catch::Contains("radius"));
  CHECK_THROWS_WITH(ring.radial_velocity(1.0, 0.0), Catch::Contains("tau"));
  CHECK_THROWS_WITH(sph::ViscousRing(1.0, 1.0, 0.0), Catch::Contains("viscosity"));
}

#include "sph/setups/viscous_ring.hpp"

TEST_CASE("viscous ring set-up: the annulus filled, eq 20's mass, Kepler plus eq 21", "[ring]") {
  sph::setups::ViscousRingDisc disc;
  disc.particles = 6000;
  disc.inner = 0.6, disc.outer = 1.4;
  const sph::Particles<2> p = sph::setups::make_viscous_ring(disc);
  CHECK(std::abs(static_cast<double>(p.size()) / 6000 - 1) < 0.02);
  // The mass is eq 20's within the annulus (the particles stand for rings of width Delta).
  double mass = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double R = p.position[i].norm();
    REQUIRE(R > 0.6);
    REQUIRE(R < 1.4);
    mass += p.mass[i];
    // Keplerian azimuthal speed, eq 21's radial speed, the disc's h.
    const sph::Vec<2> e_r = p.position[i] / R;
    const double v_r = p.velocity[i].dot(e_r);
    const double v_phi = e_r[0] * p.velocity[i][1] - e_r[1] * p.velocity[i][0];
    REQUIRE(v_phi == Approx(1 / std::sqrt(R)).epsilon(1e-12));
    REQUIRE(v_r == Approx(disc.ring.radial_velocity(R, disc.tau0)).epsilon(1e-12));
    REQUIRE(p.smoothing_length[i] == disc.h);
  }
  double exact = 0;  // eq 20 over the annulus, midpoint rule
  for (int k = 0; k < 8000; ++k) {
    const double r = 0.6 + (k + 0.5) * 0.8 / 8000;
    exact += 2 * std::numbers::pi * r * disc.ring.surface_density(r, disc.tau0) * 0.8 / 8000;
  }
  CHECK(mass == Approx(exact).epsilon(1e-3));
  disc.inner = 1.5;
  CHECK_THROWS_WITH(sph::setups::make_viscous_ring(disc), Catch::Contains("inner < outer"));
}
