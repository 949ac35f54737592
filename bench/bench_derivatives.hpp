#pragma once
// The cost of second derivatives (chapter 7): on the settled 3D set of Watkins' static tests
// (60 neighbours, constant h) at 5000 and 40000 particles, microseconds per particle of the
// density pass, of one first-derivative pass (the velocity gradient, sph/derivatives), of
// Watkins' curl curl (two passes), Flebbe's and Brookshaw's; and of one evaluation of the step
// with the pressure force alone and with Watkins' Navier-Stokes viscosity added (its gradient
// pass and its pair accelerations).  The parts alternate within each repeat; medians of 7.

#include "sph/derivatives/brookshaw_1985.hpp"
#include "sph/derivatives/flebbe_1994.hpp"
#include "sph/derivatives/watkins_1996_two_pass.hpp"
#include "sph/setups/watkins_static.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/pressure.hpp"
#include "sph/terms/watkins_1996.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

namespace bench {

namespace derivatives_detail {

struct PressureScene : sph::Scene<3> {
  using Terms = sph::Terms<sph::PressureHernquistKatz>;
};
struct ViscousScene : sph::Scene<3> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, sph::WatkinsViscosity<3>>;
};

inline double seconds_of(const std::function<void()>& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace derivatives_detail

inline void bench_derivatives(bool quick) {
  using namespace derivatives_detail;
  namespace dv = sph::derivatives;
  const int threads = omp_get_num_procs();
  const int repeats = quick ? 3 : 7;
  const std::vector<std::size_t> sizes =
      quick ? std::vector<std::size_t>{2000} : std::vector<std::size_t>{5000, 40000};
  std::printf(
      "\nSecond derivatives (chapter 7), settled 3D set, 60 neighbours, constant h; "
      "microseconds per particle, median of %d\n",
      repeats);
  const char* parts[] = {"density pass",        "first derivatives",   "Watkins curl curl",
                         "Flebbe curl curl",    "Brookshaw Laplacian", "step: pressure",
                         "step: + NS viscosity"};
  constexpr int n_parts = 7;
  for (const std::size_t n : sizes) {
    sph::Particles<3> p = sph::setups::watkins_settled_set<3>(n, 60, 5);
    for (std::size_t i = 0; i < n; ++i) {
      p.velocity[i] = sph::Vec<3>(std::sin(2 * std::numbers::pi * p.position[i][1]), 0, 0);
      p.internal_energy[i] = 1;
    }
    const sph::Box<3> box = sph::setups::unit_box<3>();
    sph::NeighbourSearch<3> search;
    search.update(p, box, sph::SmoothingLengthRule::fixed());
    sph::compute_density<3>(p, search.list(), sph::DensityForm::watkins());
    const dv::ParticleSet<3> set(p, search.list(), box);
    const std::vector<sph::Vec<3>> v(p.velocity.begin(), p.velocity.end());
    const std::span<const sph::Vec<3>> vs(v);
    sph::Settings settings;
    settings.smoothing = sph::SmoothingLengthRule::fixed();
    settings.density = sph::DensityForm::watkins();
    sph::Simulation<PressureScene> pressure(p, box, settings);
    sph::Simulation<ViscousScene> viscous(p, box, sph::WatkinsViscosity<3>({0.1, 0.05}), settings);
    sph::Particles<3> q = p;
    const std::function<void()> run[n_parts] = {
        [&] { sph::compute_density<3>(q, search.list(), sph::DensityForm::watkins()); },
        [&] { (void)dv::jacobian(set, vs); },
        [&] { (void)dv::curl_curl(set, vs); },
        [&] { (void)dv::flebbe::curl_curl(set, vs); },
        [&] { (void)dv::brookshaw::laplacian(set, vs); },
        [&] { pressure.evaluate(); },
        [&] { viscous.evaluate(); }};
    for (int t : {threads, 1}) {
      omp_set_num_threads(t);
      std::vector<double> times[n_parts];
      for (int r = 0; r < repeats; ++r)
        for (int k = 0; k < n_parts; ++k) times[k].push_back(seconds_of(run[k]));
      std::printf("  N = %zu, %d thread(s):\n", n, t);
      const double density = [&] {
        std::sort(times[0].begin(), times[0].end());
        return times[0][times[0].size() / 2];
      }();
      for (int k = 0; k < n_parts; ++k) {
        std::sort(times[k].begin(), times[k].end());
        const double median = times[k][times[k].size() / 2];
        std::printf("    %-22s %8.3f us/particle  (%5.2f x the density pass)\n", parts[k],
                    median / static_cast<double>(n) * 1e6, median / density);
      }
    }
    omp_set_num_threads(threads);
  }
}

}  // namespace bench
