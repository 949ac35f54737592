// Tests of the error norms (lib/sph/measures/norms.hpp) and of the totals and finite-value checks
// of lib/sph/measures/diagnostics.hpp: hand-computable cases, selections, and the rule that a NaN
// is never a small error.

#include "sph/measures/diagnostics.hpp"
#include "sph/measures/norms.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

using sph::Vec;

namespace {

/// Positions x_i = i on a line.
std::vector<Vec<1>> line_positions(int n) {
  std::vector<Vec<1>> x(n);
  for (int i = 0; i < n; ++i) x[i] << double(i);
  return x;
}

/// The reference f(x) = 2x + 1.
double linear(const Vec<1>& x) { return 2.0 * x[0] + 1.0; }

/// Reference values plus the given errors.
std::vector<double> values_with_errors(const std::vector<Vec<1>>& x,
                                       const std::vector<double>& errors) {
  std::vector<double> f(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) f[i] = linear(x[i]) + errors[i];
  return f;
}

}  // namespace

TEST_CASE("L1, L2 and Linf of known errors", "[norms]") {
  const auto x = line_positions(4);
  const auto f = values_with_errors(x, {0.1, -0.3, 0.0, 0.2});
  const sph::ErrorNorms n = sph::error_norms<1>("f", x, f, linear);
  CHECK(n.count == 4);
  CHECK(n.L1 == Approx(0.6 / 4).epsilon(1e-12));
  CHECK(n.L2 == Approx(std::sqrt((0.01 + 0.09 + 0.04) / 4)).epsilon(1e-12));
  CHECK(n.Linf == Approx(0.3).epsilon(1e-12));
  CHECK(n.worst_index == 1);
  CHECK(n.worst_reference == Approx(3.0));
  CHECK(n.summary().find("particle 1") != std::string::npos);
}

TEST_CASE("A value equal to the reference has zero error", "[norms]") {
  const auto x = line_positions(10);
  const auto f = values_with_errors(x, std::vector<double>(10, 0.0));
  const sph::ErrorNorms n = sph::error_norms<1>("f", x, f, linear);
  CHECK(n.L1 == 0.0);
  CHECK(n.L2 == 0.0);
  CHECK(n.Linf == 0.0);
}

TEST_CASE("Selections: an x-range, a mask, both", "[norms]") {
  const auto x = line_positions(6);
  const auto f = values_with_errors(x, {1.0, 2.0, 3.0, 4.0, 5.0, 6.0});
  SECTION("range [1, 3] is closed") {
    const auto n = sph::error_norms<1>("f", x, f, linear, sph::Selection::range(1.0, 3.0));
    CHECK(n.count == 3);
    CHECK(n.L1 == Approx(3.0));
    CHECK(n.Linf == Approx(4.0));
  }
  SECTION("mask") {
    const auto n = sph::error_norms<1>(
        "f", x, f, linear, sph::Selection::masked({true, false, false, false, false, true}));
    CHECK(n.count == 2);
    CHECK(n.L1 == Approx(3.5));
  }
  SECTION("range and mask together") {
    sph::Selection s = sph::Selection::range(2.0, 10.0);
    s.mask = {true, true, true, false, true, false};
    const auto n = sph::error_norms<1>("f", x, f, linear, s);
    CHECK(n.count == 2);  // particles 2 and 4
    CHECK(n.L1 == Approx(4.0));
    CHECK(s.describe() == "x in [2, 10], masked");
  }
  SECTION("nothing selected is an error") {
    CHECK_THROWS_WITH(sph::error_norms<1>("f", x, f, linear, sph::Selection::range(7.0, 8.0)),
                      Catch::Contains("no particles selected") && Catch::Contains("x in [7, 8]"));
  }
  SECTION("a mask of the wrong length is an error") {
    CHECK_THROWS_WITH(sph::error_norms<1>("f", x, f, linear, sph::Selection::masked({true})),
                      Catch::Contains("mask has 1 entries for 6"));
  }
}

