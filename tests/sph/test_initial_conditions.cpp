// Initial conditions (lib/sph/setups/initial_conditions.hpp, lib/sph/setups/relax.hpp): lattices
// fill their box exactly and seamlessly, cuts keep what they should, disturbances stay within their
// amplitude, random sets are reproducible, coincident points are caught, and relaxation settles a
// random set without pairing particles.
#include "sph/setups/initial_conditions.hpp"
#include "sph/setups/relax.hpp"

#include <catch2/catch.hpp>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace {

using sph::LatticeType;
using sph::Vec;

// The smallest distance between two different points (nearest periodic image on a periodic
// box), by brute force.
template <int D>
double smallest_separation(const std::vector<Vec<D>>& x, const sph::Box<D>& box) {
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = i + 1; j < x.size(); ++j)
      smallest = std::min(smallest, box.separation(x[i], x[j]).norm());
  return smallest;
}

template <int D>
bool inside(const Vec<D>& x, const Vec<D>& lower, const Vec<D>& upper) {
  for (int a = 0; a < D; ++a)
    if (!(x[a] >= lower[a] && x[a] < upper[a])) return false;
  return true;
}

// Relative spread max/min - 1 of a positive vector.
double spread(const std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *hi / *lo - 1.0;
}

}  // namespace

TEST_CASE("SplitMix64 is reproducible and uniform on the unit interval", "[initial_conditions]") {
  sph::Random a(42), b(42), c(43);
  double sum = 0, square = 0;
  const int n = 200000;
  bool same = true, different = false;
  for (int k = 0; k < n; ++k) {
    const double u = a.uniform();
    REQUIRE(u >= 0.0);
    REQUIRE(u < 1.0);
    same = same && u == b.uniform();
    different = different || u != c.uniform();
    sum += u;
    square += u * u;
  }
  CHECK(same);
  CHECK(different);
  // Mean 1/2 and variance 1/12, each within 5 standard errors of n draws.
  const double mean = sum / n, variance = square / n - mean * mean;
  INFO("mean " << mean << ", variance " << variance);
  CHECK(std::abs(mean - 0.5) < 5 * std::sqrt(1.0 / 12.0 / n));
  CHECK(std::abs(variance - 1.0 / 12.0) < 5 * std::sqrt(1.0 / 180.0 / n));
}

TEST_CASE("lattices fill the box with the right count and spacing", "[initial_conditions]") {
  SECTION("1D evenly spaced") {
    const auto x =
        sph::lattice<1>(LatticeType::cubic, Vec<1>(-1.0), Vec<1>(1.0), std::array<int, 1>{40});
    REQUIRE(x.size() == 40);
    CHECK(x.front()[0] == Approx(-1.0 + 0.025));
    CHECK(smallest_separation<1>(x, sph::Box<1>::periodic_box(Vec<1>(-1.0), Vec<1>(1.0))) ==
          Approx(0.05));
  }
  SECTION("2D square and hexagonal") {
    const Vec<2> lo(0, 0), hi(1, 0.5);
    const auto square = sph::lattice<2>(LatticeType::cubic, lo, hi, 0.1);
    CHECK(square.size() == 10u * 5u);
    // A regular hexagonal lattice of spacing 0.1: rows sqrt(3)/2 * 0.1 apart, an even number.
    const auto cells = sph::lattice_cells<2>(LatticeType::hexagonal, lo, hi, 0.1);
    CHECK(cells[0] == 10);
    CHECK(cells[1] % 2 == 0);
    CHECK(cells[1] == 6);  // 0.5 / 0.0866 = 5.8 -> 6
    const auto hex = sph::lattice<2>(LatticeType::hexagonal, lo, hi, cells);
    CHECK(hex.size() == 60u);
    const auto box = sph::Box<2>::periodic_box(lo, hi);
    // Every point has its nearest neighbour in its own row, 0.1 away, or in the next row at
    // sqrt(0.05^2 + (0.5/6)^2) = 0.097 (the box forces rows 0.0833 apart, not 0.0866).
    CHECK(smallest_separation<2>(hex, box) == Approx(std::hypot(0.05, 0.5 / 6)).epsilon(1e-12));
    for (const auto& x : hex) CHECK(inside<2>(x, lo, hi));
  }
  SECTION("3D cubic and body-centred") {
    const Vec<3> lo(0, 0, 0), hi(1, 1, 2);
    const auto cubic = sph::lattice<3>(LatticeType::cubic, lo, hi, std::array<int, 3>{5, 5, 10});
    const auto bcc =
        sph::lattice<3>(LatticeType::body_centred, lo, hi, std::array<int, 3>{5, 5, 10});
    CHECK(cubic.size() == 250u);
    CHECK(bcc.size() == 500u);
    const auto box = sph::Box<3>::periodic_box(lo, hi);
    CHECK(smallest_separation<3>(cubic, box) == Approx(0.2).epsilon(1e-12));
    CHECK(smallest_separation<3>(bcc, box) == Approx(0.2 * std::sqrt(3.0) / 2).epsilon(1e-12));
    for (const auto& x : bcc) CHECK(inside<3>(x, lo, hi));
    sph::require_distinct_positions<3>(bcc, box, 0.17);  // nothing closer than 0.173
  }
  SECTION("bad requests are refused") {
    CHECK_THROWS_AS(sph::lattice<3>(LatticeType::hexagonal, Vec<3>::Zero(), Vec<3>::Ones(), 0.1),
                    sph::Error);
    CHECK_THROWS_AS(sph::lattice<2>(LatticeType::cubic, Vec<2>::Zero(), Vec<2>::Ones(), -0.1),
                    sph::Error);
    CHECK_THROWS_AS(sph::lattice<2>(LatticeType::cubic, Vec<2>::Zero(), Vec<2>(1, 0), 0.1),
                    sph::Error);
  }
}

