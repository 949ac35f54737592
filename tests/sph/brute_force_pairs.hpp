#pragma once
// The reference the neighbour-list tests compare against: every pair found by trying every
// particle against every other, and every periodic image that can possibly reach.
#include "sph/neighbours.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <tuple>

namespace test {

/// (i, j, image) triples: j, or its periodic image `image`, is a neighbour of i.
using PairSet = std::set<std::tuple<std::size_t, std::uint32_t, sph::Image>>;

/// Every (i, j, image) with |x_i - x_j - image offset| < 2 max(h_i, h_j).
template <int D>
PairSet brute_force(const sph::Particles<D>& p, const sph::Box<D>& box) {
  PairSet pairs;
  const double hmax = *std::max_element(p.smoothing_length.begin(), p.smoothing_length.end());
  std::array<int, D> reach{};
  for (int a = 0; a < D; ++a)
    reach[a] = box.periodic[a] ? static_cast<int>(std::ceil(4 * hmax / box.length(a))) + 1 : 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = 0; j < p.size(); ++j) {
      std::array<int, D> k{};
      for (int a = 0; a < D; ++a) k[a] = -reach[a];
      while (true) {
        sph::Vec<D> offset = sph::Vec<D>::Zero();
        for (int a = 0; a < D; ++a) offset[a] = k[a] * (box.periodic[a] ? box.length(a) : 0.0);
        const sph::Image image = sph::pack_image<D>(k);
        const double r = (p.position[i] - p.position[j] - offset).norm();
        const double reach_ij = 2.0 * std::max(p.smoothing_length[i], p.smoothing_length[j]);
        if (!(i == j && image == 0) && r < reach_ij)
          pairs.insert({i, static_cast<std::uint32_t>(j), image});
        int a = 0;
        while (a < D && k[a] == reach[a]) {
          k[a] = -reach[a];
          ++a;
        }
        if (a == D) break;
        ++k[a];
      }
    }
  }
  return pairs;
}

/// The pairs a neighbour list holds for particles 0..n-1.
template <int D>
PairSet listed(const sph::NeighbourList<D>& list, std::size_t n) {
  PairSet pairs;
  for (std::size_t i = 0; i < n; ++i)
    for (const auto& nb : list.of(i)) pairs.insert({i, nb.index, nb.image});
  return pairs;
}

}  // namespace test
