// The atlas of stiff and extreme cases: every scheme run where it is hardest, one row per case
// and scheme, and the Sedov-Taylor blast against its self-similar solution.
//
// Each row is one run: a case (a very strong shock tube, a near vacuum, a vacuum that opens,
// Mach-100 streams, gamma near 1 and gamma = 10, the Sedov blast, a Galilean boost, degenerate
// input), its dimension, the scheme (the symmetric energy equation of Hernquist & Katz against
// each particle heated by its own pressure's work, sph::PressureOwnWork; the Monaghan-Gingold
// viscosity on or off), and what happened: ran to the end time, or stopped with the library's
// message.  A stop with a clear message is a legitimate outcome; a NaN, a crash or a hang is
// not.  For each run we also report the conservation of momentum and energy, the criterion that
// limited the time step most often, the steps and the wall time.
//
// The program writes stiff_cases.md (a page of the documentation, "Stiff and extreme cases"),
// the Sedov figure and summary.txt into its output directory (figures/atlas by default).  With
// --quick every case runs at a small resolution in seconds: that is the ctest.
#include "app/chapter.hpp"
#include "app/stopwatch.hpp"
#include "plot/figure.hpp"
#include "sph/measures/diagnostics.hpp"
#include "sph/measures/penetration.hpp"
#include "sph/reference/riemann.hpp"
#include "sph/reference/sedov_solution.hpp"
#include "sph/setups/colliding_streams.hpp"
#include "sph/setups/sedov.hpp"
#include "sph/setups/shock_tube.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/pressure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

// ---- The schemes ------------------------------------------------------------------------------
// The same force in all of them; they differ in who is heated by it, and in the viscosity.
template <int D>
struct SymmetricViscous : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983>;
  static constexpr const char* name = "symmetric + MG";
};
template <int D>
struct OwnWorkViscous : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureOwnWork, sph::MonaghanGingold1983>;
  static constexpr const char* name = "own work + MG";
};
template <int D>
struct OwnWorkInviscid : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureOwnWork>;
  static constexpr const char* name = "own work, no AV";
};

// ---- One row of the atlas ---------------------------------------------------------------------
enum class Expect { anything, runs, stops };

struct Row {
  std::string name;
  int dimension = 1;
  std::string scheme;
  Expect expect = Expect::anything;
  long particles = 0;
  bool ran = false;         // reached t_end
  bool finite = true;       // every field finite where it stopped
  bool unexpected = false;  // an exception other than the library's sph::Error
  std::string message;      // why it stopped
  double t_end = 0, t_reached = 0;
  double momentum_error = std::numeric_limits<double>::quiet_NaN();
  double energy_error = std::numeric_limits<double>::quiet_NaN();
  std::string limiter;  // the criterion that limited the most steps
  long steps = 0;
  double seconds = 0;
  std::string note;
};

template <int D>
struct Run {
  Row row;
  sph::Particles<D> particles;  // where it ended or stopped (empty if it never started)
};

// Every field a run carries on with, finite?
template <int D>
bool all_finite(const sph::Particles<D>& p) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.position[i].allFinite() || !p.velocity[i].allFinite() ||
        !std::isfinite(p.internal_energy[i]) || !std::isfinite(p.density[i]) ||
        !std::isfinite(p.pressure[i]) || !std::isfinite(p.smoothing_length[i]))
      return false;
  }
  return true;
}

template <int D>
double total_energy(const sph::Particles<D>& p) {
  return sph::kinetic_energy(p) + sph::thermal_energy(p);
}

// What a run is given besides its particles.
struct RunLimits {
  double t_end = 0.2;
  long max_steps = 100000;      // the library stops a run that needs more, with a message
  double max_seconds = 120;     // the atlas's own budget, so that no case can hang the page
  std::vector<double> outputs;  // times at which at_output is called (before t_end)
  // Selhammar's eq 7 (the chapters' default) or the signal velocity of Monaghan (1997)
  sph::Settings::TimestepRule timestep = sph::Settings::TimestepRule::selhammar_eq7;
};

