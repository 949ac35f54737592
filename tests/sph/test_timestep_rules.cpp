// The two time-step rules of the step: Selhammar's eq 7 (the particle's own speed and the
// viscosity's share in the signal speed) and the pair signal velocity of Monaghan (1997).  The
// second must be Galilean invariant, the first is not; the second's first step on Sod's tube is
// known in closed form; and a Sod tube run with it stays accurate.
#include "sph/setups/shock_tube.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/pressure.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

struct ViscousGas1 : sph::Scene<1> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983>;
};
using Rule = sph::Settings::TimestepRule;

struct Run {
  long steps = 0;
  double first_dt = 0;
  double l1_rho = 0, l1_v = 0;
  std::string limit;
};

// Sod's periodic tube at 400 particles per unit length on the dense side, every particle moving
// with `boost` on top of Sod's states, run to t; the errors are taken in the frame moving with
// the boost (x - boost t, wrapped into the tube; v - boost).
Run run_sod(Rule rule, double boost, double t) {
  sph::ShockTubeSetup setup = sph::ShockTubeSetup::sod();
  setup.left_spacing = 1.0 / 400;
  const auto smoothing = sph::SmoothingLengthRule::from_density(4);
  sph::ShockTube<1> tube = sph::make_shock_tube<1>(setup, smoothing);
  for (auto& v : tube.particles.velocity) v[0] += boost;
  sph::Settings settings;
  settings.smoothing = smoothing;
  settings.timestep_rule = rule;
  sph::Simulation<ViscousGas1> sim(tube.particles, tube.box, sph::IdealGas(1.4),
                                   sph::MonaghanGingold1983(1, 2), settings);
  Run run;
  run.first_dt = sim.allowed_timestep().dt;
  sim.run_until(t, [&](const auto& s) {
    if (s.last_limit().criterion != "output time") run.limit = s.last_limit().criterion;
  });
  run.steps = sim.steps();
  sph::Particles<1> p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.position[i] = tube.box.wrap(p.position[i] - sph::Vec<1>::Constant(boost * t));
    p.velocity[i][0] -= boost;
  }
  const auto errors = sph::shock_tube_errors(p, tube.exact, t);
  run.l1_rho = errors[0].L1;
  run.l1_v = errors[1].L1;
  return run;
}

}  // namespace

TEST_CASE("the signal-velocity time step is Galilean invariant, eq 7 is not", "[timestep]") {
  const double t = 0.05;
  const Run rest_signal = run_sod(Rule::signal_velocity, 0.0, t);
  const Run boosted_signal = run_sod(Rule::signal_velocity, 3.0, t);
  const Run rest_eq7 = run_sod(Rule::selhammar_eq7, 0.0, t);
  const Run boosted_eq7 = run_sod(Rule::selhammar_eq7, 3.0, t);
  // Only relative velocities enter: the boost changes the steps by round-off, if at all.
  CHECK(std::abs(boosted_signal.steps - rest_signal.steps) <= 1);
  CHECK(boosted_signal.first_dt == Approx(rest_signal.first_dt).epsilon(1e-12));
  // Eq 7 has |v_i| in its signal speed: a boost of 3 (2.5 sound speeds) multiplies the steps.
  CHECK(boosted_eq7.steps > 2 * rest_eq7.steps);
  // The answer in the moving frame is the same with the boost (to the integration's error).
  CHECK(boosted_signal.l1_rho == Approx(rest_signal.l1_rho).epsilon(0.02));
}

TEST_CASE("the signal-velocity step on Sod's tube: the first step and the count", "[timestep]") {
  // At rest, v_sig = c_i + c_j; the smallest h/v_sig is on the dense side, h = dx = 1/400
  // (h from the density with N = 4), c = sqrt(1.4): dt = 0.3 h / (2c).
  const double dt0 = 0.3 * (1.0 / 400) / (2 * std::sqrt(1.4));
  const Run signal = run_sod(Rule::signal_velocity, 0.0, 0.2);
  CHECK(signal.first_dt == Approx(dt0).epsilon(1e-6));
  CHECK(signal.limit == "signal velocity");
  // The shock raises v_sig only in a few particles of the thin, wide-h side, so the count stays
  // close to t/dt0; eq 7 with alpha = 1 takes 1 + 1.2 alpha = 2.2 sound speeds at rest, 10 %
  // more steps.
  const double at_rest = 0.2 / dt0;
  CHECK(signal.steps >= at_rest);
  CHECK(signal.steps < 1.05 * at_rest);
  const Run eq7 = run_sod(Rule::selhammar_eq7, 0.0, 0.2);
  CHECK(eq7.steps > 1.08 * signal.steps);
  CHECK(eq7.limit == "Courant (eq 7)");
}

