// Tests of the penetration diagnostic (lib/sph/measures/penetration.hpp): hand-countable cases, the
// merge-sort count against a brute-force double loop, ties in 2D lattices, periodic unwrapping,
// and clear errors for bad input.

#include "sph/measures/penetration.hpp"

#include <catch2/catch.hpp>

#include <random>
#include <vector>

using sph::Vec;

namespace {

/// x_i = i * dx on a line.
std::vector<Vec<1>> line(int n, double dx = 1.0) {
  std::vector<Vec<1>> x(n);
  for (int i = 0; i < n; ++i) x[i] << i * dx;
  return x;
}

const sph::Box<1> open_line = [] {
  sph::Box<1> b;
  b.periodic = {false};
  return b;
}();

/// Pairs i < j (by initial x) now reversed, by the definition.
std::size_t brute_force_inversions(const std::vector<Vec<1>>& x0, const std::vector<Vec<1>>& x) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < x0.size(); ++i)
    for (std::size_t j = 0; j < x0.size(); ++j) count += x0[i][0] < x0[j][0] && x[i][0] > x[j][0];
  return count;
}

}  // namespace

TEST_CASE("particles that keep their order have no inversions", "[penetration]") {
  const auto x0 = line(50);
  SECTION("at rest") {
    const auto r = sph::order_inversions<1>(x0, x0, open_line);
    CHECK(r.all == 0);
    CHECK(r.adjacent == 0);
    CHECK(r.deepest == 0);
    CHECK(r.pairs() == 50 * 49 / 2);
  }
  SECTION("a uniform translation and a compression") {
    auto x = x0;
    for (auto& p : x) p[0] = 0.3 * p[0] + 17.0;
    const auto r = sph::order_inversions<1>(x0, x, open_line);
    CHECK(r.all == 0);
    CHECK(r.deepest == 0);
  }
}

TEST_CASE("hand-counted inversions", "[penetration]") {
  SECTION("two neighbours swap places") {
    const auto x0 = line(10);
    auto x = x0;
    std::swap(x[4], x[5]);
    const auto r = sph::order_inversions<1>(x0, x, open_line);
    CHECK(r.adjacent == 1);
    CHECK(r.all == 1);
    CHECK(r.deepest == Approx(1.0));
    CHECK(r.deepest_behind == 4);
    CHECK(r.deepest_ahead == 5);
  }
  SECTION("the whole line reversed") {
    const int n = 37;
    const auto x0 = line(n);
    auto x = x0;
    for (int i = 0; i < n; ++i) x[i][0] = -x0[i][0];
    const auto r = sph::order_inversions<1>(x0, x, open_line);
    CHECK(r.adjacent == n - 1);
    CHECK(r.all == std::size_t(n) * (n - 1) / 2);
    CHECK(r.deepest == Approx(n - 1.0));  // particle 0 (now at 0) against particle n-1 (now at 1-n)
  }
  SECTION("two streams that have passed through each other keep their own order") {
    // 20 particles at 0..19 moving right by 5.5, 20 at 20..39 moving left by 5.5: each
    // particle of one stream within 11 of the interface has crossed some of the other.
    const auto x0 = line(40);
    auto x = x0;
    for (int i = 0; i < 40; ++i) x[i][0] += i < 20 ? 5.5 : -5.5;
    const auto r = sph::order_inversions<1>(x0, x, open_line);
    CHECK(r.adjacent == 1);  // only the pair that met first: (19, 20)
    CHECK(r.all == brute_force_inversions(x0, x));
    // Particle 19 (now at 24.5) has passed 20..30 (now at 14.5..24.5): 10 strictly; in all
    // sum_{k=1..11} (11 - k) = 55 crossings.
    CHECK(r.all == 55);
    CHECK(r.deepest == Approx(10.0));  // 19 at 24.5 against 20 at 14.5
  }
}

TEST_CASE("the merge-sort count equals the double loop on random motions", "[penetration]") {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> kick(0.0, 3.0);
  for (int trial = 0; trial < 5; ++trial) {
    const auto x0 = line(300, 0.5);
    auto x = x0;
    for (auto& p : x) p[0] += kick(rng);
    const auto r = sph::order_inversions<1>(x0, x, open_line);
    INFO("trial " << trial << ": " << r.summary());
    CHECK(r.all == brute_force_inversions(x0, x));
    // The deepest pair is a real pair that started in order and is now reversed.
    if (r.all > 0) {
      CHECK(x0[r.deepest_behind][0] < x0[r.deepest_ahead][0]);
      CHECK(x[r.deepest_behind][0] - x[r.deepest_ahead][0] == Approx(r.deepest));
    }
  }
}

TEST_CASE("particles in the same lattice plane are not ordered", "[penetration]") {
  // A 2D square lattice: whole columns share an x.  Shuffling particles within a column (a
  // shear along y) changes nothing along x; moving one column past the next does.
  std::vector<Vec<2>> x0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 4; ++j) x0.emplace_back(i, j);
  sph::Box<2> box;
  box.periodic = {false, false};
  auto sheared = x0;
  for (auto& p : sheared) p[1] += 0.7 * p[0];
  CHECK(sph::order_inversions<2>(x0, sheared, box, 0).all == 0);
  auto overtaken = x0;
  for (auto& p : overtaken) {
    if (p[0] == 2.0) p[0] = 3.5;  // column 2 passes column 3
  }
  const auto r = sph::order_inversions<2>(x0, overtaken, box, 0);
  CHECK(r.all == 16);  // 4 x 4 pairs
  CHECK(r.deepest == Approx(0.5));
  // Along y nothing moved.
  CHECK(sph::order_inversions<2>(x0, overtaken, box, 1).all == 0);
}

TEST_CASE("on a periodic axis positions are unwrapped", "[penetration]") {
  // Ten particles in [0, 10) drift right by 2.5: three of them wrap to the left end, but no
  // particle has passed another.
  auto box = sph::Box<1>::periodic_box(Vec<1>(0.0), Vec<1>(10.0));
  std::vector<Vec<1>> x0(10), x(10);
  for (int i = 0; i < 10; ++i) {
    x0[i] << i + 0.5;
    x[i] = box.wrap(x0[i] + Vec<1>(2.5));
  }
  CHECK(sph::order_inversions<1>(x0, x, box).all == 0);
  // Without unwrapping (an open line) the wrapped three would seem to have passed the rest.
  CHECK(sph::order_inversions<1>(x0, x, open_line).all == 21);
}

TEST_CASE("bad input stops with a message", "[penetration]") {
  const auto x0 = line(5);
  auto x = line(4);
  CHECK_THROWS_WITH(sph::order_inversions<1>(x0, x, open_line),
                    Catch::Contains("5 initial positions for 4"));
  x = x0;
  x[2][0] = std::nan("");
  CHECK_THROWS_WITH(sph::order_inversions<1>(x0, x, open_line), Catch::Contains("particle 2"));
  CHECK_THROWS_WITH(sph::order_inversions<1>(x0, x0, open_line, 1), Catch::Contains("axis 1"));
}