TEST_CASE("a lattice in a periodic box is seamless: every particle sees the same density",
          "[initial_conditions]") {
  // A seam (a lattice that does not tile the box) would show as particles near the faces with a
  // different neighbour set, hence a different density.
  const Vec<3> lo(0, 0, 0), hi(1, 1, 1);
  for (LatticeType type : {LatticeType::cubic, LatticeType::body_centred}) {
    auto x = sph::lattice<3>(type, lo, hi, 1.0 / 8);
    auto p = sph::make_particles<3>(x, 1.0 / static_cast<double>(x.size()));
    const auto box = sph::Box<3>::periodic_box(lo, hi);
    for (auto& h : p.smoothing_length) h = 1.3 * std::cbrt(1.0 / static_cast<double>(x.size()));
    sph::NeighbourSearch<3> search;
    search.update(p, box, sph::SmoothingLengthRule::fixed());
    sph::compute_density(p, search.list());
    INFO(sph::lattice_name(type) << ": relative spread of density " << spread(p.density));
    CHECK(spread(p.density) < 1e-12);
    CHECK(*std::min_element(p.neighbour_count.begin(), p.neighbour_count.end()) ==
          *std::max_element(p.neighbour_count.begin(), p.neighbour_count.end()));
  }
  // The 2D hexagonal lattice with an even number of rows.
  const Vec<2> lo2(0, 0), hi2(1, std::sqrt(3.0) / 2);
  auto p = sph::make_particles<2>(sph::lattice<2>(LatticeType::hexagonal, lo2, hi2, 0.05), 1.0);
  for (auto& h : p.smoothing_length) h = 0.06;
  sph::NeighbourSearch<2> search;
  search.update(p, sph::Box<2>::periodic_box(lo2, hi2), sph::SmoothingLengthRule::fixed());
  sph::compute_density(p, search.list());
  INFO("hexagonal: relative spread of density " << spread(p.density));
  CHECK(spread(p.density) < 1e-12);
}

