// The pieces that let a neighbour search keep most particles' candidates from step to step:
// the packed-image arithmetic, the local motion bound, the SIMD compaction of kept pairs, and
// the search itself when part of the gas moves and part rests (against brute force).
#include "brute_force_pairs.hpp"
#include "sph/neighbours.hpp"
#include "sph/neighbours/local_motion.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <vector>

using test::brute_force;
using test::listed;

TEST_CASE("packed images add and subtract axis by axis, negative shifts included", "[neighbours]") {
  long wrong = 0;
  for (int a0 = -60; a0 <= 60; a0 += 7)
    for (int a1 = -60; a1 <= 60; a1 += 11)
      for (int a2 = -60; a2 <= 60; a2 += 13)
        for (int b0 = -60; b0 <= 60; b0 += 9)
          for (int b1 = -60; b1 <= 60; b1 += 17)
            for (int b2 = -60; b2 <= 60; b2 += 19) {
              const auto a = sph::pack_image<3>({a0, a1, a2}), b = sph::pack_image<3>({b0, b1, b2});
              wrong += sph::add_images(a, b) != sph::pack_image<3>({a0 + b0, a1 + b1, a2 + b2});
              wrong +=
                  sph::subtract_images(a, b) != sph::pack_image<3>({a0 - b0, a1 - b1, a2 - b2});
              wrong += sph::mirror_image<3>(a) != sph::pack_image<3>({-a0, -a1, -a2});
            }
  CHECK(wrong == 0);
}

TEST_CASE("the local motion bound holds for every pair closer than the cell size", "[neighbours]") {
  // Random positions in a box periodic along x and y, open along z; displacements that are a
  // common drift plus a shear plus noise (so boxes of different cells differ).  For every pair
  // closer than the cell size (periodic images included), |d_i - d_j| <= bound(i).
  const sph::Box<3> box{sph::Vec<3>(0, 0, 0), sph::Vec<3>(1, 0.5, 0.7), {true, true, false}};
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t n = 600;
  std::vector<sph::Vec<3>> x(n);
  std::array<std::vector<double>, 3> d;
  for (auto& axis : d) axis.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = sph::Vec<3>(unit(rng), 0.5 * unit(rng), 0.7 * unit(rng));
    d[0][i] = 0.3 + 0.05 * std::sin(6.0 * x[i][1]) + 0.01 * unit(rng);
    d[1][i] = -0.2 + 0.04 * x[i][2] + 0.01 * unit(rng);
    d[2][i] = 0.02 * unit(rng);
  }
  sph::LocalMotion<3> motion;
  motion.build(x, box, {d[0].data(), d[1].data(), d[2].data()}, 0.11);
  const double s = motion.cell_size();
  CHECK(s >= 0.11);
  // A value per particle (a smooth field plus noise, as h is) and its smallest nearby value.
  std::vector<double> value(n), least;
  for (std::size_t i = 0; i < n; ++i)
    value[i] = 1.0 + 0.3 * std::cos(5.0 * x[i][0]) + 0.05 * unit(rng);
  motion.neighbourhood_min(value.data(), least);
  REQUIRE(least.size() == n);
  double worst = -1, tightest = 1e300;
  std::size_t pairs = 0, above_floor = 0, below_own = 0;
  for (std::size_t i = 0; i < n; ++i) {
    above_floor += least[i] > value[i];
    below_own += least[i] < value[i];
    for (std::size_t j = 0; j < n; ++j) {
      sph::Vec<3> r = box.separation(x[i], x[j]);
      if (i == j || r.norm() >= s) continue;
      ++pairs;
      const double diff =
          std::sqrt(std::pow(d[0][i] - d[0][j], 2) + std::pow(d[1][i] - d[1][j], 2) +
                    std::pow(d[2][i] - d[2][j], 2));
      worst = std::max(worst, diff - motion.bound(i));
      tightest = std::min(tightest, motion.bound(i));
      above_floor += least[i] > value[j];
    }
  }
  INFO(pairs << " pairs within the cell size");
  CHECK(pairs > 1000);
  CHECK(worst <= 1e-15);
  // The smallest nearby value is at most each near particle's own, and at most i's own; and
  // it is not simply the global minimum (most particles have a larger one).
  CHECK(above_floor == 0);
  CHECK(below_own > 0);
  CHECK(*std::max_element(least.begin(), least.end()) >
        *std::min_element(value.begin(), value.end()) + 0.1);
  // The common drift (0.3, -0.2, 0) does not enter the bound: it stays of the order of the shear
  // and noise.
  CHECK(tightest < 0.08);
}