// Runs the scene from the particles to t_end, or until the library stops it, and fills the row.
template <class Scene>
Run<Scene::D> run_case(Row row, const sph::Particles<Scene::D>& particles,
                       const sph::Box<Scene::D>& box, double gamma,
                       const sph::SmoothingLengthRule& rule, const RunLimits& limits,
                       const std::function<void(const sph::Simulation<Scene>&)>& at_output = {}) {
  constexpr int D = Scene::D;
  using Sim = sph::Simulation<Scene>;
  row.dimension = D;
  row.scheme = Scene::name;
  row.particles = static_cast<long>(particles.size());
  row.t_end = limits.t_end;
  sph::Settings settings;
  settings.smoothing = rule;
  settings.max_steps = limits.max_steps;
  settings.timestep_rule = limits.timestep;
  std::cerr << "  " << row.name << " (" << D << "D, " << row.scheme << ") ..." << std::flush;
  const app::Stopwatch clock;
  std::optional<Sim> sim;
  std::map<std::string, long> limiting;
  double energy_before = 0;
  sph::Vec<D> momentum_before = sph::Vec<D>::Zero();
  try {
    if constexpr (Scene::Terms::template contains<sph::MonaghanGingold1983>) {
      sim.emplace(particles, box, sph::IdealGas(gamma), settings,
                  sph::MonaghanGingold1983{1.0, 2.0});
    } else {
      sim.emplace(particles, box, sph::IdealGas(gamma), settings);
    }
    energy_before = total_energy(sim->particles());
    momentum_before = sph::total_momentum(sim->particles());
    const auto on_step = [&](const Sim& s) {
      if (s.last_limit().criterion != "output time") ++limiting[s.last_limit().criterion];
      if (clock.seconds() > limits.max_seconds) {
        throw sph::Error("atlas: wall-time budget of " + sph::show(limits.max_seconds) +
                         " s spent at t = " + sph::show(s.time()) + " after " +
                         sph::show(s.steps()) + " steps (last step " +
                         sph::show(s.last_limit().dt) + ", limited by " + s.last_limit().criterion +
                         " at particle " + sph::show(s.last_limit().particle) + ")");
      }
    };
    for (double t : limits.outputs) {
      sim->run_until(t, on_step);
      if (at_output) at_output(*sim);
    }
    sim->run_until(limits.t_end, on_step);
    row.ran = true;
  } catch (const sph::Error& e) {
    row.message = e.what();
  } catch (const std::exception& e) {
    row.message = std::string("unexpected exception: ") + e.what();
    row.unexpected = true;
  }
  row.seconds = clock.seconds();
  Run<D> run;
  if (sim) {
    run.particles = sim->particles();
    row.t_reached = sim->time();
    row.steps = sim->steps();
    row.finite = all_finite(run.particles);
    if (row.finite) {
      row.energy_error = std::abs(total_energy(run.particles) - energy_before) / energy_before;
      const double scale = sph::momentum_scale(run.particles);
      row.momentum_error =
          (sph::total_momentum(run.particles) - momentum_before).norm() / (scale > 0 ? scale : 1);
    }
  }
  long most = 0;
  for (const auto& [criterion, count] : limiting) {
    if (count > most) {
      most = count;
      row.limiter = criterion + ", " + std::to_string(100 * count / std::max(1L, row.steps)) + " %";
    }
  }
  std::cerr << (row.ran ? " ran" : " stopped") << ", " << row.steps << " steps, " << row.seconds
            << " s\n";
  run.row = row;
  return run;
}

// ---- Tubes the shock-tube set-up cannot build --------------------------------------------------
// A 1D tube of one lattice spacing on both sides and masses rho dx, so that a density ratio of
// a million is a mass ratio, not a spacing ratio (equal masses would leave one particle on the
// light side); and two states that the exact solver refuses (a vacuum opens between them).
sph::Particles<1> two_state_tube(const sph::GasState& left, const sph::GasState& right,
                                 double gamma, double spacing) {
  const sph::IdealGas gas(gamma);
  sph::Particles<1> p;
  const int cells = static_cast<int>(std::lround(1.0 / spacing));
  const double dx = 1.0 / cells;
  for (int k = -cells; k < cells; ++k) {
    const double x = (k + 0.5) * dx;
    const sph::GasState& s = x < 0 ? left : right;
    p.add(sph::Vec<1>(x), sph::Vec<1>(s.velocity), s.density * dx,
          gas.internal_energy(s.density, s.pressure));
  }
  return p;
}

// The fastest particle and the smallest h: what sets a Courant step.
template <int D>
std::string extremes(const sph::Particles<D>& p) {
  double v = 0, h = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    v = std::max(v, p.velocity[i].norm());
    h = std::min(h, p.smoothing_length[i]);
  }
  char text[80];
  std::snprintf(text, sizeof text, "fastest particle %.3g, smallest h %.3g", v, h);
  return text;
}