TEST_CASE("cuts keep exactly the points inside", "[initial_conditions]") {
  const auto x =
      sph::lattice<3>(LatticeType::cubic, Vec<3>::Constant(-1), Vec<3>::Constant(1), 0.05);
  const auto sphere = sph::cut_sphere<3>(x, Vec<3>::Zero(), 1.0);
  std::size_t expected = 0;
  for (const auto& xi : x) expected += xi.norm() < 1.0;
  CHECK(sphere.size() == expected);
  for (const auto& xi : sphere) CHECK(xi.norm() < 1.0);
  // The count approximates the volume: 4/3 pi / 0.05^3 = 33510, to within a surface layer.
  const double volume_count = 4.0 / 3.0 * std::numbers::pi / std::pow(0.05, 3);
  CHECK(std::abs(static_cast<double>(sphere.size()) / volume_count - 1.0) < 0.01);
  const auto slab = sph::cut_box<3>(x, Vec<3>(-1, -1, 0), Vec<3>(1, 1, 0.5));
  CHECK(slab.size() == 40u * 40u * 10u);
}

TEST_CASE("ordering by cells keeps the points and puts them slab after slab",
          "[initial_conditions]") {
  auto points = sph::lattice<3>(sph::LatticeType::cubic, sph::Vec<3>(-1, 0, 0),
                                sph::Vec<3>(1, 0.2, 0.2), 0.02);
  sph::disturb<3>(points, 0.004, 9);
  auto ordered = points;
  sph::order_by_cells<3>(ordered, 0.05);
  REQUIRE(ordered.size() == points.size());
  // The same points (as a multiset)...
  auto less = [](const sph::Vec<3>& a, const sph::Vec<3>& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  auto a = points, b = ordered;
  std::sort(a.begin(), a.end(), less);
  std::sort(b.begin(), b.end(), less);
  CHECK(a == b);
  // ...with x never falling back by more than a cell, and y by more than a cell only where x
  // moves on to the next cell.
  long backwards = 0;
  double lowest_x = std::numeric_limits<double>::infinity();
  for (const auto& x : points) lowest_x = std::min(lowest_x, x[0]);
  for (std::size_t k = 1; k < ordered.size(); ++k) {
    backwards += ordered[k][0] < ordered[k - 1][0] - 0.05;
    const bool same_slab = std::floor((ordered[k][0] - lowest_x) / 0.05) ==
                           std::floor((ordered[k - 1][0] - lowest_x) / 0.05);
    backwards += same_slab && ordered[k][1] < ordered[k - 1][1] - 0.05;
  }
  CHECK(backwards == 0);
  // lattice() itself counts x fastest: it jumps back along x at every row.
  long jumps = 0;
  for (std::size_t k = 1; k < points.size(); ++k) jumps += points[k][0] < points[k - 1][0] - 0.05;
  CHECK(jumps > 50);
  CHECK_THROWS_WITH(sph::order_by_cells<3>(ordered, 0.0), Catch::Contains("cell size"));
}

TEST_CASE("disturbances stay within their amplitude and are reproducible", "[initial_conditions]") {
  const auto box = sph::Box<2>::periodic_box(Vec<2>::Zero(), Vec<2>::Ones());
  const auto lattice = sph::lattice<2>(LatticeType::cubic, Vec<2>::Zero(), Vec<2>::Ones(), 0.1);
  auto a = lattice, b = lattice, c = lattice;
  sph::disturb<2>(a, 0.01, 7, box);
  sph::disturb<2>(b, 0.01, 7, box);
  sph::disturb<2>(c, 0.01, 8, box);
  double largest = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    largest = std::max(largest, box.separation(a[i], lattice[i]).cwiseAbs().maxCoeff());
    CHECK(inside<2>(a[i], Vec<2>::Zero(), Vec<2>::Ones()));
  }
  INFO("largest displacement " << largest);
  CHECK(largest <= 0.01);
  CHECK(largest > 0.009);  // 200 draws: the largest comes close to the amplitude
  CHECK(a == b);
  CHECK(a != c);
}

TEST_CASE("uniform random sets are reproducible and fill the box", "[initial_conditions]") {
  const Vec<3> lo(-1, 0, 2), hi(1, 0.5, 3);
  const auto a = sph::uniform_random<3>(lo, hi, 20000, 1),
             b = sph::uniform_random<3>(lo, hi, 20000, 1);
  CHECK(a == b);
  Vec<3> mean = Vec<3>::Zero();
  for (const auto& x : a) {
    CHECK(inside<3>(x, lo, hi));
    mean += x / 20000.0;
  }
  // The mean of 20000 uniform draws is within 5 standard errors, (hi - lo)/sqrt(12 * 20000).
  const Vec<3> centre = 0.5 * (lo + hi);
  for (int axis = 0; axis < 3; ++axis)
    CHECK(std::abs(mean[axis] - centre[axis]) <
          5 * (hi[axis] - lo[axis]) / std::sqrt(12.0 * 20000));
}

