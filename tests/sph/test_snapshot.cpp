// Tests of the SPLASH-readable snapshots (lib/sph/measures/snapshot.hpp): the exact header layout,
// an emulation of how SPLASH's ASCII reader finds the header lines, time, gamma and column labels
// (read_data_ascii.f90 / asciiutils.f90), bit-exact round trips in 1D and 3D, and errors.

#include "sph/measures/diagnostics.hpp"
#include "sph/measures/snapshot.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#ifndef SPH_TEST_OUTPUT_DIR
#define SPH_TEST_OUTPUT_DIR "."
#endif

using sph::Vec;

namespace {

std::string output_path(const std::string& name) {
  std::filesystem::create_directories(SPH_TEST_OUTPUT_DIR);
  return std::string(SPH_TEST_OUTPUT_DIR) + "/" + name;
}

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// n particles with random values in every written field (awkward numbers on purpose).
template <int D>
sph::Particles<D> random_particles(int n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  sph::Particles<D> p;
  for (int i = 0; i < n; ++i) {
    Vec<D> x, v;
    for (int a = 0; a < D; ++a) {
      x[a] = uniform(random) / 3.0;
      v[a] = uniform(random) * 1e-7;
    }
    p.add(x, v, 1.0 / (n + 0.3), std::exp(10 * uniform(random)), 0.01 + 0.001 * uniform(random));
    p.density[i] = 1.0 + uniform(random);
    p.pressure[i] = 1e-300 * (1.5 + uniform(random));  // tiny numbers must survive too
  }
  return p;
}

/// The first value SPLASH's list-directed read takes from a header line after the '#', or
/// false if the text there does not start with a number.
bool splash_header_number(const std::string& line, double& value) {
  const std::string after_hash = line.substr(1);
  const auto tokens = sph::splash_ascii::split(after_hash);
  return !tokens.empty() && sph::splash_ascii::parse_number(tokens[0], value);
}

/// Number of numeric columns SPLASH counts on a line (a '#' line counts none).
std::size_t numeric_columns(const std::string& line) {
  std::size_t count = 0;
  double x = 0;
  for (auto token : sph::splash_ascii::split(line)) {
    if (!sph::splash_ascii::parse_number(token, x)) break;
    ++count;
  }
  return count;
}

/// What SPLASH infers from a file without options (read_data_ascii.f90, get_ncolumns).
struct SplashView {
  std::size_t header_lines = 0, columns = 0;
  bool time_set = false, gamma_set = false;
  double time = 0, gamma = 0;
};
SplashView splash_view(const std::vector<std::string>& lines) {
  SplashView view;
  // Header lines: everything before the first two consecutive lines with equal non-zero counts.
  std::size_t k = 1;
  while (k < lines.size() && !(numeric_columns(lines[k]) > 0 &&
                               numeric_columns(lines[k]) == numeric_columns(lines[k - 1])))
    ++k;
  view.header_lines = k - 1;
  view.columns = numeric_columns(lines[k]);
  // Time: the first header number with a decimal point; gamma: the next one in (1, 2].
  for (std::size_t i = 0; i < view.header_lines; ++i) {
    double value = 0;
    if (!splash_header_number(lines[i], value)) continue;
    if (view.time_set && !view.gamma_set && value > 1.0 && value < 2.000001) {
      view.gamma = value;
      view.gamma_set = true;
    } else if (!view.time_set && lines[i].find('.') != std::string::npos) {
      view.time = value;
      view.time_set = true;
    }
  }
  return view;
}

}  // namespace

TEST_CASE("snapshot: the header is exactly SPLASH's layout", "[snapshot]") {
  sph::Particles<1> p;
  for (int i = 0; i < 3; ++i) p.add(Vec<1>(0.1 * i), Vec<1>(0.0), 0.5, 2.5, 0.02);
  const std::string path = output_path("snapshot_header_1d.dat");
  sph::write_snapshot(path, p, 0.2, 1.4);
  const auto lines = read_lines(path);
  REQUIRE(lines.size() == 6 + 3);
  CHECK(lines[1] == "# 3  npart");
  CHECK(lines[2] == "# 1  dimensions");
  CHECK(lines[3] == "# 2.0000000000000001e-01  time");
  CHECK(lines[4] == "# 1.3999999999999999e+00  gamma");
  // Fortran ('#',N(1x,'[',i2.2,1x,a11,']',2x)), as written by Phantom and read by SPLASH.
  CHECK(lines[5] ==
        "# [01           x]   [02          vx]   [03        mass]   [04           h]   "
        "[05     density]   [06           u]   [07    pressure]");
  CHECK(sph::splash_ascii::parse_column_labels(lines[5]) ==
        std::vector<std::string>{"x", "vx", "mass", "h", "density", "u", "pressure"});
}

