// Individual time steps (individual_leapfrog.hpp): the evaluation of a subset of the particles
// gives each of them what an evaluation of all gives, to the bit, and leaves the others alone;
// with every particle on one level the scheme is the leapfrog, to round-off; on the Evrard
// collapse it follows the run with one step for all while it updates far fewer particles.
#include "brute_force_pairs.hpp"
#include "sph/gravity/direct.hpp"
#include "sph/gravity/tree.hpp"
#include "sph/integration/individual_leapfrog.hpp"
#include "sph/measures/diagnostics.hpp"
#include "sph/setups/evrard.hpp"
#include "sph/setups/sedov.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/pressure.hpp"
#include "sph/terms/selhammar_1997.hpp"

#include <catch2/catch.hpp>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <tuple>
#include <vector>

namespace {

struct Standard : sph::Scene<3> {
  using Terms = sph::Terms<sph::PressureOwnWork, sph::MonaghanGingold1983>;
  using Gravity = sph::TreeGravity;
};
struct StandardOwnSteps : Standard {
  using Integrator = sph::IndividualLeapfrog<3>;
};
// Selhammar's modified viscosity: a term that changes v at the kicks, with gravity.
struct Modified : sph::Scene<3> {
  using Terms = sph::Terms<sph::PressureOwnWork, sph::RestrictedVonNeumannRichtmyer,
                           sph::SelhammarCollective<3>>;
  using Gravity = sph::TreeGravity;
};
struct ModifiedOwnSteps : Modified {
  using Integrator = sph::IndividualLeapfrog<3>;
};

// The Evrard sphere of `setup` with the standard viscosity and individual time steps.
sph::Simulation<StandardOwnSteps> standard_own_steps(
    const sph::EvrardSetup& setup, const sph::IndividualLeapfrog<3>& integrator = {}) {
  return sph::Simulation<StandardOwnSteps>(
      sph::make_evrard_sphere(setup), sph::Box<3>::open(),
      typename Standard::Terms{{}, sph::MonaghanGingold1983{1, 2, 1e-4}},
      sph::IdealGas{setup.gamma}, integrator);
}

std::vector<std::uint32_t> every_third(std::size_t n) {
  std::vector<std::uint32_t> list;
  for (std::size_t i = 1; i < n; i += 3) list.push_back(static_cast<std::uint32_t>(i));
  return list;
}

template <class Gravity>
void check_subset(Gravity gravity, const char* name) {
  sph::EvrardSetup setup;
  setup.particles = 3000;
  sph::Particles<3> all = sph::make_evrard_sphere(setup);
  for (std::size_t i = 0; i < all.size(); ++i) all.smoothing_length[i] = 0.05 + 1e-5 * i;
  sph::Particles<3> some = all;
  const sph::Vec<3> untouched(7, 8, 9);
  for (auto& a : some.acceleration) a = untouched;
  gravity.add_accelerations(all, sph::Box<3>::open());
  const std::vector<double> potential_all = gravity.potential();
  const std::vector<std::uint32_t> list = every_third(all.size());
  gravity.add_accelerations(some, sph::Box<3>::open(), sph::ActiveSet{&list});
  std::size_t same = 0, kept = 0, k = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (k < list.size() && list[k] == i) {
      ++k;
      same += some.acceleration[i] == sph::Vec<3>(all.acceleration[i] + untouched) &&
              gravity.potential()[i] == potential_all[i];
    } else {
      kept += some.acceleration[i] == untouched;
    }
  }
  std::printf(
      "  %s on a third of 3000 particles: %zu of %zu the same to the bit, %zu of %zu "
      "untouched\n",
      name, same, list.size(), kept, all.size() - list.size());
  CHECK(same == list.size());
  CHECK(kept == all.size() - list.size());
}

}  // namespace

TEST_CASE(
    "gravity of a subset of the particles: each as in an evaluation of all, the others "
    "untouched",
    "[individual]") {
  check_subset(sph::TreeGravity{}, "tree");
  check_subset(sph::DirectGravity{}, "direct summation");
}

TEST_CASE("individual time steps with every particle on one level are the leapfrog, to round-off",
          "[individual]") {
  // A fixed step puts every particle on the block's one level: every step is a whole block.
  sph::EvrardSetup setup;
  setup.particles = 1000;
  sph::Settings settings;
  settings.fixed_timestep = 2e-3;
  const typename Modified::Terms terms{{}, {2, 1e-4}, {1, 64}};
  sph::Simulation<Modified> global(sph::make_evrard_sphere(setup), sph::Box<3>::open(), terms,
                                   sph::IdealGas{setup.gamma}, settings);
  sph::Simulation<ModifiedOwnSteps> own(sph::make_evrard_sphere(setup), sph::Box<3>::open(), terms,
                                        sph::IdealGas{setup.gamma}, settings);
  for (int s = 0; s < 12; ++s) {
    global.step();
    own.step();
  }
  // (not to the bit: the compiler may fuse a multiplication and an addition of a kick in one
  // integrator and not in the other, a difference in the last bit)
  const auto& a = global.particles();
  const auto& b = own.particles();
  double dx = 0, dv = 0, du = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    dx = std::max(dx, (a.position[i] - b.position[i]).norm() / a.position[i].norm());
    dv = std::max(dv, (a.velocity[i] - b.velocity[i]).norm() / a.velocity[i].norm());
    du = std::max(du, std::abs(a.internal_energy[i] / b.internal_energy[i] - 1));
  }
  std::printf(
      "  one level, 12 steps of the modified viscosity with gravity: largest relative "
      "difference in x %.1e, v %.1e, u %.1e\n",
      dx, dv, du);
  CHECK(dx < 1e-13);
  CHECK(dv < 1e-13);
  CHECK(du < 1e-13);
  CHECK(own.synchronised());
  CHECK(own.time() == global.time());
}

