// Tests of the error-against-run-time facility (lib/sph/measures/convergence.hpp) on synthetic data
// with known orders, plus the table layout and the rules for bad data.

#include "sph/measures/convergence.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

/// Runs with error = C dx^order and run time = t0 N^cost, for N = 100, 200, 400, 800 in 1D.
void add_synthetic(sph::ErrorVsTime& study, const std::string& method, double C, double order,
                   double cost) {
  for (int n : sph::geometric_series(100, 2.0, 4)) {
    const double dx = 1.0 / n;
    study.add({method,
               n,
               dx,
               1e-6 * std::pow(n, cost),
               {{"L1(rho)", C * std::pow(dx, order)}, {"L1(v)", 2 * C * std::pow(dx, 1.0)}}});
  }
}

/// The lines of a text.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

TEST_CASE("convergence: fitted orders of synthetic data", "[convergence]") {
  sph::ErrorVsTime study("synthetic");
  add_synthetic(study, "second order", 3.0, 2.0, 2.0);
  add_synthetic(study, "first order", 0.5, 1.0, 1.0);
  CHECK(study.order("second order", "L1(rho)") == Approx(2.0).epsilon(1e-12));
  CHECK(study.order("first order", "L1(rho)") == Approx(1.0).epsilon(1e-12));
  CHECK(study.order("second order", "L1(v)") == Approx(1.0).epsilon(1e-12));
  // error ~ dx^2 = N^-2 and time ~ N^2: error ~ time^-1.
  CHECK(study.cost_slope("second order", "L1(rho)") == Approx(-1.0).epsilon(1e-12));
  CHECK(study.cost_slope("first order", "L1(rho)") == Approx(-1.0).epsilon(1e-12));
  CHECK(study.methods() == std::vector<std::string>{"second order", "first order"});
  CHECK(study.quantities() == std::vector<std::string>{"L1(rho)", "L1(v)"});
}

TEST_CASE("convergence: noisy data still gives the order", "[convergence]") {
  sph::ErrorVsTime study("noisy");
  const double noise[] = {1.05, 0.97, 1.02, 0.99, 1.01};
  for (int k = 0; k < 5; ++k) {
    const double dx = 0.1 / std::pow(2.0, k);
    study.add({"a", 10 << k, dx, 0.1 * (k + 1), {{"L2", 7.0 * dx * dx * noise[k]}}});
  }
  CHECK(study.order("a", "L2") == Approx(2.0).margin(0.05));
}

TEST_CASE("convergence: the table lists the runs and the orders, aligned", "[convergence]") {
  sph::ErrorVsTime study("Sod shock tube, t = 0.2");
  add_synthetic(study, "alpha=1, beta=2", 3.0, 2.0, 2.0);
  add_synthetic(study, "alpha=0.5, beta=1", 0.5, 1.0, 1.0);
  const std::string table = study.table();
  INFO(table);
  CHECK(table.find("Sod shock tube, t = 0.2") == 0);
  CHECK(table.find("alpha=1, beta=2") != std::string::npos);
  CHECK(table.find("alpha=0.5, beta=1") != std::string::npos);
  CHECK(table.find("order p, error ~ dx^p") != std::string::npos);
  CHECK(table.find("2.00") != std::string::npos);
  CHECK(table.find("-1.00") != std::string::npos);
  // The run block: a heading and 8 rows, all ending in the same column (numbers right-aligned).
  const auto lines = lines_of(table);
  REQUIRE(lines.size() > 10);
  CHECK(lines[2].find("method") == 0);
  for (int k = 3; k <= 10; ++k) CHECK(lines[k].size() == lines[2].size());
  // The coarsest run of each method comes first.
  CHECK(lines[3].find("alpha=1, beta=2") == 0);
  CHECK(lines[3].find(" 100 ") != std::string::npos);
}

TEST_CASE("convergence: a method with one resolution has no order", "[convergence]") {
  sph::ErrorVsTime study("one point");
  study.add({"single", 100, 0.01, 1.0, {{"L1", 0.1}}});
  CHECK_THROWS_WITH(study.order("single", "L1"),
                    Catch::Contains("fewer than two distinct resolutions"));
  CHECK(study.table().find("n/a") != std::string::npos);
}

TEST_CASE("convergence: bad runs are refused", "[convergence]") {
  sph::ErrorVsTime study("bad");
  CHECK_THROWS_WITH(study.add({"m", 100, 0.01, 1.0, {{"L1(rho)", std::nan("")}}}),
                    Catch::Contains("L1(rho) = nan"));
  CHECK_THROWS_WITH(study.add({"m", 100, -0.01, 1.0, {{"L1", 0.1}}}),
                    Catch::Contains("resolution"));
  CHECK_THROWS_WITH(study.add({"m", 0, 0.01, 1.0, {{"L1", 0.1}}}),
                    Catch::Contains("particle number"));
  CHECK_THROWS_WITH(study.add({"", 10, 0.01, 1.0, {{"L1", 0.1}}}), Catch::Contains("method"));
  CHECK_THROWS_WITH(study.add({"m", 10, 0.01, 1.0, {}}), Catch::Contains("measured no error"));
  CHECK(study.records().empty());
}

TEST_CASE("convergence: run() and sweep() time the scene with the wall clock", "[convergence]") {
  sph::ErrorVsTime study("timed");
  std::ostringstream log;
  study.sweep(
      "sleeper", {10, 20},
      [](int n) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5 * n / 10));
        return sph::Measurement{1.0 / n, {{"L1", 1.0 / n}}};
      },
      &log);
  REQUIRE(study.records().size() == 2);
  CHECK(study.records()[0].seconds >= 0.005);
  CHECK(study.records()[1].seconds >= 0.010);
  CHECK(log.str().find("sleeper: N = 20") != std::string::npos);
  const sph::ErrorCurve curve = study.curve("sleeper", "L1");
  CHECK(curve.particles == std::vector<int>{10, 20});
  CHECK(curve.error[1] == Approx(0.05));
}

TEST_CASE("convergence: helpers", "[convergence]") {
  CHECK(sph::geometric_series(100, 2.0, 4) == std::vector<int>{100, 200, 400, 800});
  CHECK(sph::geometric_series(1000, std::sqrt(2.0), 3) == std::vector<int>{1000, 1414, 2000});
  CHECK(sph::mean_spacing(1000, 3) == Approx(0.1));
  CHECK(sph::mean_spacing(400, 1, 2.0) == Approx(0.005));
  const sph::PowerLaw fit = sph::fit_power_law({1, 2, 4}, {3, 12, 48});
  CHECK(fit.exponent == Approx(2.0));
  CHECK(fit.prefactor == Approx(3.0));
  CHECK_THROWS_AS(sph::fit_power_law({1, 1}, {2, 3}), sph::Error);
  CHECK_THROWS_AS(sph::fit_power_law({1, 2}, {0, 3}), sph::Error);
}

TEST_CASE("the table shows a method's TeX name as plain Unicode", "[convergence]") {
  sph::ErrorVsTime study("study");
  for (int n : {100, 200}) {
    study.add({"\\alpha = 1, \\beta = 2", n, 1.0 / n, 0.1 * n, {{"L1(rho)", 1.0 / n}}});
  }
  const std::string table = study.table();
  CHECK(table.find("α = 1, β = 2") != std::string::npos);
  CHECK(table.find("\\alpha") == std::string::npos);
  CHECK(sph::convergence_detail::plain_text("\\varepsilon, \\eta, \\rho") == "ε, η, ρ");
}