TEST_CASE("the SIMD compaction of kept pairs equals the plain loop", "[neighbours]") {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t n : {0u, 1u, 7u, 8u, 9u, 57u, 80u, 203u}) {
    std::vector<std::uint32_t> index(n);
    std::vector<sph::Image> image(n);
    std::vector<double> r2(n);
    std::vector<sph::Image> wrapped(300);
    for (auto& w : wrapped)
      w = sph::pack_image<3>({int(unit(rng) * 5) - 2, int(unit(rng) * 5) - 2, 0});
    for (std::size_t k = 0; k < n; ++k) {
      index[k] = static_cast<std::uint32_t>(unit(rng) * 300);
      image[k] = sph::pack_image<3>(
          {int(unit(rng) * 3) - 1, int(unit(rng) * 3) - 1, int(unit(rng) * 3) - 1});
      r2[k] = unit(rng);
    }
    for (const sph::Image* w : {static_cast<const sph::Image*>(nullptr),
                                static_cast<const sph::Image*>(wrapped.data())}) {
      std::vector<sph::Neighbour> a(n + 8), b(n + 8);
      const sph::Image own = wrapped[17];
      double fa = -1, fb = -2;
      const std::size_t ka = sph::detail::keep_closer<false>(index.data(), image.data(), r2.data(),
                                                             n, 0.6, w, own, a.data(), fa);
      const std::size_t kb = sph::detail::keep_closer<true>(index.data(), image.data(), r2.data(),
                                                            n, 0.6, w, own, b.data(), fb);
      REQUIRE(ka == kb);
      std::size_t expected = 0;
      double farthest = 0;
      for (std::size_t k = 0; k < n; ++k) {
        expected += r2[k] < 0.6;
        if (r2[k] < 0.6) farthest = std::max(farthest, r2[k]);
      }
      CHECK(ka == expected);
      CHECK(fa == farthest);
      CHECK(fb == farthest);
      for (std::size_t k = 0; k < ka; ++k) {
        CHECK(a[k].index == b[k].index);
        CHECK(a[k].image == b[k].image);
      }
    }
  }
}

TEST_CASE(
    "a search that keeps the candidates of resting gas and searches the moving gas again equals "
    "brute force",
    "[neighbours]") {
  // A 3D box periodic in y and z: the left half rests, the right half streams in +x and wraps
  // across the y faces with a shear, so its particles must be searched again while the
  // resting ones keep their candidates.  After every update the list equals brute force.
  const sph::Box<3> box{sph::Vec<3>(0, 0, 0), sph::Vec<3>(1, 0.25, 0.25), {false, true, true}};
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  sph::Particles<3> p;
  for (int i = 0; i < 500; ++i)
    p.add(sph::Vec<3>(unit(rng), 0.25 * unit(rng), 0.25 * unit(rng)), sph::Vec<3>::Zero(), 1.0);
  for (auto rule :
       {sph::SmoothingLengthRule::neighbour_number(30, 3), sph::SmoothingLengthRule::fixed()}) {
    for (auto& h : p.smoothing_length) h = 0.045;
    sph::NeighbourSearch<3> search;
    for (int step = 0; step < 15; ++step) {
      for (auto& x : p.position) {
        if (x[0] < 0.5) continue;
        const sph::Vec<3> jitter(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
        x = box.wrap(x + sph::Vec<3>(0.0, 0.006 + 0.01 * (x[0] - 0.5), -0.004) + 0.001 * jitter);
      }
      search.update(p, box, rule);
      REQUIRE(listed(search.list(), p.size()) == brute_force(p, box));
    }
    INFO("updates that searched " << search.searches() << ", full " << search.full_searches()
                                  << ", reused " << search.reuses() << ", particle searches "
                                  << search.particle_searches());
    CHECK(search.full_searches() == 1);
    CHECK(search.searches() > search.full_searches());  // partial searches happened
    // The resting half far from the interface was not searched again: each partial search
    // took well under the whole set.
    const long partial = search.particle_searches() - static_cast<long>(p.size());
    CHECK(partial < static_cast<long>(0.6 * static_cast<double>(p.size()) *
                                      static_cast<double>(search.searches() - 1)));
    // With fixed h only the motion decides, and some updates need no search at all (the count
    // rule also searches when a count leaves its tolerance and the new h would reach past the
    // candidates, which at this sliding interface happens every step).
    if (rule.mode == sph::SmoothingLengthRule::Mode::fixed) CHECK(search.reuses() > 0);
  }
}

TEST_CASE("a collapsing cloud whose h spans a factor 30 keeps its list equal to brute force",
          "[neighbours]") {
  // The situation of the Evrard collapse: a ball with rho ~ 1/r^2 (h from 40 neighbours spans
  // a factor ~40 from the centre to the edge), falling in non-homologously (the inner parts
  // faster), in an open box.  After every update the list must equal brute force.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  sph::Particles<3> p;
  while (p.size() < 3000) {
    const sph::Vec<3> dir(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
    if (dir.norm() > 0.5 || dir.norm() < 1e-3) continue;
    const double r = unit(rng);  // uniform in r: rho ~ 1/r^2
    p.add(r * dir.normalized(), sph::Vec<3>::Zero(), 1.0);
  }
  for (auto& h : p.smoothing_length) h = 0.05;
  const auto rule = sph::SmoothingLengthRule::neighbour_number(40, 4);
  sph::NeighbourSearch<3> search;
  for (int step = 0; step < 25; ++step) {
    for (auto& x : p.position) {
      const double r = x.norm();
      x *= 1.0 - 0.002 / std::sqrt(std::max(r, 0.05));  // free-fall-like: faster inside
    }
    search.update(p, sph::Box<3>::open(), rule);
    REQUIRE(listed(search.list(), p.size()) == brute_force(p, sph::Box<3>::open()));
  }
  const auto [h_min, h_max] =
      std::minmax_element(p.smoothing_length.begin(), p.smoothing_length.end());
  INFO("h from " << *h_min << " to " << *h_max << "; particle searches "
                 << search.particle_searches());
  CHECK(*h_max / *h_min > 10);
  // Candidates are kept: fewer than half the particles are searched again per update.
  CHECK(search.particle_searches() < static_cast<long>(p.size()) * (1 + 24 / 2));
}

namespace {

// `count` particles of unit mass at rest, uniformly in the ball of `radius` about `centre`.
void add_ball(sph::Particles<3>& p, std::mt19937_64& rng, double radius, const sph::Vec<3>& centre,
              std::size_t count) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (std::size_t k = 0; k < count;) {
    const sph::Vec<3> x(unit(rng), unit(rng), unit(rng));
    if (x.norm() > 1.0) continue;
    p.add(centre + radius * x, sph::Vec<3>::Zero(), 1.0);
    ++k;
  }
}

}  // namespace

TEST_CASE("a dense clump in a wide cloud: finer grids, and searches that outgrow them",
          "[neighbours]") {
  // A cloud of large h around a ball 40 times denser, whose x > 0 half starts with an h eight
  // times too small: those particles search on a finer grid than the ball's other half, and
  // as their radius grows past what their level's box allows, on coarser grids -- the other
  // half's, whose box ends near x = 0, or the main one.  Every other update is partial (a third
  // of the particles active, as with individual time steps).  After every update the list
  // must equal brute force.
  std::mt19937_64 rng(7);
  sph::Particles<3> p;
  add_ball(p, rng, 1.0, sph::Vec<3>::Zero(), 600);
  add_ball(p, rng, 0.1, sph::Vec<3>::Zero(), 2000);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool in_ball = p.position[i].norm() < 0.1;
    p.smoothing_length[i] = !in_ball ? 0.2 : p.position[i][0] < 0 ? 0.012 : 0.0015;
  }
  const auto rule = sph::SmoothingLengthRule::neighbour_number(40, 4);
  sph::NeighbourSearch<3> search;
  std::vector<std::uint32_t> active;
  for (std::uint32_t i = 0; i < p.size(); i += 3) active.push_back(i);
  for (int step = 0; step < 6; ++step) {
    for (auto& x : p.position) x *= 0.995;
    if (step % 2 == 0) {
      search.update(p, sph::Box<3>::open(), rule);
      REQUIRE(listed(search.list(), p.size()) == brute_force(p, sph::Box<3>::open()));
    } else {
      search.update(p, sph::Box<3>::open(), rule, sph::ActiveSet{&active});
      const auto all = brute_force(p, sph::Box<3>::open());
      const auto found = listed(search.list(), p.size());
      for (std::uint32_t i : active) {
        const auto first = all.lower_bound({i, 0, 0}), last = all.lower_bound({i + 1, 0, 0});
        REQUIRE(std::set(first, last) ==
                std::set(found.lower_bound({i, 0, 0}), found.lower_bound({i + 1, 0, 0})));
      }
    }
  }
  INFO("finer grids " << search.fine_grids_built() << ", fallbacks "
                      << search.fine_grid_fallbacks());
  CHECK(search.fine_grids_built() > 0);
  CHECK(search.fine_grid_fallbacks() > 0);
}