TEST_CASE(
    "individual time steps on the Evrard collapse: the energies of one step for all, with "
    "fewer updates",
    "[individual]") {
  sph::EvrardSetup setup;
  setup.particles = 2048;
  const typename Standard::Terms terms{{}, sph::MonaghanGingold1983{1, 2, 1e-4}};
  sph::Simulation<Standard> global(sph::make_evrard_sphere(setup), sph::Box<3>::open(), terms,
                                   sph::IdealGas{setup.gamma});
  sph::Simulation<StandardOwnSteps> own(sph::make_evrard_sphere(setup), sph::Box<3>::open(), terms,
                                        sph::IdealGas{setup.gamma});
  const auto energy = [](const auto& s) {
    return sph::kinetic_energy(s.particles()) + sph::thermal_energy(s.particles()) +
           s.potential_energy();
  };
  const double e0 = energy(global);
  double updates_global = 0, updates_own = 0;
  bool mid_block = false;
  global.run_until(0.8, [&](const auto& s) { updates_global += s.evaluated(); });
  own.run_until(0.8, [&](const auto& s) {
    updates_own += s.evaluated();
    mid_block = mid_block || !s.synchronised();
  });
  REQUIRE(own.synchronised());
  const double kinetic[2] = {sph::kinetic_energy(global.particles()),
                             sph::kinetic_energy(own.particles())};
  const double thermal[2] = {sph::thermal_energy(global.particles()),
                             sph::thermal_energy(own.particles())};
  const double potential[2] = {global.potential_energy(), own.potential_energy()};
  const double error[2] = {std::abs(energy(global) / e0 - 1), std::abs(energy(own) / e0 - 1)};
  std::printf(
      "  Evrard, 2048 particles, t = 0.8: E_kin %.5f / %.5f, E_th %.5f / %.5f, "
      "W %.5f / %.5f, |dE/E| %.2e / %.2e (one step for all / individual); particle "
      "updates %.0f / %.0f\n",
      kinetic[0], kinetic[1], thermal[0], thermal[1], potential[0], potential[1], error[0],
      error[1], updates_global, updates_own);
  CHECK(mid_block);
  CHECK(std::abs(kinetic[1] / kinetic[0] - 1) < 0.01);
  CHECK(std::abs(thermal[1] / thermal[0] - 1) < 0.01);
  CHECK(std::abs(potential[1] / potential[0] - 1) < 0.005);
  CHECK(error[1] < 1.5 * error[0]);
  CHECK(updates_own < 0.7 * updates_global);
}

TEST_CASE("individual time steps: an output time inside a block is refused with a message",
          "[individual]") {
  sph::EvrardSetup setup;
  setup.particles = 1000;
  sph::Simulation<StandardOwnSteps> own = standard_own_steps(setup);
  while (own.synchronised() && own.time() < 0.5) own.step();
  REQUIRE_FALSE(own.synchronised());
  CHECK_THROWS_WITH(own.step(1e-9), Catch::Contains("inside a block"));
}

TEST_CASE("individual time steps: an impossible limiter is refused with a message",
          "[individual]") {
  sph::EvrardSetup setup;
  setup.particles = 500;
  for (const double limiter : {0.5, -1.0, std::nan("")}) {
    sph::IndividualLeapfrog<3> integrator;
    integrator.limiter = limiter;
    sph::Simulation<StandardOwnSteps> own = standard_own_steps(setup, integrator);
    CHECK_THROWS_WITH(own.step(), Catch::Contains("limiter must be 0 (off)"));
  }
}