TEST_CASE("snapshot: SPLASH finds the header, time, gamma and the columns without options",
          "[snapshot]") {
  SECTION("1D") {
    const std::string path = output_path("snapshot_splash_1d.dat");
    sph::write_snapshot(path, random_particles<1>(20, 1), 1.0, 5.0 / 3.0);  // t = 1 still has a '.'
    const SplashView view = splash_view(read_lines(path));
    CHECK(view.header_lines == 6);
    CHECK(view.columns == 7);
    CHECK(view.time_set);
    CHECK(view.time == 1.0);
    CHECK(view.gamma_set);
    CHECK(view.gamma == Approx(5.0 / 3.0).epsilon(1e-15));
  }
  SECTION("3D") {
    const std::string path = output_path("snapshot_splash_3d.dat");
    sph::write_snapshot(path, random_particles<3>(20, 2), 0.0, 1.4);
    const auto lines = read_lines(path);
    const SplashView view = splash_view(lines);
    CHECK(view.header_lines == 6);
    CHECK(view.columns == 11);
    CHECK(view.time_set);
    CHECK(view.time == 0.0);
    CHECK(view.gamma == 1.4);
    CHECK(sph::splash_ascii::parse_column_labels(lines[5]) ==
          std::vector<std::string>{"x", "y", "z", "vx", "vy", "vz", "mass", "h", "density", "u",
                                   "pressure"});
  }
}

TEST_CASE("snapshot: round trip is bit-exact in 1D and 3D", "[snapshot]") {
  SECTION("1D") {
    const auto p = random_particles<1>(450, 3);
    const std::string path = output_path("snapshot_round_trip_1d.dat");
    sph::write_snapshot(path, p, 0.123456789012345678, 1.4);
    const sph::Snapshot<1> s = sph::read_snapshot<1>(path);
    CHECK(s.time == 0.123456789012345678);
    CHECK(s.gamma == 1.4);
    REQUIRE(s.particles.size() == p.size());
    CHECK(s.particles.position == p.position);
    CHECK(s.particles.velocity == p.velocity);
    CHECK(s.particles.mass == p.mass);
    CHECK(s.particles.smoothing_length == p.smoothing_length);
    CHECK(s.particles.density == p.density);
    CHECK(s.particles.internal_energy == p.internal_energy);
    CHECK(s.particles.pressure == p.pressure);
    CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
  }
  SECTION("3D") {
    const auto p = random_particles<3>(300, 4);
    const std::string path = output_path("snapshot_round_trip_3d.dat");
    sph::write_snapshot(path, p, 20.0, 5.0 / 3.0);
    const sph::Snapshot<3> s = sph::read_snapshot<3>(path);
    CHECK(s.time == 20.0);
    CHECK(s.gamma == 5.0 / 3.0);
    CHECK(s.particles.position == p.position);
    CHECK(s.particles.velocity == p.velocity);
    CHECK(s.particles.internal_energy == p.internal_energy);
    CHECK(s.particles.pressure == p.pressure);
  }
}

TEST_CASE("snapshot: errors name the path", "[snapshot]") {
  const auto p = random_particles<1>(5, 5);
  SECTION("an unwritable path") {
    CHECK_THROWS_WITH(sph::write_snapshot("/nonexistent-directory/snap.dat", p, 0.0, 1.4),
                      Catch::Contains("cannot write /nonexistent-directory/snap.dat"));
  }
  SECTION("a missing file") {
    CHECK_THROWS_WITH(
        sph::read_snapshot<1>(output_path("no-such-snapshot.dat")),
        Catch::Contains("cannot read snapshot") && Catch::Contains("no-such-snapshot.dat"));
  }
  SECTION("the wrong dimension") {
    const std::string path = output_path("snapshot_3d_read_as_1d.dat");
    sph::write_snapshot(path, random_particles<3>(4, 6), 0.0, 1.4);
    CHECK_THROWS_WITH(sph::read_snapshot<1>(path), Catch::Contains("3-dimensional, read as 1D"));
  }
  SECTION("a corrupted row") {
    const std::string path = output_path("snapshot_corrupted.dat");
    sph::write_snapshot(path, p, 0.0, 1.4);
    auto lines = read_lines(path);
    lines[8] = "  1.0  2.0  three  4  5  6  7";
    std::ofstream(path) << [&] {
      std::string text;
      for (const auto& l : lines) text += l + "\n";
      return text;
    }();
    CHECK_THROWS_WITH(sph::read_snapshot<1>(path),
                      Catch::Contains("line 9") && Catch::Contains("'three'"));
  }
  SECTION("a field of the wrong size") {
    auto q = p;
    q.density.pop_back();
    CHECK_THROWS_WITH(sph::write_snapshot(output_path("snapshot_bad.dat"), q, 0.0, 1.4),
                      Catch::Contains("4 entries for 5 particles"));
  }
}

TEST_CASE("snapshot_path numbers the outputs", "[snapshot]") {
  CHECK(sph::snapshot_path("out", "sod", 12) == "out/sod_00012.dat");
  CHECK(sph::snapshot_path("", "sod", 0) == "sod_00000.dat");
}

TEST_CASE("EnergyHistory::write gives a SPLASH-readable table", "[snapshot][diagnostics]") {
  sph::EnergyHistory h;
  h.record(0.0, 0.0, 1.0, -2.0);
  h.record(0.5, 0.25, 0.75, -2.0);
  const std::string path = output_path("energies.ev");
  h.write(path);
  const auto lines = read_lines(path);
  REQUIRE(lines.size() == 4);
  CHECK(sph::splash_ascii::parse_column_labels(lines[1]) ==
        std::vector<std::string>{"time", "ekin", "etherm", "epot", "etot"});
  CHECK(numeric_columns(lines[3]) == 5);
}