TEST_CASE("A selection on the x axis of 3D particles (a shock tube in a box)", "[norms]") {
  std::vector<Vec<3>> x;
  std::vector<double> f;
  for (int i = 0; i < 10; ++i) {
    x.push_back(Vec<3>(0.1 * i, 0.5, -0.25));
    f.push_back(i < 5 ? 1.0 : 1.5);  // the reference below is 1 everywhere
  }
  const auto one = [](const Vec<3>&) { return 1.0; };
  CHECK(sph::error_norms<3>("rho", x, f, one, sph::Selection::range(0.0, 0.45)).Linf == 0.0);
  CHECK(sph::error_norms<3>("rho", x, f, one, sph::Selection::range(0.45, 1.0)).L1 == Approx(0.5));
  CHECK(sph::error_norms<3>("rho", x, f, one, sph::Selection::range(0.4, 0.6, 1)).count == 10);
  CHECK_THROWS_WITH(sph::error_norms<3>("rho", x, f, one, sph::Selection::range(0, 1, 3)),
                    Catch::Contains("axis 3"));
}

TEST_CASE("NaN never passes as a small error", "[norms]") {
  const auto x = line_positions(5);
  auto f = values_with_errors(x, std::vector<double>(5, 0.0));
  SECTION("NaN in a selected value") {
    f[3] = std::nan("");
    CHECK_THROWS_WITH(sph::error_norms<1>("density", x, f, linear),
                      Catch::Contains("density: particle 3") && Catch::Contains("must be finite"));
  }
  SECTION("NaN outside the selection is still an error") {
    f[4] = std::nan("");
    CHECK_THROWS_WITH(sph::error_norms<1>("density", x, f, linear, sph::Selection::range(0, 1)),
                      Catch::Contains("particle 4"));
  }
  SECTION("infinity") {
    f[0] = INFINITY;
    CHECK_THROWS_WITH(sph::error_norms<1>("density", x, f, linear), Catch::Contains("particle 0"));
  }
  SECTION("NaN in the reference") {
    const auto bad = [](const Vec<1>& y) { return y[0] > 2.5 ? std::nan("") : linear(y); };
    CHECK_THROWS_WITH(sph::error_norms<1>("density", x, f, bad),
                      Catch::Contains("reference is nan at particle 3"));
  }
  SECTION("relative scatter") {
    f[2] = std::nan("");
    CHECK_THROWS_WITH(sph::relative_scatter<1>("v", x, f, linear, 0.0, 10.0),
                      Catch::Contains("particle 2"));
  }
  SECTION("sizes must agree") {
    f.pop_back();
    CHECK_THROWS_WITH(sph::error_norms<1>("density", x, f, linear),
                      Catch::Contains("4 values for 5 positions"));
  }
}

TEST_CASE("Relative scatter in a region", "[norms]") {
  // Watkins et al. (1996) section 4.3 quote the velocity scatter about the exact solution in the
  // shocked region: here values deviate by +-15 % in [2, 5] and by 50 % outside it.
  const auto x = line_positions(8);
  std::vector<double> f(8);
  for (int i = 0; i < 8; ++i) {
    const double deviation = (i >= 2 && i <= 5) ? (i % 2 ? 0.15 : -0.15) : 0.5;
    f[i] = linear(x[i]) * (1.0 + deviation);
  }
  CHECK(sph::relative_scatter<1>("v", x, f, linear, 2.0, 5.0) == Approx(0.15).epsilon(1e-12));
  CHECK(sph::relative_scatter<1>("v", x, f, linear, sph::Selection::range(0.0, 1.0)) ==
        Approx(0.5).epsilon(1e-12));
  const auto zero = [](const Vec<1>&) { return 0.0; };
  CHECK_THROWS_WITH(sph::relative_scatter<1>("v", x, f, zero, 0.0, 3.0),
                    Catch::Contains("reference is 0 at particle 0"));
}

