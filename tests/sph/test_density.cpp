// The density pass (lib/sph/density.hpp) against results known independently of it: the exact
// lattice sum of the M4 kernel in 1D (Poisson summation), a brute-force sum over all particles
// and periodic images, the self term, the expectation over a random set, and bitwise
// independence of the thread count.  Degenerate input -- bad masses, coincident particles, an
// isolated particle -- must give a clear error naming the particle or a documented finite result.
#include "sph/density.hpp"
#include "sph/setups/initial_conditions.hpp"
#include "sph/setups/relax.hpp"

#include <catch2/catch.hpp>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace {

using sph::LatticeType;
using sph::Vec;

// The 1D lattice density by Poisson summation (sph::m4_lattice_density_1d): a formula that
// shares no code with the density pass.
double lattice_density_1d(double h_over_dx) { return sph::m4_lattice_density_1d(h_over_dx); }

// Relative error with an absolute floor (NaN fails).
bool close(double value, double expected, double relative, double floor = 1e-300) {
  return std::abs(value - expected) <= relative * std::abs(expected) + floor;
}

// A random 3D set in a periodic unit box with constant h.
sph::Particles<3> random_set(std::size_t n, double h, std::uint64_t seed) {
  auto p = sph::make_particles<3>(sph::uniform_random<3>(Vec<3>::Zero(), Vec<3>::Ones(), n, seed),
                                  1.0 / n);
  for (auto& hi : p.smoothing_length) hi = h;
  return p;
}

}  // namespace

TEST_CASE("the density of a 1D lattice equals the Poisson-summed lattice sum", "[density]") {
  const auto box = sph::Box<1>::periodic_box(Vec<1>(0.0), Vec<1>(1.0));
  const int n = 64;
  double worst = 0;
  for (double h_over_dx : {0.8, 1.0, 1.2, 1.5, 1.7, 2.0, 2.6, 3.3}) {
    auto p = sph::make_particles<1>(
        sph::lattice<1>(LatticeType::cubic, Vec<1>(0.0), Vec<1>(1.0), std::array<int, 1>{n}),
        1.0 / n);
    for (auto& h : p.smoothing_length) h = h_over_dx / n;
    sph::NeighbourSearch<1> search;
    search.update(p, box, sph::SmoothingLengthRule::fixed());
    sph::compute_density(p, search.list());
    const double expected = lattice_density_1d(h_over_dx);
    for (double rho : p.density) worst = std::max(worst, std::abs(rho / expected - 1.0));
    CHECK(close(p.density[7], expected, 1e-12));
  }
  INFO("worst relative difference " << worst);
  CHECK(worst < 1e-12);
  // The number quoted in chapter 2: +0.18 % at h = 1.2 dx.
  CHECK(close(lattice_density_1d(1.2) - 1.0, 0.0018004, 1e-3));
}

TEST_CASE("the density pass equals a brute-force sum over all periodic images", "[density]") {
  // 3D random set with a 5x spread of h (even the smallest kernel holds ~20 others, so the
  // gather density without self term is never empty); both forms, with and without self term.
  const auto box = sph::Box<3>::periodic_box(Vec<3>::Zero(), Vec<3>::Ones());
  auto p = random_set(600, 0.1, 5);
  sph::Random random(9);
  for (auto& h : p.smoothing_length) h = 0.1 * std::pow(5.0, random.uniform());
  for (auto& m : p.mass) m *= 0.5 + random.uniform();
  sph::NeighbourSearch<3> search;
  search.update(p, box, sph::SmoothingLengthRule::fixed());
  for (auto form : {sph::DensityForm::selhammar(), sph::DensityForm::watkins(true),
                    sph::DensityForm::watkins(false)}) {
    sph::compute_density(p, search.list(), form);
    double worst = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      double rho =
          form.self_term ? p.mass[i] * sph::Kernel<3>::value(0, p.smoothing_length[i]) : 0.0;
      for (std::size_t j = 0; j < p.size(); ++j) {
        for (int kx = -1; kx <= 1; ++kx)
          for (int ky = -1; ky <= 1; ++ky)
            for (int kz = -1; kz <= 1; ++kz) {
              if (i == j && kx == 0 && ky == 0 && kz == 0) continue;
              const double r = (p.position[i] - p.position[j] - Vec<3>(kx, ky, kz)).norm();
              if (form.sum == sph::DensityForm::Sum::gather) {
                rho += p.mass[j] * sph::Kernel<3>::value(r, p.smoothing_length[i]);
              } else {
                rho +=
                    0.5 * (p.mass[i] + p.mass[j]) *
                    sph::Kernel<3>::value(r, 0.5 * (p.smoothing_length[i] + p.smoothing_length[j]));
              }
            }
      }
      worst = std::max(worst, std::abs(p.density[i] / rho - 1.0));
    }
    INFO(form.name() << (form.self_term ? " with" : " without")
                     << " self term: worst relative difference " << worst);
    CHECK(worst < 1e-12);
  }
}

TEST_CASE("the self term is m W(0, h), and pair-averaged equals gather at constant h and mass",
          "[density]") {
  const auto box = sph::Box<3>::periodic_box(Vec<3>::Zero(), Vec<3>::Ones());
  auto p = random_set(2000, 0.07, 2);
  sph::NeighbourSearch<3> search;
  search.update(p, box, sph::SmoothingLengthRule::fixed());
  sph::compute_density(p, search.list(), sph::DensityForm::watkins(true));
  const auto with_self = p.density;
  sph::compute_density(p, search.list(), sph::DensityForm::watkins(false));
  const auto without_self = p.density;
  sph::compute_density(p, search.list(), sph::DensityForm::selhammar());
  const double self = p.mass[0] * sph::Kernel<3>::value(0, 0.07);
  for (std::size_t i = 0; i < p.size(); ++i) {
    CHECK(close(with_self[i] - without_self[i], self, 1e-10));
    CHECK(close(p.density[i], with_self[i], 1e-13));
  }
}