TEST_CASE("a Sod tube with the signal-velocity step at twice the Courant factor is stable",
          "[timestep]") {
  sph::ShockTubeSetup setup = sph::ShockTubeSetup::sod();
  setup.left_spacing = 1.0 / 400;
  const auto smoothing = sph::SmoothingLengthRule::from_density(4);
  const sph::ShockTube<1> tube = sph::make_shock_tube<1>(setup, smoothing);
  const auto run = [&](Rule rule, double courant) {
    sph::Settings settings;
    settings.smoothing = smoothing;
    settings.timestep_rule = rule;
    settings.courant = courant;
    sph::Simulation<ViscousGas1> sim(tube.particles, tube.box, sph::IdealGas(1.4),
                                     sph::MonaghanGingold1983(1, 2), settings);
    sim.run_until(0.2);
    return sph::shock_tube_errors(sim.particles(), tube.exact, 0.2);
  };
  const auto eq7 = run(Rule::selhammar_eq7, 0.3);
  const auto signal = run(Rule::signal_velocity, 0.6);
  // No ringing or blow-up: the errors stay within 10 % of those of eq 7's shorter steps.
  CHECK(signal[0].L1 < 1.1 * eq7[0].L1);
  CHECK(signal[1].L1 < 1.1 * eq7[1].L1);
  CHECK(signal[2].Linf < 1.1 * eq7[2].Linf);
}

TEST_CASE("the signal-velocity rule refuses a negative beta", "[timestep]") {
  sph::Particles<1> p;
  p.add(sph::Vec<1>(0.0), sph::Vec<1>(0.0), 1.0, 1.0);
  p.add(sph::Vec<1>(0.5), sph::Vec<1>(0.0), 1.0, 1.0);
  sph::Settings settings;
  settings.smoothing = sph::SmoothingLengthRule::from_density(4);
  settings.timestep_rule = Rule::signal_velocity;
  settings.signal_beta = -1;
  const auto box = sph::Box<1>::periodic_box(sph::Vec<1>(0.0), sph::Vec<1>(1.0));
  CHECK_THROWS_WITH((sph::Simulation<ViscousGas1>(p, box, settings)),
                    Catch::Contains("signal velocity's beta"));
}

TEST_CASE("each particle's own step: the global step is the least of them", "[timestep]") {
  // Sod's tube after a few steps, both rules: the particles' own steps differ (the dense side
  // has a smaller h, the shock a larger signal speed), and the global step is their minimum,
  // to the bit, with the criterion of the particle that sets it.
  for (const Rule rule : {Rule::selhammar_eq7, Rule::signal_velocity}) {
    sph::ShockTubeSetup setup = sph::ShockTubeSetup::sod();
    setup.left_spacing = 1.0 / 200;
    const auto smoothing = sph::SmoothingLengthRule::from_density(4);
    sph::ShockTube<1> tube = sph::make_shock_tube<1>(setup, smoothing);
    sph::Settings settings;
    settings.smoothing = smoothing;
    settings.timestep_rule = rule;
    sph::Simulation<ViscousGas1> sim(tube.particles, tube.box, sph::IdealGas(1.4),
                                     sph::MonaghanGingold1983(1, 2), settings);
    for (int k = 0; k < 20; ++k) sim.step();
    std::vector<double> own;
    sim.particle_timesteps(own);
    REQUIRE(own.size() == sim.particles().size());
    const auto least = std::min_element(own.begin(), own.end());
    const sph::TimestepLimit global = sim.allowed_timestep();
    CHECK(*least == global.dt);
    CHECK(static_cast<std::size_t>(least - own.begin()) == global.particle);
    // the steps spread: the largest is well above the least
    CHECK(*std::max_element(own.begin(), own.end()) > 1.5 * *least);
  }
}