TEST_CASE("individual time steps: each evaluated particle's neighbours are the brute-force ones",
          "[individual]") {
  // Only the particles whose step ends get a new h and a list (neighbour_search.hpp); their
  // lists must hold every pair within 2 max(h_i, h_j), with the h the others kept.
  sph::EvrardSetup setup;
  setup.particles = 1000;
  sph::Simulation<StandardOwnSteps> own = standard_own_steps(setup);
  own.run_until(0.7);
  const auto n = static_cast<std::size_t>(setup.particles);
  long partial = 0, compared = 0, wrong = 0, listed_inactive = 0;
  for (int s = 0; s < 60; ++s) {
    own.step();
    const auto& active = own.integrator().active();
    partial += active.size() < n;
    const test::PairSet expected = test::brute_force(own.particles(), sph::Box<3>::open());
    const test::PairSet found = test::listed(own.neighbours(), n);
    std::vector<std::uint8_t> is_active(n, 0);
    for (const std::uint32_t i : active) is_active[i] = 1;
    for (const auto& pair : expected) {
      if (!is_active[std::get<0>(pair)]) continue;
      ++compared;
      wrong += found.count(pair) == 0;
    }
    for (const auto& pair : found) {
      if (is_active[std::get<0>(pair)])
        wrong += expected.count(pair) == 0;
      else
        ++listed_inactive;
    }
  }
  std::printf(
      "  60 steps from t = 0.7 (1000 particles, %ld of them partial): %ld pairs of "
      "evaluated particles compared, %ld missing or extra; %ld pairs listed for others\n",
      partial, compared, wrong, listed_inactive);
  CHECK(partial > 30);
  CHECK(compared > 0);
  CHECK(wrong == 0);
  CHECK(listed_inactive == 0);
}

// A point explosion in cold gas (Saitoh & Makino's test of the limiter): the hot particles
// need steps far shorter than the gas around them.
struct Blast : sph::Scene<3> {
  using Terms = sph::Terms<sph::PressureOwnWork, sph::MonaghanGingold1983>;
  using Integrator = sph::IndividualLeapfrog<3>;
};

TEST_CASE("individual time steps: particles that start together are within the limiter's factor",
          "[individual]") {
  // The particles whose steps end at one moment start their next steps together, and each
  // takes at most `limiter` times the step of any neighbour starting with it -- also when that
  // neighbour's own step was shortened for a third particle (the limiter is applied until
  // nothing changes).  The lists are those of the evaluation that ended their steps.
  sph::SedovSetup setup;
  setup.cells = 10;
  const auto rule = sph::SmoothingLengthRule::neighbour_number(40);
  sph::SedovBlast<3> blast = sph::make_sedov_blast<3>(setup, rule);
  const auto n = blast.particles.size();
  sph::Settings settings;
  settings.smoothing = rule;
  sph::Simulation<Blast> own(std::move(blast.particles), blast.box,
                             Blast::Terms{{}, sph::MonaghanGingold1983{1, 2, 1e-4}},
                             sph::IdealGas{setup.gamma}, settings);
  const double limiter = own.integrator().limiter;
  long pairs = 0, beyond = 0;
  double worst = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> listed;  // neighbours starting together
  for (int s = 0; s < 150; ++s) {
    own.step();
    for (const auto& [i, j] : listed) {
      const double ratio = own.integrator().step_length(i) / own.integrator().step_length(j);
      ++pairs;
      beyond += ratio > limiter;
      worst = std::max(worst, ratio);
    }
    std::vector<std::uint8_t> starts(n, 0);
    for (const std::uint32_t i : own.integrator().active()) starts[i] = 1;
    listed.clear();
    for (const std::uint32_t i : own.integrator().active()) {
      for (const auto& nb : own.neighbours().of(i)) {
        if (starts[nb.index]) listed.emplace_back(i, static_cast<std::uint32_t>(nb.index));
      }
    }
  }
  std::printf(
      "  point explosion, %zu particles, 150 steps to t = %.3g: %ld pairs starting together, "
      "%ld of them more than %g times apart; largest ratio %g\n",
      n, own.time(), pairs, beyond, limiter, worst);
  CHECK(pairs > 0);
  CHECK(beyond == 0);
}

TEST_CASE("individual time steps: the same to the bit with 1 and 2 threads", "[individual]") {
  // 4096 particles: every parallel loop of the scheme (the limiter's sweeps, the drift, the
  // kicks) and of the step (search, tree) runs on the threads.  Steps into the collapse, where
  // the particles spread over several levels and the limiter shortens some.
  sph::EvrardSetup setup;
  setup.particles = 4096;
  const int saved = omp_get_max_threads();
  const auto run = [&setup](int threads) {
    omp_set_num_threads(threads);
    auto sim = standard_own_steps(setup);
    long updates = 0;
    for (int s = 0; s < 40; ++s) {
      sim.step();
      updates += static_cast<long>(sim.evaluated());
    }
    return std::make_tuple(sim.particles(), sim.time(), updates);
  };
  const auto [one, t_one, updates_one] = run(1);
  const auto [two, t_two, updates_two] = run(2);
  omp_set_num_threads(saved);
  std::printf("  Evrard, 4096 particles, 40 individual steps to t = %.4f: %ld particle updates\n",
              t_one, updates_one);
  CHECK(updates_one < 40L * 4096);
  CHECK(t_one == t_two);
  CHECK(updates_one == updates_two);
  CHECK(one.position == two.position);
  CHECK(one.velocity == two.velocity);
  CHECK(one.internal_energy == two.internal_energy);
  CHECK(one.smoothing_length == two.smoothing_length);
}