TEST_CASE("a random set without the self term has mean density (N-1)/N", "[density]") {
  // Each of the N-1 other particles lands anywhere in the unit box, so E[rho_i] = (N-1) m int W dV.
  // The standard error of the mean over particles is estimated from 8 independent sets.
  const std::size_t n = 4000;
  const double h =
      std::cbrt(3.0 * 60 / (32 * std::numbers::pi * n));  // Watkins eq A6, 60 neighbours
  const auto box = sph::Box<3>::periodic_box(Vec<3>::Zero(), Vec<3>::Ones());
  std::vector<double> means;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    auto p = random_set(n, h, seed);
    sph::NeighbourSearch<3> search;
    search.update(p, box, sph::SmoothingLengthRule::fixed());
    sph::compute_density(p, search.list(), sph::DensityForm::watkins(false));
    means.push_back(sph::density_scatter(p.density).mean);
  }
  double mean = 0, square = 0;
  for (double m : means) mean += m / 8;
  for (double m : means) square += (m - mean) * (m - mean) / 7;
  const double standard_error = std::sqrt(square / 8);
  INFO("mean over 8 sets " << mean << " +- " << standard_error);
  CHECK(std::abs(mean - (n - 1.0) / n) < 5 * standard_error + 1e-3);
  CHECK(standard_error < 0.01);
}

TEST_CASE("the density does not depend on the number of threads", "[density]") {
  const auto box = sph::Box<3>::periodic_box(Vec<3>::Zero(), Vec<3>::Ones());
  auto a = random_set(20000, 0.03, 4), b = a;  // above the parallel threshold
  const int threads = omp_get_max_threads();
  // One search per thread count: a search keeps the candidates of its last update for the next,
  // so a second update of the same object is a different computation.
  sph::NeighbourSearch<3> search_a, search_b;
  omp_set_num_threads(1);
  search_a.update(a, box, sph::SmoothingLengthRule::neighbour_number(50, 3));
  sph::compute_density(a, search_a.list());
  omp_set_num_threads(std::max(2, threads));
  search_b.update(b, box, sph::SmoothingLengthRule::neighbour_number(50, 3));
  sph::compute_density(b, search_b.list());
  omp_set_num_threads(threads);
  CHECK(a.smoothing_length == b.smoothing_length);
  CHECK(a.density == b.density);
}

TEST_CASE("bad masses are reported with the particle named", "[density][degenerate]") {
  const auto box = sph::Box<2>::periodic_box(Vec<2>::Zero(), Vec<2>::Ones());
  for (double bad : {0.0, -0.01, std::nan("")}) {
    auto p = sph::make_particles<2>(sph::uniform_random<2>(Vec<2>::Zero(), Vec<2>::Ones(), 300, 1),
                                    1.0 / 300);
    p.mass[42] = bad;
    sph::NeighbourSearch<2> search;
    INFO("mass " << bad);
    search.update(p, box, sph::SmoothingLengthRule::neighbour_number(20));
    CHECK_THROWS_WITH(sph::compute_density(p, search.list()),
                      Catch::Contains("particle 42") && Catch::Contains("mass"));
    CHECK_THROWS_WITH(search.update(p, box, sph::SmoothingLengthRule::from_density(20)),
                      Catch::Contains("particle 42") && Catch::Contains("mass"));
  }
}

TEST_CASE("coincident particles give a finite density, documented: each sees the other at r = 0",
          "[density][degenerate]") {
  // Two particles on one spot are neighbours at r = 0: each adds m W(0, h) to the other's density,
  // and the kernel gradient between them is zero (not NaN).  An initial-condition generator that
  // does this is at fault; require_distinct_positions finds it.
  const auto box = sph::Box<2>::periodic_box(Vec<2>::Zero(), Vec<2>::Ones());
  auto p = sph::make_particles<2>(
      sph::lattice<2>(LatticeType::cubic, Vec<2>::Zero(), Vec<2>::Ones(), 0.05), 1.0 / 400);
  p.position[7] = p.position[3];
  for (auto& h : p.smoothing_length) h = 0.06;
  sph::NeighbourSearch<2> search;
  search.update(p, box, sph::SmoothingLengthRule::fixed());
  sph::compute_density(p, search.list(), sph::DensityForm::watkins());
  for (double rho : p.density) CHECK(std::isfinite(rho));
  CHECK(close(p.density[3],
              p.density[0] + p.mass[7] * sph::Kernel<2>::value(0, 0.06) -
                  p.mass[3] * sph::Kernel<2>::value(0.05 * 4, 0.06),
              1e-12));
  CHECK(sph::Kernel<2>::gradient(Vec<2>::Zero(), 0.06).norm() == 0.0);
  CHECK_THROWS_WITH(sph::require_distinct_positions<2>(p.position),
                    Catch::Contains("particles 3 and 7 coincide"));
}

TEST_CASE("an isolated particle is reported, not given a zero density", "[density][degenerate]") {
  auto p =
      sph::make_particles<3>(sph::uniform_random<3>(Vec<3>::Zero(), Vec<3>::Ones(), 500, 2), 0.002);
  p.position[99] = Vec<3>(10, 10, 10);
  for (auto& h : p.smoothing_length) h = 0.1;
  sph::NeighbourSearch<3> search;
  CHECK_THROWS_WITH(search.update(p, sph::Box<3>::open(), sph::SmoothingLengthRule::fixed()),
                    Catch::Contains("particle 99") && Catch::Contains("no neighbours"));
}
