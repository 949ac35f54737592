// The neighbour list against a brute-force search (after SWIFT's brute-force checks): the same
// pairs, periodic images included, on random sets in 1D/2D/3D, periodic and open, with a 100x
// spread of smoothing lengths and periodic boxes narrower than the kernel support.
#include "brute_force_pairs.hpp"
#include "sph/neighbours.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <set>
#include <tuple>

namespace {

using test::brute_force;

template <int D>
void compare_with_brute_force(const sph::Box<D>& box, std::size_t n, double h_spread, unsigned seed,
                              double h_min = 0.02) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  sph::Particles<D> p;
  for (std::size_t i = 0; i < n; ++i) {
    sph::Vec<D> x;
    for (int a = 0; a < D; ++a) x[a] = box.lower[a] + unit(rng) * box.length(a);
    // h log-uniform over [h0, h0 * spread]
    const double h = h_min * std::pow(h_spread, unit(rng));
    p.add(x, sph::Vec<D>::Zero(), 1.0, 0.0, h);
  }
  sph::NeighbourSearch<D> search;
  search.update(p, box, sph::SmoothingLengthRule::fixed());
  std::set<std::tuple<std::size_t, std::uint32_t, sph::Image>> found;
  std::size_t entries = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (const auto& nb : search.list().of(i)) {
      found.insert({i, nb.index, nb.image});
      ++entries;
    }
  }
  const auto expected = brute_force(p, box);
  CHECK(entries == found.size());  // no pair listed twice
  CHECK(found == expected);
  INFO("pairs " << expected.size());
}

}  // namespace

TEST_CASE("neighbour list equals brute force, open and periodic, 100x spread of h",
          "[neighbours]") {
  for (bool periodic : {false, true}) {
    SECTION(periodic ? "periodic" : "open") {
      sph::Box<1> b1{sph::Vec<1>(0.0), sph::Vec<1>(1.0), {periodic}};
      compare_with_brute_force<1>(b1, 300, 100.0, 1);
      sph::Box<2> b2{sph::Vec<2>(0, 0), sph::Vec<2>(1, 1), {periodic, periodic}};
      compare_with_brute_force<2>(b2, 400, 100.0, 2);
      sph::Box<3> b3{sph::Vec<3>(0, 0, 0), sph::Vec<3>(1, 1, 1), {periodic, periodic, periodic}};
      // h from 0.004 to 0.4: the largest kernels still reach past the box (2h = 0.8), while the
      // brute-force reference stays cheap.
      compare_with_brute_force<3>(b3, 500, 100.0, 3, 0.004);
    }
  }
}

TEST_CASE("neighbour list in periodic tubes narrower than the kernel support", "[neighbours]") {
  // A 3D tube 1 x 0.05 x 0.05, periodic across, open along: support up to 2 * 0.02 * 10 = 0.4,
  // eight times the tube width, so each particle sees many images of its neighbours.
  sph::Box<3> tube{sph::Vec<3>(0, 0, 0), sph::Vec<3>(1, 0.05, 0.05), {false, true, true}};
  compare_with_brute_force<3>(tube, 200, 10.0, 4);
  sph::Box<2> strip{sph::Vec<2>(0, 0), sph::Vec<2>(1, 0.03), {true, true}};
  compare_with_brute_force<2>(strip, 150, 10.0, 5);
}

TEST_CASE("reused candidates give the brute-force list as particles move and wrap",
          "[neighbours]") {
  // A 3D tube periodic across (0.06 wide, narrower than 2h) and along x, particles drifting at
  // a uniform velocity (so they cross the periodic faces) plus a small random jitter each step.
  // After every update the list must equal brute force, whether the update reused the old
  // candidates or searched again; both must happen.
  sph::Box<3> tube{sph::Vec<3>(0, 0, 0), sph::Vec<3>(1, 0.06, 0.06), {true, true, true}};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  sph::Particles<3> p;
  for (int i = 0; i < 300; ++i) {
    p.add(sph::Vec<3>(unit(rng), 0.06 * unit(rng), 0.06 * unit(rng)), sph::Vec<3>::Zero(), 1.0);
  }
  for (auto rule :
       {sph::SmoothingLengthRule::neighbour_number(30, 2), sph::SmoothingLengthRule::fixed()}) {
    // (h = 0.029, not 0.03: at 2h = 0.06, exactly the tube's width, each particle's own image
    // would sit on the kernel's edge and round-off would decide whether it counts.)
    for (auto& h : p.smoothing_length) h = 0.029;
    sph::NeighbourSearch<3> search;
    for (int step = 0; step < 12; ++step) {
      for (auto& x : p.position) {
        const sph::Vec<3> jitter(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
        x = tube.wrap(x + sph::Vec<3>(0.013, 0.007, -0.011) + 0.004 * jitter);
      }
      search.update(p, tube, rule);
      REQUIRE(test::listed(search.list(), p.size()) == brute_force(p, tube));
    }
    INFO("searches " << search.searches() << ", reuses " << search.reuses());
    CHECK(search.reuses() > 0);
    CHECK(search.searches() > 1);
  }
}

TEST_CASE("reused candidates give the brute-force list across a shear layer, h spread 10x",
          "[neighbours]") {
  // A thin gas in a unit cube sheared along x (the upper half moves at +0.5, the lower at
  // -0.5) with a dense clump in one corner, so that the smallest reach is a twentieth of the
  // largest and the local motion is bounded on several levels of cells.  A thin particle near
  // the layer sees hardly any other particle in the finest cells around it; only cells as
  // large as its reach see the other half of the gas slide past.  A bound read on cells
  // smaller than the reach would keep stale candidates and miss the pairs that slide in.
  // (test_local_reuse.cpp follows a collapse, where the levels matter as well.)
  const sph::Box<3> open = sph::Box<3>::open();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  sph::Particles<3> p;
  for (int i = 0; i < 1500; ++i)
    p.add(sph::Vec<3>(unit(rng), unit(rng), unit(rng)), sph::Vec<3>::Zero(), 1.0);
  while (p.size() < 2500) {
    const sph::Vec<3> x(2 * unit(rng) - 1, 2 * unit(rng) - 1, 2 * unit(rng) - 1);
    if (x.norm() < 1) p.add(sph::Vec<3>(0.9, 0.9, 0.9) + 0.05 * x, sph::Vec<3>::Zero(), 1.0);
  }
  sph::NeighbourSearch<3> search;
  double h_min = 1e30, h_max = 0;
  for (int step = 0; step < 20; ++step) {
    for (auto& x : p.position) x[0] += x[2] > 0.5 ? 0.005 : -0.005;
    search.update(p, open, sph::SmoothingLengthRule::neighbour_number(32));
    REQUIRE(test::listed(search.list(), p.size()) == brute_force(p, open));
    for (double h : p.smoothing_length) h_min = std::min(h_min, h), h_max = std::max(h_max, h);
  }
  INFO("h from " << h_min << " to " << h_max << "; reuses " << search.reuses());
  CHECK(h_max > 10 * h_min);
  CHECK(search.reuses() > 0);
}