TEST_CASE("coincident positions are reported with both particles named", "[initial_conditions]") {
  auto x = sph::uniform_random<2>(Vec<2>::Zero(), Vec<2>::Ones(), 100, 3);
  CHECK_NOTHROW(sph::require_distinct_positions<2>(x));
  x[61] = x[17];
  CHECK_THROWS_WITH(sph::require_distinct_positions<2>(x),
                    Catch::Contains("particles 17 and 61 coincide"));
  // With a minimum separation, on a periodic box, across the periodic face.
  std::vector<Vec<2>> pair = {Vec<2>(0.001, 0.5), Vec<2>(0.998, 0.5), Vec<2>(0.5, 0.5)};
  const auto box = sph::Box<2>::periodic_box(Vec<2>::Zero(), Vec<2>::Ones());
  CHECK_NOTHROW(sph::require_distinct_positions<2>(pair, box, 0.002));
  CHECK_THROWS_WITH(sph::require_distinct_positions<2>(pair, box, 0.01),
                    Catch::Contains("particles 0 and 1"));
  CHECK_NOTHROW(sph::require_distinct_positions<2>(pair, sph::Box<2>::open(), 0.01));
}

TEST_CASE("mass calibration makes the SPH density of a lattice exact", "[initial_conditions]") {
  // A 2D square lattice with m = rho dx^2 has the M4 lattice bias; one calibration sweep
  // removes it (every particle is alike), to round-off.
  const auto box = sph::Box<2>::periodic_box(Vec<2>::Zero(), Vec<2>::Ones());
  auto p = sph::make_particles<2>(
      sph::lattice<2>(LatticeType::cubic, Vec<2>::Zero(), Vec<2>::Ones(), 0.04), 2.5 * 0.04 * 0.04);
  for (auto& h : p.smoothing_length) h = 1.3 * 0.04;
  sph::NeighbourSearch<2> search;
  search.update(p, box, sph::SmoothingLengthRule::fixed());
  const auto report = sph::calibrate_mass_to_density<2>(p, search.list(), 2.5);
  INFO("bias before " << report.initial_error << ", after " << report.final_error);
  CHECK(report.initial_error > 1e-5);  // the bias is really there (5e-5 at h = 1.3 dx in 2D)
  CHECK(report.iterations == 1);
  CHECK(report.final_error < 1e-13);
  for (double rho : p.density) CHECK(std::abs(rho / 2.5 - 1.0) < 1e-13);
}

TEST_CASE("mass calibration across a density jump (pair-averaged form)", "[initial_conditions]") {
  // A periodic 1D tube: density 1 on [0, 1/2) with 200 particles, 1/4 on [1/2, 1) with 50.
  auto x = sph::lattice<1>(LatticeType::cubic, Vec<1>(0.0), Vec<1>(0.5), std::array<int, 1>{200});
  const auto right =
      sph::lattice<1>(LatticeType::cubic, Vec<1>(0.5), Vec<1>(1.0), std::array<int, 1>{50});
  x.insert(x.end(), right.begin(), right.end());
  auto p = sph::make_particles<1>(x, 1.0);
  auto target = [](const Vec<1>& xi) { return xi[0] < 0.5 ? 1.0 : 0.25; };
  for (std::size_t i = 0; i < p.size(); ++i)
    p.mass[i] = target(p.position[i]) * (p.position[i][0] < 0.5 ? 0.0025 : 0.01);
  sph::NeighbourSearch<1> search;
  search.update(p, sph::Box<1>::periodic_box(Vec<1>(0.0), Vec<1>(1.0)),
                sph::SmoothingLengthRule::neighbour_number(5));
  const auto report = sph::calibrate_mass_to_density<1>(p, search.list(), target);
  INFO("iterations " << report.iterations << ", error before " << report.initial_error << ", after "
                     << report.final_error << " at particle " << report.worst_particle);
  CHECK(report.initial_error > 0.1);  // nominal masses smear the jump
  CHECK(report.final_error < 1e-12);
  for (double m : p.mass) CHECK(m > 0);
}