TEST_CASE("a dense clump and a far, lone particle in a wide cloud: finer grids, the same list",
          "[neighbours]") {
  // A cloud of large h with a clump 200 times denser (h a sixth of the cloud's) and one particle
  // far out, started with a small h: the clump's particles search on finer grids than the
  // cloud's; the lone particle's search grows until its radius belongs to the main grid.
  // After every update the list must equal brute force.
  std::mt19937_64 rng(7);
  sph::Particles<3> p;
  add_ball(p, rng, 1.0, sph::Vec<3>::Zero(), 1500);
  add_ball(p, rng, 0.1, sph::Vec<3>(0.4, -0.2, 0.1), 1000);
  p.add(sph::Vec<3>(3.0, 0.0, 0.0), sph::Vec<3>::Zero(), 1.0);
  for (auto& h : p.smoothing_length) h = 0.02;
  const auto rule = sph::SmoothingLengthRule::neighbour_number(40, 4);
  sph::NeighbourSearch<3> search;
  for (int step = 0; step < 6; ++step) {
    for (auto& x : p.position) x *= 0.99;
    search.update(p, sph::Box<3>::open(), rule);
    REQUIRE(listed(search.list(), p.size()) == brute_force(p, sph::Box<3>::open()));
  }
  const auto [h_min, h_max] =
      std::minmax_element(p.smoothing_length.begin(), p.smoothing_length.end());
  INFO("h from " << *h_min << " to " << *h_max << "; finer grids " << search.fine_grids_built());
  CHECK(*h_max / *h_min > 5);
  CHECK(search.fine_grids_built() > 0);
}