// ---- The page's numbers ------------------------------------------------------------------------
std::string number(double x, const char* format = "%.3g") {
  if (!std::isfinite(x)) return "-";
  char text[64];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

// A message as a table cell: in code font, without the characters that end a cell.
std::string cell_message(std::string text) {
  std::replace(text.begin(), text.end(), '|', '/');
  std::replace(text.begin(), text.end(), '`', '\'');
  std::replace(text.begin(), text.end(), '\n', ' ');
  return "`" + text + "`";
}

std::string outcome(const Row& r) {
  if (r.ran) return "ran to t = " + number(r.t_end);
  if (r.unexpected) return "CRASHED: " + cell_message(r.message);
  return "stopped at t = " + number(r.t_reached) + ": " + cell_message(r.message);
}

// ---- The Sedov blast ---------------------------------------------------------------------------
struct SedovParameters {
  double gamma = 5.0 / 3.0;
  int cells = 32;
  double neighbours = 64;
  double final_radius = 0.35;  // the run ends when the exact shock reaches this radius
  int outputs = 10;            // times at which the shock radius is measured
};

// The radius of the densest shell: mean density in shells of width dr, its maximum.
template <int D>
double shell_peak_radius(const sph::Particles<D>& p, double dr, double r_max) {
  const int shells = static_cast<int>(r_max / dr);
  std::vector<double> sum(shells, 0.0);
  std::vector<int> count(shells, 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int k = static_cast<int>(p.position[i].norm() / dr);
    if (k >= shells) continue;
    sum[k] += p.density[i];
    ++count[k];
  }
  int best = 0;
  double best_density = -1;
  for (int k = 0; k < shells; ++k) {
    if (count[k] == 0) continue;
    const double mean = sum[k] / count[k];
    if (mean > best_density) {
      best_density = mean;
      best = k;
    }
  }
  return (best + 0.5) * dr;
}

struct SedovResult {
  Row row;
  std::vector<double> times, radius_sph, radius_exact;
  double l1_density = 0;    // mean |rho - rho_exact| over the particles inside 1.2 R
  double radius_error = 0;  // the largest |R_sph / R - 1| over the outputs
  std::string figure;
};

template <class Scene>
SedovResult run_sedov(const SedovParameters& par, app::Chapter& chapter, bool draw) {
  sph::SedovSetup setup;
  setup.gamma = par.gamma;
  setup.cells = par.cells;
  const auto rule = sph::SmoothingLengthRule::neighbour_number(par.neighbours, 2);
  const sph::SedovBlast<3> blast = sph::make_sedov_blast<3>(setup, rule);
  const sph::SedovSolution& exact = blast.exact;
  RunLimits limits;
  limits.t_end = exact.time_at_radius(par.final_radius);
  for (int k = 1; k < par.outputs; ++k) limits.outputs.push_back(limits.t_end * k / par.outputs);
  SedovResult result;
  const double dr = 0.5 * blast.spacing;
  const auto measure = [&](const sph::Simulation<Scene>& s) {
    result.times.push_back(s.time());
    result.radius_sph.push_back(shell_peak_radius(s.particles(), dr, 0.5));
    result.radius_exact.push_back(exact.shock_radius(s.time()));
  };
  Row row;
  row.name = "Sedov blast, gamma = " + number(par.gamma, "%.4g");
  row.expect = Expect::anything;
  Run<3> run = run_case<Scene>(row, blast.particles, blast.box, par.gamma, rule, limits, measure);
  result.row = run.row;
  result.row.note =
      std::to_string(blast.heated) + " particles heated; xi0 = " + number(exact.xi0(), "%.4f");
  if (!run.row.ran || !run.row.finite) return result;
  // The last output: t_end.
  result.times.push_back(limits.t_end);
  result.radius_sph.push_back(shell_peak_radius(run.particles, dr, 0.5));
  result.radius_exact.push_back(exact.shock_radius(limits.t_end));
  for (std::size_t k = 0; k < result.times.size(); ++k)
    result.radius_error =
        std::max(result.radius_error, std::abs(result.radius_sph[k] / result.radius_exact[k] - 1));
  // The density profile against the exact one, inside 1.2 R.
  const double R = exact.shock_radius(limits.t_end);
  double sum = 0;
  int count = 0;
  std::vector<double> r, rho, v, P;
  for (std::size_t i = 0; i < run.particles.size(); ++i) {
    const sph::Vec<3>& x = run.particles.position[i];
    const double ri = x.norm();
    if (ri < 1.2 * R) {
      sum += std::abs(run.particles.density[i] - exact.sample(ri, limits.t_end).density);
      ++count;
    }
    if (ri > 0.5) continue;
    r.push_back(ri);
    rho.push_back(run.particles.density[i]);
    v.push_back(ri > 0 ? run.particles.velocity[i].dot(x) / ri : 0.0);
    P.push_back(run.particles.pressure[i]);
  }
  result.l1_density = sum / std::max(1, count);
  result.row.note += "; L1(rho) = " + number(result.l1_density) + " inside 1.2 R; R_peak/R - 1 " +
                     "at most " + number(100 * result.radius_error, "%.2g") + " %";
  if (!draw) return result;

  // The figure: rho, v_r, P against r at t_end (particles as dots, the solution as a line), and
  // the shock radius against time.
  const int samples = 2000;
  std::vector<double> re(samples), rhoe(samples), ve(samples), Pe(samples);
  for (int k = 0; k < samples; ++k) {
    re[k] = 0.5 * k / (samples - 1);
    const auto s = exact.sample(re[k], limits.t_end);
    rhoe[k] = s.density;
    ve[k] = s.velocity;
    Pe[k] = s.pressure;
  }
  std::vector<double> tl(200), Rl(200);
  for (int k = 0; k < 200; ++k) {
    tl[k] = limits.t_end * (k + 1) / 200.0;
    Rl[k] = exact.shock_radius(tl[k]);
  }
  plot::Figure figure(2, 2, {.width = 1500, .height = 1150});
  figure.title("Sedov-Taylor blast in 3D, \\gamma = " + number(par.gamma, "%.4g") +
               ", E = 1, \\rho_0 = 1, t = " + number(limits.t_end, "%.4f"));
  figure.stamp({.scheme = std::string(Scene::name) + " (\\alpha = 1, \\beta = 2)",
                .kernel = "M4",
                .neighbours = par.neighbours,
                .particles = static_cast<long long>(blast.particles.size()),
                .run_time = run.row.seconds,
                .extra = "cubic lattice " + std::to_string(par.cells) + "^3, periodic box"});
  const double size = 4.0;
  struct Panel {
    const char* label;
    const std::vector<double>* particles;
    const std::vector<double>* exact_values;
  };
  const Panel panels[3] = {{"\\rho  [\\rho_0]", &rho, &rhoe},
                           {"v_r  [code units]", &v, &ve},
                           {"P  [code units]", &P, &Pe}};
  for (int k = 0; k < 3; ++k) {
    plot::Axes& ax = figure.panel(k);
    ax.xlabel("r  [code units]").ylabel(panels[k].label).xlim(0, 0.5);
    ax.scatter(r, *panels[k].particles,
               {.label = "SPH particles", .color = plot::black, .size = size, .alpha = 0.7});
    ax.line(re, *panels[k].exact_values,
            {.label = "self-similar solution", .color = plot::red, .width = 2.0});
    if (k == 0) ax.legend(plot::Corner::upper_left);
  }
  plot::Axes& ax = figure.panel(3);
  ax.xlabel("t  [code units]").ylabel("shock radius R  [code units]");
  ax.line(tl, Rl, {.label = "R = \\xi_0 (E t^2/\\rho_0)^{1/5}", .color = plot::red, .width = 2.0});
  ax.scatter(result.times, result.radius_sph,
             {.label = "SPH: densest shell", .color = plot::black, .size = 9.0});
  ax.legend(plot::Corner::upper_left);
  result.figure = "sedov_3d.png";
  figure.save_png(chapter.figure_path(result.figure).string());
  return result;
}

// ---- The cases ---------------------------------------------------------------------------------
struct Parameters {
  bool quick = false;
  std::string only;  // run only the groups whose name contains this
  double boost = 10;
  SedovParameters sedov;
};

template <class Scene>
void strong_tube(std::vector<Row>& rows, double ratio, double spacing,
                 const sph::SmoothingLengthRule& rule, const RunLimits& limits) {
  constexpr int D = Scene::D;
  sph::ShockTubeSetup s;
  s.left = {1.0, 0.0, 1.0};
  s.right = {0.125, 0.0, 1.0 / ratio};
  s.left_spacing = spacing;
  if (D > 1) s.start = sph::ShockTubeSetup::Start::settled;
  const auto tube = sph::make_shock_tube<D>(s, rule);
  Row row;
  row.name =
      "Sod, pressure ratio 1e" + std::to_string(static_cast<int>(std::lround(std::log10(ratio))));
  rows.push_back(run_case<Scene>(row, tube.particles, tube.box, s.gamma, rule, limits).row);
}

template <int D>
void strong_tubes(std::vector<Row>& rows, double spacing, const sph::SmoothingLengthRule& rule) {
  RunLimits limits;
  limits.max_steps = D == 1 ? 200000 : 20000;
  for (double ratio : {1e5, 1e10}) {
    strong_tube<SymmetricViscous<D>>(rows, ratio, spacing, rule, limits);
    strong_tube<OwnWorkViscous<D>>(rows, ratio, spacing, rule, limits);
    if (D == 1) strong_tube<OwnWorkInviscid<D>>(rows, ratio, spacing, rule, limits);
  }
}

template <class Scene>
void sod_with_gamma(std::vector<Row>& rows, double gamma, double spacing) {
  sph::ShockTubeSetup s;
  s.gamma = gamma;
  s.left_spacing = spacing;
  const auto rule = sph::SmoothingLengthRule::from_density(4);
  const auto tube = sph::make_shock_tube<1>(s, rule);
  Row row;
  row.name = "Sod, gamma = " + number(gamma, "%.3g");
  Run<1> run = run_case<Scene>(row, tube.particles, tube.box, gamma, rule, {});
  if (run.row.ran) {
    const auto errors = sph::shock_tube_errors(run.particles, tube.exact, 0.2);
    run.row.note = "L1(rho) = " + number(errors[0].L1) + " against the exact solution";
  }
  rows.push_back(run.row);
}

// The Sod tube at rest and moving at +boost: the same physics, and the same error once the
// particles are carried back into the rest frame.
// Under each time-step rule: Selhammar's eq 7 puts the particle's own speed into the Courant
// limit, the signal velocity of Monaghan (1997) only the pairs' relative speeds.
template <class Scene>
void boosted_sod(std::vector<Row>& rows, double boost, double spacing,
                 sph::Settings::TimestepRule timestep) {
  const double t_end = 0.2;
  const auto rule = sph::SmoothingLengthRule::from_density(4);
  const bool signal = timestep == sph::Settings::TimestepRule::signal_velocity;
  for (double v : {0.0, boost}) {
    sph::ShockTubeSetup s;
    s.left_spacing = spacing;
    s.left.velocity = s.right.velocity = v;
    auto tube = sph::make_shock_tube<1>(s, rule);
    Row row;
    row.name = (v == 0 ? "Sod at rest" : "Sod moving at +" + number(v, "%g")) +
               (signal ? ", signal-velocity step" : ", eq 7 step");
    RunLimits limits;
    limits.t_end = t_end;
    limits.timestep = timestep;
    Run<1> run = run_case<Scene>(row, tube.particles, tube.box, s.gamma, rule, limits);
    if (run.row.ran) {
      // Back into the rest frame: x - v t (wrapped into the periodic tube), v_x - v.
      for (std::size_t i = 0; i < run.particles.size(); ++i) {
        run.particles.position[i] =
            tube.box.wrap(run.particles.position[i] - sph::Vec<1>(v * t_end));
        run.particles.velocity[i][0] -= v;
      }
      const sph::RiemannSolution rest({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, s.gamma);
      const auto errors = sph::shock_tube_errors(run.particles, rest, t_end);
      run.row.note = "rest frame: L1(rho) = " + number(errors[0].L1, "%.4g") +
                     ", L1(v) = " + number(errors[1].L1, "%.4g");
    }
    rows.push_back(run.row);
  }
}

template <class Scene>
void near_vacuum(std::vector<Row>& rows, double spacing) {
  const double gamma = 1.4;
  const sph::GasState left{1.0, 0.0, 1.0}, right{1e-6, 0.0, 1e-6};
  const auto p = two_state_tube(left, right, gamma, spacing);
  const auto box = sph::Box<1>::periodic_box(sph::Vec<1>(-1.0), sph::Vec<1>(1.0));
  Row row;
  row.name = "near vacuum, rho_R = 1e-6";
  Run<1> run = run_case<Scene>(row, p, box, gamma, sph::SmoothingLengthRule::from_density(4), {});
  if (!run.particles.position.empty() && run.row.finite) run.row.note = extremes(run.particles);
  rows.push_back(run.row);
}

// One hot particle in a uniform 1D gas at rest: its internal energy `factor` times its
// neighbours'.  A Sedov blast in miniature, in 1D, with nothing to smooth it.
template <class Scene>
void hot_particle(std::vector<Row>& rows, double factor, double spacing) {
  const double gamma = 1.4;
  const sph::GasState gas{1.0, 0.0, 1.0};
  auto p = two_state_tube(gas, gas, gamma, spacing);
  const std::size_t hot = p.size() / 2;
  p.internal_energy[hot] *= factor;
  const auto box = sph::Box<1>::periodic_box(sph::Vec<1>(-1.0), sph::Vec<1>(1.0));
  Row row;
  row.name = "one hot particle, u x " + number(factor, "%g");
  RunLimits limits;
  limits.t_end = 0.05;
  Run<1> run =
      run_case<Scene>(row, p, box, gamma, sph::SmoothingLengthRule::from_density(4), limits);
  if (!run.particles.position.empty() && run.row.finite) {
    double u_min = std::numeric_limits<double>::infinity();
    for (double u : run.particles.internal_energy) u_min = std::min(u_min, u);
    run.row.note = "least u at the end " + number(u_min) +
                   " (the gas's own: " + number(p.internal_energy[0]) + ")";
  }
  rows.push_back(run.row);
}

template <class Scene>
void opening_vacuum(std::vector<Row>& rows, double spacing, const std::string& exact_says) {
  const double gamma = 1.4;
  const sph::GasState left{1.0, -8.0, 1.0}, right{1.0, 8.0, 1.0};
  const auto p = two_state_tube(left, right, gamma, spacing);
  Row row;
  row.name = "streams apart at +-8 (vacuum)";
  Run<1> run = run_case<Scene>(row, p, sph::Box<1>::open(), gamma,
                               sph::SmoothingLengthRule::from_density(4), {});
  if (run.row.ran) {
    double gap = 0;  // the widest gap between neighbours at the end
    std::vector<double> x;
    for (const auto& q : run.particles.position) x.push_back(q[0]);
    std::sort(x.begin(), x.end());
    for (std::size_t k = 1; k < x.size(); ++k) gap = std::max(gap, x[k] - x[k - 1]);
    run.row.note =
        "widest gap " + number(gap) + " (spacing " + number(spacing) + "); " + exact_says;
  } else {
    run.row.note = exact_says;
  }
  rows.push_back(run.row);
}

template <class Scene>
void mach_100_streams(std::vector<Row>& rows, double spacing) {
  sph::CollidingStreamsSetup s;
  s.mach = 100;
  s.spacing = spacing;
  const auto streams = sph::make_colliding_streams<1>(s);
  Row row;
  row.name = "colliding streams, Mach 100";
  RunLimits limits;
  limits.t_end = 0.4;
  Run<1> run = run_case<Scene>(row, streams.particles, streams.box, s.gamma,
                               sph::SmoothingLengthRule::from_density(4), limits);
  if (!run.particles.position.empty() && run.row.finite) {
    const auto inversions =
        sph::order_inversions<1>(streams.particles.position, run.particles.position, streams.box);
    run.row.note = inversions.summary();
  }
  rows.push_back(run.row);
}

void degenerate(std::vector<Row>& rows) {
  using Scene = OwnWorkViscous<1>;
  const auto rule = sph::SmoothingLengthRule::from_density(4);
  {
    // A lattice with one particle moved onto its neighbour.
    auto p = two_state_tube({1, 0, 1}, {0.125, 0, 0.1}, 1.4, 1.0 / 50);
    p.position[31] = p.position[30];
    Row row;
    row.name = "coincident particles";
    row.expect = Expect::stops;
    const auto box = sph::Box<1>::periodic_box(sph::Vec<1>(-1.0), sph::Vec<1>(1.0));
    rows.push_back(run_case<Scene>(row, p, box, 1.4, rule, {}).row);
  }
  {
    sph::Particles<3> p;
    for (int k = 0; k < 20; ++k) p.add(sph::Vec<3>(0.3, 0.3, 0.3), sph::Vec<3>::Zero(), 0.05, 1.0);
    Row row;
    row.name = "all particles at one point";
    row.expect = Expect::stops;
    rows.push_back(run_case<OwnWorkViscous<3>>(row, p, sph::Box<3>::open(), 1.4,
                                               sph::SmoothingLengthRule::neighbour_number(10), {})
                       .row);
  }
}

// ---- The page ----------------------------------------------------------------------------------
std::string table(const std::vector<Row>& rows) {
  std::ostringstream md;
  md << "| case | D | scheme | N | outcome | momentum error | energy error "
        "| step limited most often by | steps | wall time | notes |\n"
     << "|:--|:-:|:--|--:|:--|--:|--:|:--|--:|--:|:--|\n";
  for (const Row& r : rows) {
    md << "| " << r.name << " | " << r.dimension << " | " << r.scheme << " | " << r.particles
       << " | " << outcome(r) << " | " << number(r.momentum_error, "%.1e") << " | "
       << number(r.energy_error, "%.1e") << " | " << (r.limiter.empty() ? "-" : r.limiter) << " | "
       << r.steps << " | " << number(r.seconds, "%.2f") << " s | " << (r.note.empty() ? "" : r.note)
       << " |\n";
  }
  return md.str();
}

// What the table shows, in sentences made from its rows.
std::string findings(const std::vector<Row>& rows) {
  std::ostringstream md;
  const auto dimension = [](const Row& r) { return std::to_string(r.dimension) + "D"; };
  // The two energy equations, case by case.
  std::vector<std::string> only_own, both_stop;
  int pairs = 0;
  for (const Row& s : rows) {
    if (s.scheme != SymmetricViscous<1>::name) continue;
    for (const Row& o : rows) {
      if (o.scheme != OwnWorkViscous<1>::name || o.name != s.name || o.dimension != s.dimension)
        continue;
      ++pairs;
      const std::string which = s.name + " (" + dimension(s) + ")";
      if (!s.ran && o.ran) only_own.push_back(which);
      if (!s.ran && !o.ran) both_stop.push_back(which);
    }
  }
  const auto list = [](const std::vector<std::string>& items) {
    std::string text;
    for (std::size_t k = 0; k < items.size(); ++k)
      text += (k == 0 ? "" : (k + 1 == items.size() ? " and " : ", ")) + items[k];
    return text;
  };
  md << "- Of the " << pairs << " cases run with both energy equations (with the viscosity), "
     << only_own.size() << " ran to the end only with the own-work form: " << list(only_own) << ".";
  const bool by_cooling = std::all_of(rows.begin(), rows.end(), [&](const Row& r) {
    const bool listed = std::find(only_own.begin(), only_own.end(),
                                  r.name + " (" + dimension(r) + ")") != only_own.end();
    return !listed || r.scheme != SymmetricViscous<1>::name ||
           r.message.find("cooling") != std::string::npos;
  });
  if (!only_own.empty() && by_cooling)
    md << "  In each, the symmetric form stopped on the cooling of a cold particle beside a hot "
          "one: the time step collapsed under the cooling limit, or the particle's internal "
          "energy went negative within a step (the message says which; the column of limits "
          "says how often cooling set the step).";
  if (!both_stop.empty()) md << "  Both stopped in " << list(both_stop) << ".";
  md << "\n";
  // Without viscosity.
  std::vector<std::string> inviscid;
  for (const Row& r : rows) {
    if (r.scheme == OwnWorkInviscid<1>::name && !r.ran)
      inviscid.push_back(r.name + " (" + dimension(r) + ", stopped at t = " + number(r.t_reached) +
                         ")");
  }
  if (!inviscid.empty())
    md << "- Without viscosity, " << list(inviscid)
       << " stopped: the particles meet with nothing to stop them, and the Courant step "
          "collapses.\n";
  // The boost, under each time-step rule.
  for (const char* rule : {", eq 7 step", ", signal-velocity step"}) {
    const Row *rest = nullptr, *moving = nullptr;
    for (const Row& r : rows) {
      if (!r.name.ends_with(rule)) continue;
      if (r.name.starts_with("Sod at rest")) rest = &r;
      if (r.name.starts_with("Sod moving")) moving = &r;
    }
    if (!(rest && moving && rest->ran && moving->ran)) continue;
    const bool eq7 = std::string(rule) == ", eq 7 step";
    md << "- Galilean invariance" << rule << ": carried back into the rest frame, the moving "
       << "tube's errors are those of the tube at rest (the notes give both), and it takes "
       << moving->steps << " steps against " << rest->steps << " at rest"
       << (eq7 ? ": Selhammar's eq 7 puts the particle's own speed into the Courant limit, so the "
                 "step depends on the frame.\n"
               : ": the signal velocity of Monaghan (1997) sees only the pairs' relative speeds, "
                 "so the step does not depend on the frame.\n");
  }
  return md.str();
}

void write_page(const std::string& path, const std::vector<Row>& rows, const SedovResult& sedov,
                const SedovParameters& sp, bool quick, const std::string& only) {
  std::ofstream md(path);
  int ran = 0, stopped = 0;
  for (const Row& r : rows) (r.ran ? ran : stopped) += 1;
  md << "# Stiff and extreme cases {#stiff_cases}\n\n"
     << "Every scheme run where it is hardest.  This page is written by the program "
        "`atlas/stiff_cases.cpp` (`build/atlas/atlas_stiff_cases`"
     << (quick ? " --quick: a reduced resolution" : ", at full resolution") << "); " << rows.size()
     << " runs, " << ran << " reached their end time and " << stopped
     << " were stopped by the library with the message shown"
     << (only.empty() ? "" : " (only the groups matching --only " + only + ")") << ".\n\n"
     << "A run may end in two ways: it reaches its end time with every field finite, or the "
        "library stops it with a message that names the particle, the quantity and the limit "
        "(sph::Error).  A NaN, a crash or a hang is neither, and the program fails if any run "
        "ends so; under ctest every case runs at a small resolution "
        "(`atlas_stiff_cases --quick`).\n\n"
     << "The schemes differ only in their energy equation and viscosity; the force is "
        "Hernquist & Katz's symmetric pressure force in all of them: "
        "<em>symmetric</em> shares the work of a pair equally between its two particles "
        "(sph::PressureHernquistKatz), <em>own work</em> heats each particle by the work of "
        "its own pressure (sph::PressureOwnWork); <em>MG</em> is the Monaghan & Gingold (1983) "
        "viscosity with alpha = 1, beta = 2.  Momentum error: the change of the total "
        "momentum over the sum of the momenta's magnitudes (sph::momentum_scale); energy error: "
        "the relative "
        "change of kinetic plus thermal energy, both at the end or where the run stopped.  "
        "The time step is the smallest of the limits the step computes (Courant with the "
        "particle's own speed, as Selhammar's eq 7 prints it; acceleration; cooling; see "
        "sph::Simulation): the column gives the one that set the most steps, with its "
        "share.\n\n"
     << "The cases: Sod's tube (rho 1 and 0.125) with the right pressure lowered to 1e-5 "
        "and 1e-10 of the left's, in 1D, 2D and 3D at chapter 4's full resolutions (2D and 3D "
        "from settled glasses); a "
        "near vacuum (rho and P of 1e-6 on the right, on one lattice, so the masses differ a "
        "million times); two halves of a gas flying apart at -8 and +8, faster than "
        "2c/(gamma-1) each, so that a vacuum opens between them; one particle of a uniform 1D "
        "gas at rest with 40 and 10^4 times its neighbours' internal energy (to t = 0.05); "
        "Mach-100 colliding streams "
        "(sph::make_colliding_streams); Sod's tube with gamma = 1.01 and gamma = 10; the "
        "Sedov-Taylor blast below; Sod's tube moving at +10 against the same tube at rest "
        "(the errors compared in the rest frame), under each of the two time-step rules; and "
        "degenerate input.\n\n"
     << table(rows) << "\n"
     << "What the table shows:\n\n"
     << findings(rows)
     << "- The near vacuum is a mass ratio of a million between neighbours: light particles "
        "that enter the dense gas take its density, so their h = N m/(4 rho) shrinks with "
        "their mass, and the Courant step with it (the notes give the smallest h).\n"
     << "- The opening vacuum has no exact solution to compare with (the note quotes the "
        "exact solver's refusal); the particles part, and h grows to span the gap.\n"
     << "- Degenerate input stops before the first step.  Two particles at one point "
        "were, before this atlas, reported only as a smoothing length that did not "
        "converge; the step now names both particles (sph::Simulation).\n\n";
  md << "## The Sedov-Taylor blast {#stiff_cases_sedov}\n\n"
     << "An energy E = 1 is put into the particles within 2h of the centre of a cold "
        "(u = 1e-7), uniform (rho_0 = 1) gas: a cubic lattice of "
     << sp.cells
     << "^3 "
        "particles in the periodic box [-0.5, 0.5]^3, with gamma = "
     << number(sp.gamma, "%.4g")
     << ", shared in proportion to the kernel (sph::make_sedov_blast).  The self-similar "
        "solution (sph::SedovSolution) is integrated from the shock inwards; its constant "
        "xi_0 = "
     << number(sph::SedovSolution(3, sp.gamma).xi0(), "%.4f")
     << " comes from the energy integral.  The run ends when the exact shock reaches r = "
     << number(sp.final_radius) << ".\n\n";
  if (sedov.row.ran) {
    md << "The densest shell of particles follows R(t) to within "
       << number(100 * sedov.radius_error, "%.2g")
       << " % over the run; the mean absolute difference between the particles' density and "
          "the solution's, over the particles inside 1.2 R at the end, is "
       << number(sedov.l1_density)
       << " (the peak, (gamma+1)/(gamma-1) = " << number((sp.gamma + 1) / (sp.gamma - 1), "%.3g")
       << " times rho_0 just behind the exact shock, is smoothed over about 2h, which is where "
          "most of this difference sits).  Energy changed by "
       << number(sedov.row.energy_error, "%.1e") << " of E, momentum by "
       << number(sedov.row.momentum_error, "%.1e")
       << " of the sum of the momenta's magnitudes.\n\n";
  } else {
    md << "The own-work run did not reach the end: " << cell_message(sedov.row.message) << "\n\n";
  }
  if (!sedov.figure.empty()) {
    md << "\\image html " << sedov.figure
       << " \"The Sedov-Taylor blast: density, radial velocity and pressure against radius at "
          "the end, and the shock radius against time\"\n";
  }
  md << "\n## What to try {#stiff_cases_try}\n\n"
     << "- `--sedov-gamma 1.4`: the blast in a diatomic gas; xi_0 becomes 1.0328 and the "
        "compression just behind the shock 6 instead of 4: compare the particles' peak and the "
        "L1 difference with the ones above.\n"
     << "- `--sedov-cells 48`: 3.4 times the particles; see whether the densest shell closes "
        "on R(t) and by how much the L1 difference falls.\n"
     << "- `--boost 100`: the tube moving at +100; compare its rest-frame errors and its "
        "steps with the tube at rest, under eq 7 (the own speed in the Courant limit) and "
        "under the signal velocity.\n"
     << "- `--only sedov` (or strong, vacuum, hot, streams, gamma, boost, degenerate): one group "
        "alone.\n";
}

}  // namespace

int main(int argc, char** argv) {
  return app::run_main([&] {
    app::Chapter chapter("atlas", "The atlas of stiff and extreme cases", argc, argv);
    Parameters par;
    // (up to 10^4 the moving tube runs, or stops at the step budget with eq 7's step, saying
    // so; far beyond it the sound speed is lost in the boost's round-off and no step is left)
    chapter.parameter("--boost", par.boost, "Galilean boost of the moving Sod tube")
        .check(app::greater_than(0.0))
        ->check(app::at_most(1e4));
    chapter.parameter("--sedov-gamma", par.sedov.gamma, "Sedov blast: adiabatic index")
        .check(app::between(1.05, 5.0));
    // (--quick makes 12 cells per axis the default, as it makes every case small; a number
    // given by name is honoured, with or without --quick)
    chapter.parameter("--sedov-cells", par.sedov.cells, "Sedov blast: lattice cells per axis", 12)
        .check(app::count_between(
            8, 96, [](double cells) { return app::particle_bytes(3, cells * cells * cells); }));
    static const std::vector<std::string> groups = {"strong", "vacuum", "hot",        "streams",
                                                    "gamma",  "boost",  "degenerate", "sedov"};
    std::string group_list;
    for (const std::string& group : groups) group_list += (group_list.empty() ? "" : ", ") + group;
    chapter
        .parameter("--only", par.only,
                   "run only the groups whose name contains this: " + group_list)
        .check(app::require<std::string>(
                   [](const std::string& only) {
                     return std::any_of(groups.begin(), groups.end(),
                                        [&](const std::string& group) {
                                          return group.find(only) != std::string::npos;
                                        });
                   },
                   "matches no group (" + group_list + ")")
                   .description(""));  // (--help lists the groups already)
    if (int rc = chapter.parse(); rc >= 0) return rc;
    const auto wanted = [&](const std::string& group) {
      return par.only.empty() || group.find(par.only) != std::string::npos;
    };
    par.quick = chapter.quick();
    if (par.quick) par.sedov.neighbours = 40;
    const double spacing_1d = par.quick ? 1.0 / 100 : 1.0 / 800;
    std::vector<Row> rows;

    if (wanted("strong")) {
      // At chapter 4's full resolutions and neighbour numbers: 3600, 5621 and 9000 particles.
      std::cerr << "Strong shock tubes\n";
      strong_tubes<1>(rows, par.quick ? 1.0 / 100 : 1.0 / 3200,
                      sph::SmoothingLengthRule::from_density(4));
      strong_tubes<2>(rows, par.quick ? 1.0 / 32 : 1.0 / 200,
                      sph::SmoothingLengthRule::neighbour_number(20, 1));
      strong_tubes<3>(rows, par.quick ? 1.0 / 16 : 1.0 / 80,
                      sph::SmoothingLengthRule::neighbour_number(par.quick ? 50 : 60, 2));
    }

    if (wanted("vacuum")) {
      std::cerr << "Vacuum\n";
      // (one resolution: the light particles' h shrinks a millionfold where they enter the
      // dense gas, and the Courant step with it, so that the steps grow much faster than N)
      const double vacuum_spacing = par.quick ? 1.0 / 50 : 1.0 / 100;
      near_vacuum<SymmetricViscous<1>>(rows, vacuum_spacing);
      near_vacuum<OwnWorkViscous<1>>(rows, vacuum_spacing);
      std::string exact_says;
      try {
        sph::RiemannSolution({1.0, -8.0, 1.0}, {1.0, 8.0, 1.0}, 1.4);
        exact_says = "the exact solver accepts it";
      } catch (const sph::Error& e) {
        exact_says = "the exact solver: " + cell_message(e.what());
      }
      opening_vacuum<SymmetricViscous<1>>(rows, spacing_1d, exact_says);
      opening_vacuum<OwnWorkViscous<1>>(rows, spacing_1d, exact_says);
    }

    if (wanted("hot")) {
      std::cerr << "One hot particle\n";
      for (double factor : {40.0, 1e4}) {
        hot_particle<SymmetricViscous<1>>(rows, factor, spacing_1d);
        hot_particle<OwnWorkViscous<1>>(rows, factor, spacing_1d);
      }
    }

    if (wanted("streams")) {
      std::cerr << "Colliding streams\n";
      const double streams_spacing = par.quick ? 1.0 / 50 : 1.0 / 200;
      mach_100_streams<SymmetricViscous<1>>(rows, streams_spacing);
      mach_100_streams<OwnWorkViscous<1>>(rows, streams_spacing);
      mach_100_streams<OwnWorkInviscid<1>>(rows, streams_spacing);
    }

    if (wanted("gamma")) {
      std::cerr << "Extreme gamma\n";
      for (double gamma : {1.01, 10.0}) {
        sod_with_gamma<SymmetricViscous<1>>(rows, gamma, spacing_1d);
        sod_with_gamma<OwnWorkViscous<1>>(rows, gamma, spacing_1d);
      }
    }

    if (wanted("boost")) {
      std::cerr << "Galilean boost\n";
      boosted_sod<OwnWorkViscous<1>>(rows, par.boost, spacing_1d,
                                     sph::Settings::TimestepRule::selhammar_eq7);
      boosted_sod<OwnWorkViscous<1>>(rows, par.boost, spacing_1d,
                                     sph::Settings::TimestepRule::signal_velocity);
    }

    if (wanted("degenerate")) {
      std::cerr << "Degenerate input\n";
      degenerate(rows);
    }

    SedovResult sedov;
    if (wanted("sedov")) {
      std::cerr << "Sedov blast\n";
      sedov = run_sedov<OwnWorkViscous<3>>(par.sedov, chapter, true);
      rows.push_back(sedov.row);
      rows.push_back(run_sedov<SymmetricViscous<3>>(par.sedov, chapter, false).row);
      chapter.check(sedov.row.ran, "the Sedov blast with the own-work energy equation must run");
    }

    // ---- The page, the console, the checks ----
    write_page(chapter.figure_path("stiff_cases.md").string(), rows, sedov, par.sedov, par.quick,
               par.only);
    std::cout << table(rows) << "\n";
    int ran = 0;
    for (const Row& r : rows) {
      ran += r.ran;
      const std::string who = r.name + " (" + std::to_string(r.dimension) + "D, " + r.scheme + ")";
      chapter.check(!r.unexpected, who + ": " + r.message);
      chapter.check(r.finite, who + ": a non-finite field where the run ended");
      if (r.expect == Expect::stops)
        chapter.check(!r.ran && r.message.find("particle") != std::string::npos,
                      who + ": degenerate input must stop with a message naming the particle");
      if (r.ran) {
        chapter.check(r.momentum_error < 1e-9,
                      who + ": momentum error " + number(r.momentum_error) + " above 1e-9");
        chapter.check(r.energy_error < 0.05,
                      who + ": energy error " + number(r.energy_error) + " above 5 %");
      }
    }
    chapter.summary("runs", std::to_string(rows.size()) + " (" + std::to_string(ran) + " ran)");
    if (sedov.row.ran) {
      chapter.summary("error", "Sedov L1(rho) = " + number(sedov.l1_density) +
                                   ", shock radius within " +
                                   number(100 * sedov.radius_error, "%.2g") + " %");
    }
    return chapter.finish();
  });
}