TEST_CASE("mass calibration refuses a bad target", "[initial_conditions]") {
  auto p = sph::make_particles<1>(
      sph::lattice<1>(LatticeType::cubic, Vec<1>(0.0), Vec<1>(1.0), 0.1), 0.1);
  sph::NeighbourSearch<1> search;
  search.update(p, sph::Box<1>::periodic_box(Vec<1>(0.0), Vec<1>(1.0)),
                sph::SmoothingLengthRule::neighbour_number(4));
  CHECK_THROWS_WITH(sph::calibrate_mass_to_density<1>(
                        p, search.list(), [](const Vec<1>& x) { return x[0] < 0.5 ? 1.0 : -1.0; }),
                    Catch::Contains("target density at particle 5"));
}

TEST_CASE("relaxation settles a random set without pairing, deterministically",
          "[initial_conditions][relax]") {
  // 2D, 800 particles, 20 neighbours, constant h (Watkins' eq A7 with sigma = 1).
  const int n = 800;
  const double m = 1.0 / n, h = std::sqrt(m * 20 / (4 * std::numbers::pi));
  const auto box = sph::Box<2>::periodic_box(Vec<2>::Zero(), Vec<2>::Ones());
  auto start =
      sph::make_particles<2>(sph::uniform_random<2>(Vec<2>::Zero(), Vec<2>::Ones(), n, 11), m);
  for (auto& hi : start.smoothing_length) hi = h;
  start.velocity[5] = Vec<2>(1, 2);
  auto a = start, b = start;
  const sph::RelaxReport ra = sph::relax_to_uniform_density(a, box);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const sph::RelaxReport rb = sph::relax_to_uniform_density(b, box);
  omp_set_num_threads(threads);
  const double dx = std::sqrt(m);
  const double closest = smallest_separation<2>(a.position, box);
  INFO("iterations " << ra.iterations << ", scatter " << ra.initial.relative << " -> "
                     << ra.final.relative << ", closest pair " << closest / dx << " dx");
  CHECK(ra.converged);
  CHECK(ra.final.relative < 0.05 * ra.initial.relative);
  CHECK(ra.final.relative < 0.01);
  CHECK(std::abs(ra.final.mean - 1.0) < 0.01);
  CHECK(closest > 0.4 * dx);  // no pairs: the Thomas & Couchman slope keeps close pairs apart
  // The returned density belongs to the returned positions.
  const auto stored = a.density;
  sph::NeighbourSearch<2> search;
  search.update(a, box, sph::SmoothingLengthRule::fixed());
  sph::compute_density(a, search.list(), sph::DensityForm::watkins());
  for (std::size_t i = 0; i < a.size(); ++i)
    CHECK(a.density[i] == Approx(stored[i]).epsilon(1e-14));
  // Same result on one thread; velocities untouched; positions in the box.
  CHECK(a.position == b.position);
  CHECK(ra.history == rb.history);
  CHECK(a.velocity[5] == Vec<2>(1, 2));
  for (const auto& x : a.position) CHECK(inside<2>(x, Vec<2>::Zero(), Vec<2>::Ones()));
}

TEST_CASE("relaxation refuses an open box and bad options", "[initial_conditions][relax]") {
  auto p =
      sph::make_particles<2>(sph::uniform_random<2>(Vec<2>::Zero(), Vec<2>::Ones(), 50, 1), 0.02);
  sph::Box<2> half_open{Vec<2>::Zero(), Vec<2>::Ones(), {true, false}};
  CHECK_THROWS_WITH(sph::relax_to_uniform_density(p, half_open), Catch::Contains("axis y is open"));
  sph::RelaxOptions bad;
  bad.momentum = 1.0;
  CHECK_THROWS_AS(sph::relax_to_uniform_density(
                      p, sph::Box<2>::periodic_box(Vec<2>::Zero(), Vec<2>::Ones()), bad),
                  sph::Error);
}