TEST_CASE("component() and Tolerance", "[norms]") {
  const std::vector<Vec<2>> v = {Vec<2>(1, 2), Vec<2>(3, 4)};
  CHECK(sph::component<2>(v, 1) == std::vector<double>{2, 4});
  CHECK_THROWS_AS(sph::component<2>(v, 2), sph::Error);

  const sph::Tolerance tolerance{1e-3, 1e-6};
  CHECK(tolerance.accepts(1.0005, 1.0));
  CHECK_FALSE(tolerance.accepts(1.002, 1.0));
  CHECK(tolerance.accepts(5e-7, 0.0));  // the absolute floor near zero
  CHECK_FALSE(tolerance.accepts(std::nan(""), 1.0));
  CHECK_FALSE(tolerance.accepts(1.0, std::nan("")));
}

// ---------------------------------------------------------------------------------------------
// lib/sph/measures/diagnostics.hpp

namespace {

/// Two particles with hand-checkable totals.
sph::Particles<2> two_particles() {
  sph::Particles<2> p;
  p.add(Vec<2>(0, 0), Vec<2>(1, 0), 1.0, 2.0, 0.1);
  p.add(Vec<2>(3, 0), Vec<2>(0, -2), 2.0, 0.5, 0.1);
  return p;
}

}  // namespace

TEST_CASE("diagnostics: totals of two particles", "[diagnostics]") {
  const auto p = two_particles();
  CHECK(sph::total_mass(p) == 3.0);
  CHECK(sph::kinetic_energy(p) == Approx(0.5 * 1 * 1 + 0.5 * 2 * 4));
  CHECK(sph::thermal_energy(p) == Approx(1 * 2.0 + 2 * 0.5));
  CHECK(sph::total_momentum(p).isApprox(Vec<2>(1, -4)));
  CHECK(sph::centre_of_mass(p).isApprox(Vec<2>(2, 0)));
  const auto t = sph::totals(p);
  CHECK(t.kinetic == Approx(4.5));
  CHECK(t.centre_of_mass.isApprox(Vec<2>(2, 0)));
}

TEST_CASE("diagnostics: the momentum scale adds the momenta without their directions",
          "[diagnostics]") {
  const auto p = two_particles();
  CHECK(sph::momentum_scale(p) == Approx(1 * 1 + 2 * 2));
  CHECK(sph::momentum_scale(p) >= sph::total_momentum(p).norm());
  CHECK(sph::momentum_scale(sph::Particles<2>{}) == 0.0);
}

TEST_CASE("diagnostics: check_finite names the pass, the particle and the field", "[diagnostics]") {
  auto p = two_particles();
  CHECK_NOTHROW(sph::check_all_finite(p, "initial conditions"));
  p.density[1] = std::nan("");
  CHECK_NOTHROW(sph::check_finite(p, {sph::Field::pressure}, "equation of state"));
  CHECK_THROWS_WITH(
      sph::check_finite(p, {sph::Field::density}, "density pass"),
      Catch::Contains("density pass: particle 1 at (3") && Catch::Contains("density = nan"));
  p.acceleration[0] = Vec<2>(INFINITY, 0);
  CHECK_THROWS_WITH(sph::check_finite(p, {sph::Field::acceleration}, "force pass"),
                    Catch::Contains("particle 0") && Catch::Contains("acceleration"));
  p.energy_rate.clear();
  CHECK_THROWS_WITH(sph::check_finite(p, {sph::Field::energy_rate}, "force pass"),
                    Catch::Contains("energy_rate has 0 entries for 2 particles"));
}

TEST_CASE("diagnostics: EnergyHistory records, sums and measures the drift", "[diagnostics]") {
  sph::EnergyHistory h;
  h.record(0.0, 1.0, 2.0);
  h.record(0.1, 1.5, 1.4);
  CHECK(h.size() == 2);
  CHECK(h.total[1] == Approx(2.9));
  CHECK(h.relative_drift() == Approx(0.1 / 3.0));
  CHECK_THROWS_WITH(h.record(0.2, 1.0, 1.0, -0.5), Catch::Contains("potential energy"));
  CHECK_THROWS_WITH(h.record(0.2, std::nan(""), 1.0), Catch::Contains("non-finite"));

  sph::EnergyHistory gravity;
  const auto p = two_particles();
  gravity.record(0.0, p, -4.0);
  CHECK(gravity.has_potential());
  CHECK(gravity.total[0] == Approx(4.5 + 3.0 - 4.0));
}
