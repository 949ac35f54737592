/// \page ch03 Chapter 3: The equations of motion
/// \builds_on ch02
///
/// \section ch03_intro What this chapter is about
///
/// Chapters 1 and 2 built the two things SPH needs before anything can move: a kernel, and a
/// density that is a sum of kernels.  In this chapter the particles move.  We write down the
/// SPH equations of motion and of energy in the form both of our papers use, integrate them
/// with Selhammar's leapfrog, and run the first real test of every hydrodynamics code:
/// **Sod's shock tube** (Sod 1978), a gas at rest with density and pressure
/// \f$ \rho = 1,\ P = 1 \f$ on the left and \f$ \rho = 0.125,\ P = 0.1 \f$ on the right,
/// \f$ \gamma = 1.4 \f$, released at \f$ t = 0 \f$ and looked at when \f$ t = 0.2 \f$.
///
/// We do it *without* artificial viscosity: the equations contain the pressure force and
/// nothing else.  That is the honest starting point, and it fails in an instructive way.
/// Where the flow is smooth (the rarefaction wave) the particles follow the exact solution
/// to a fraction of a percent.  Where it is not (the shock) the gas cannot turn the kinetic
/// energy of the incoming flow into heat, because nothing in the equations can make entropy;
/// the energy stays in the motion instead, and the post-shock gas **rings**: particle
/// velocities scatter by half the flow speed about the right value, and the scatter does not
/// shrink when we add particles.  In a second test, two cold streams colliding head-on, the
/// same lack of dissipation lets **particles pass through each other** -- or, with a
/// smoothing length that shrinks as particles crowd together, piles them into a sheet a
/// hundred thousand times denser than it should be, until the time step collapses.  These
/// failures are the reason artificial viscosity exists, and chapter 4 adds it.  To let the reader see
/// what is coming, every test is also run once with the Monaghan & Gingold (1983) viscosity
/// of chapter 4 switched on.
///
/// Along the way we meet a misprint.  Selhammar (1997) eq 4 prints the pressure term of the
/// momentum equation as \f$ \bar P_{ij}/\bar\rho_{ij}^2 \f$; the Hernquist & Katz (1989) form
/// it cites is \f$ P_i/\rho_i^2 + P_j/\rho_j^2 \f$.  We do not quietly substitute one for the
/// other: we run both, work out exactly what the printed form does, and show that the
/// simulation agrees with that prediction.
///
/// The program has five steps:
///  1. Sod's tube without viscosity at the resolution of the papers' 1D tests (450 particles
///     in the window \f$ -0.5 \le x \le 0.5 \f$), with errors, ringing and wave positions;
///  2. the same with the Monaghan-Gingold viscosity, for contrast;
///  3. the same with eq 4 as printed;
///  4. the colliding streams, with a diagnostic that counts particles that have passed one
///     another;
///  5. the error of Sod's tube against run time at six resolutions, with and without
///     viscosity: does the inviscid error converge?  (It does not.)
///
/// \section ch03_equations The equations of motion
///
/// \subsection ch03_momentum Momentum
///
/// The Euler equation \f$ d\mathbf v/dt = -\nabla P/\rho \f$ can be discretised in many ways;
/// the one that conserves momentum exactly starts from the identity
/// \f[ \frac{\nabla P}{\rho} = \nabla\!\left(\frac P\rho\right) + \frac{P}{\rho^2}\nabla\rho , \f]
/// replaces each gradient by its SPH sum \f$ \nabla A_i \approx \sum_j m_j (A_j/\rho_j)
/// \nabla_i W_{ij} \f$ (chapter 1), and gets the symmetric form of Hernquist & Katz (1989),
/// Selhammar (1997) eq 4 read as in our notes (NOTES.md):
/// \f[ \frac{d\mathbf v_i}{dt} = -\sum_j m_j \left( \frac{P_i}{\rho_i^2} + \frac{P_j}{\rho_j^2}
///       \right) \nabla_i W(r_{ij}, \bar h_{ij}), \qquad \bar h_{ij} = \tfrac12 (h_i + h_j). \f]
/// (Chapter 4 adds \f$ \Pi_{ij} \f$ to the bracket; here it is zero.)
///
/// **Sign conventions.** We write \f$ \mathbf r_{ij} = \mathbf r_i - \mathbf r_j \f$ and
/// \f$ \mathbf v_{ij} = \mathbf v_i - \mathbf v_j \f$.  The kernel gradient is
/// \f$ \nabla_i W_{ij} = W'(r_{ij})\,\mathbf r_{ij}/r_{ij} \f$ with \f$ W' < 0 \f$, so it points
/// from i towards j; the minus sign in front of the sum then pushes i *away* from j, as a
/// pressure must.  Selhammar prints \f$ \mathbf v_{ij} = \mathbf v_j - \mathbf v_i \f$ in eq 4,
/// which contradicts his own eq 6 (where an approaching pair has \f$ \mathbf r_{ij}\cdot
/// \mathbf v_{ij} < 0 \f$) and would make a compressed gas cool; we use
/// \f$ \mathbf v_i - \mathbf v_j \f$ throughout.
///
/// **Equal and opposite.** The bracket is symmetric in i and j and the gradient antisymmetric,
/// \f$ \nabla_j W_{ji} = -\nabla_i W_{ij} \f$.  The force of j on i,
/// \f$ -m_i m_j (\dots) \nabla_i W_{ij} \f$, is therefore exactly minus the force of i on j:
/// the total momentum \f$ \sum_i m_i \mathbf v_i \f$ is conserved to round-off, whatever the
/// particles do.  The program checks this after every run.
///
/// \subsection ch03_energy Energy
///
/// The first law for an adiabatic gas is \f$ du/dt = (P/\rho^2)\, d\rho/dt \f$.  With the
/// same symmetric bracket, half of it per particle,
/// \f[ \frac{du_i}{dt} = \frac12 \sum_j m_j \left( \frac{P_i}{\rho_i^2} + \frac{P_j}{\rho_j^2}
///       \right) \mathbf v_{ij}\cdot\nabla_i W(r_{ij}, \bar h_{ij}) . \f]
/// For an approaching pair \f$ \mathbf v_{ij}\cdot\nabla_i W_{ij} = W'\,\mathbf r_{ij}\cdot
/// \mathbf v_{ij}/r_{ij} > 0 \f$: compression heats, as it should.  The work the pair force
/// does on the relative motion, \f$ -m_i m_j(\dots)\,\mathbf v_{ij}\cdot\nabla_i W_{ij} \f$, is
/// exactly what the two particles gain in internal energy, so
/// \f$ E = \sum_i m_i (\tfrac12 v_i^2 + u_i) \f$ is conserved by the equations; the time
/// integration conserves it to \f$ O(\delta t^2) \f$, and we check that too.
///
/// These equations are adiabatic: in the continuum limit \f$ du/dt \f$ is exactly the
/// \f$ P\,dV \f$ work, and nothing in them can raise the entropy \f$ P/\rho^\gamma \f$ of the
/// gas.  (The discrete form is adiabatic only approximately.  It shares the work of each pair
/// equally between the two particles, which is exact only when
/// \f$ P_i/\rho_i^2 = P_j/\rho_j^2 \f$; and with h varying from particle to particle, the
/// density sum changes by terms in \f$ \partial W/\partial h \f$ that the energy equation does not
/// contain -- the "grad-h" terms of later SPH formulations.  Both errors are small in a smooth
/// flow.)  A shock, however, *must* raise the entropy: the Rankine-Hugoniot conditions put the gas behind Sod's shock on a higher
/// adiabat, with \f$ P/\rho^\gamma \f$ 5.5 % above that of the gas in front and internal energy
/// \f$ u = 2.853 \f$ instead of the \f$ u_R(\rho_{*R}/\rho_R)^{\gamma-1} = 2.702 \f$ an adiabatic
/// compression to the same density would give.  Keep that in mind when we look at the results.
///
/// \subsection ch03_printed The printed eq 4, and the gas it actually describes
///
/// Selhammar's eq 4 is printed with the bracket \f$ \bar P_{ij}/\bar\rho_{ij}^2 \f$, pair
/// means of pressure and density.  For two neighbours in a smooth flow, \f$ P_i \approx P_j
/// \approx P \f$ and \f$ \rho_i \approx \rho_j \approx \rho \f$, so it is \f$ P/\rho^2 \f$:
/// **half** the Hernquist & Katz bracket \f$ 2P/\rho^2 \f$.  Both the force and the heating
/// are halved.  In the continuum limit the printed equations are
/// \f[ \frac{d\mathbf v}{dt} = -\frac{\nabla P}{2\rho}, \qquad
///     \frac{du}{dt} = \frac{P}{2\rho^2}\frac{d\rho}{dt}, \qquad P = (\gamma - 1)\rho u . \f]
/// Write \f$ P' = P/2 \f$ and \f$ \gamma' - 1 = (\gamma - 1)/2 \f$: then
/// \f$ d\mathbf v/dt = -\nabla P'/\rho \f$, \f$ du/dt = (P'/\rho^2)\, d\rho/dt \f$ and
/// \f$ P' = (\gamma' - 1)\rho u \f$.  These are the *correct* equations of a different gas:
/// one with adiabatic index \f$ \gamma' = (\gamma + 1)/2 = 1.2 \f$ whose pressure is half the
/// one we print.  Its sound speed is \f$ \sqrt{\gamma' P'/\rho} = \sqrt{\gamma'/(2\gamma)}\,c
/// = 0.65\,c \f$, so every wave runs about a third too slow.  Better still, we can *solve*
/// that gas's shock tube exactly -- the Riemann problem with pressures 0.5 and 0.05 and
/// \f$ \gamma' = 1.2 \f$ -- and predict the printed scheme's result before running it.  Step 3
/// does both.  (The argument uses \f$ \rho_i \approx \rho_j \f$; at the contact discontinuity,
/// where the density jumps, the two brackets differ in other ways as well.)
///
/// \section ch03_integration Time integration
///
/// Selhammar's eq 8 is the leapfrog: velocities and energies at half steps, positions at whole
/// steps.  The library writes it in the equivalent kick-drift-kick form (see simulation.hpp),
/// \f[ \mathbf v^{n+1/2} = \mathbf v^n + \tfrac12\delta t\,\mathbf a^n, \quad
///     \mathbf r^{n+1} = \mathbf r^n + \delta t\,\mathbf v^{n+1/2}, \quad
///     \mathbf v^{n+1} = \mathbf v^{n+1/2} + \tfrac12\delta t\,\mathbf a^{n+1}, \f]
/// and the same for u, which produces the same trajectory for a constant step but also has
/// \f$ \mathbf v \f$ and \f$ u \f$ at whole steps for the snapshots, and allows the step to
/// change.  The step is eq 7 with \f$ \varepsilon = 0.3 \f$,
/// \f[ \delta t = \min_i \frac{\varepsilon h_i}{|\mathbf v_i| + c_i + 1.2(\alpha c_i + \beta\mu_{i,\max})}, \f]
/// in which the viscous term vanishes in this chapter (\f$ \alpha = \beta = 0 \f$), plus the
/// limit \f$ \varepsilon\sqrt{h_i/|\mathbf a_i|} \f$ on the acceleration.
///
/// \section ch03_h The smoothing length in 1D
///
/// The papers keep a fixed *number* of neighbours (Selhammar: 64 in 3D).  In our 1D shock
/// tubes we set h from the density instead, \f$ h_i = N m_i/(4\rho_i) \f$ (Watkins eqs A6-A7
/// in 1D), with \f$ N = 4 \f$, which makes \f$ h = m/\rho = \Delta x \f$: the smoothing length
/// equals the local particle spacing.  The reason is a property of the M4 kernel that chapter
/// 4 (\ref ch04) examines in depth.  At \f$ h = \Delta x \f$ the M4 is exactly the cubic
/// B-spline on the particle lattice, and its lattice sums are exact: a uniform lattice has
/// exactly the right density, and the pressure-gradient sums are exactly right.  At the more
/// common \f$ h = 1.2\Delta x \f$ the lattice sums overestimate density by 0.18 % and gradient
/// sums by 2.2 %; the rarefaction then runs 1-2 % fast, and that bias puts a floor under
/// the error that no amount of resolution removes.  With \f$ h = \Delta x \f$ what we measure
/// below is the behaviour of the equations, not of the kernel's lattice error.  (Try
/// `--neighbours 4.8` for \f$ h = 1.2\Delta x \f$.)
///
/// \section ch03_program The program
///
/// The chapter uses the library's shock-tube set-up of chapter 2 (a periodic tube of period 2
/// whose second interface at \f$ x = \pm 1 \f$ stays far from the window we measure), the
/// exact Riemann solver, the simulation loop, and two small additions: the colliding-stream
/// set-up `lib/sph/setups/colliding_streams.hpp` and the penetration diagnostic
/// `lib/sph/penetration.hpp`.

#include "app/chapter.hpp"
#include "app/error_figure.hpp"
#include "app/progress.hpp"
#include "app/shock_tube_figure.hpp"
#include "app/stopwatch.hpp"
#include "plot/figure.hpp"
#include "sph/convergence.hpp"
#include "sph/diagnostics.hpp"
#include "sph/norms.hpp"
#include "sph/penetration.hpp"
#include "sph/setups/colliding_streams.hpp"
#include "sph/setups/shock_tube.hpp"
#include "sph/simulation.hpp"
#include "sph/snapshot.hpp"
#include "sph/terms/pressure.hpp"
#include "sph/viscosity/monaghan_gingold_1983.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace {

/// \subsection ch03_schemes The three schemes
///
/// A scheme is a type, a *scene*: it derives from sph::Scene, which supplies the defaults
/// (the M4 kernel, an ideal gas, the leapfrog, no gravity, no boundaries), and names its list
/// of terms.  The simulation compiles only what the scene names.  The inviscid scheme has the
/// pressure force alone and contains no viscosity code at all; the printed scheme differs from
/// it in one pure function, the `bracket` of lib/sph/terms/pressure.hpp; the viscous scheme of
/// chapter 4 adds sph::MonaghanGingold1983 to the terms.  The dimension is a template
/// parameter, chosen in main().

template <int D>
struct HernquistKatz : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureHernquistKatz>;
};
template <int D>
struct AsPrinted : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureAsPrinted>;
};
template <int D>
struct WithViscosity : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983>;
};

/// printf into a std::string, for messages and labels.
template <class... Args>
std::string say(const char* pattern, Args... args) {
  char text[512];
  std::snprintf(text, sizeof text, pattern, args...);
  return text;
}

/// \section ch03_sod Step 1: Sod's shock tube
///
/// A scene is a shock-tube set-up, a smoothing-length rule, a Courant factor and an end time.
/// A run builds the tube (lattices of equal-mass particles, masses calibrated so that each
/// side's SPH density is its nominal density, chapter 2), integrates it to the end time and
/// keeps what we need afterwards: the particles, the exact solution, the cost in steps and
/// wall-clock seconds, and the two conservation checks of the equations above -- the
/// relative change of the total energy, and the total momentum measured against the momentum
/// scale \f$ \sum_i m_i |\mathbf v_i| \f$ (it starts at zero: the gas is at rest).

struct SodScene {
  sph::ShockTubeSetup tube = sph::ShockTubeSetup::sod();
  double neighbours = 4;  // N in h = N m / (4 rho): h = dx for N = 4
  double courant = 0.3;   // epsilon of eq 7
  double t_end = 0.2;

  sph::SmoothingLengthRule smoothing() const { return sph::SmoothingLengthRule::from_density(neighbours); }
};

template <int D>
struct SodRun {
  std::string name;
  sph::Particles<D> particles;
  sph::RiemannSolution exact;
  int in_window = 0;  // particles in [-0.5, 0.5] at t = 0
  long steps = 0;
  double seconds = 0;
  double energy_change = 0;      // |E(t) - E(0)| / E(0)
  double momentum_residual = 0;  // |sum m v| / sum m |v|
};

template <class P>
SodRun<P::D> run_sod(const std::string& name, const SodScene& scene, const typename P::Terms& terms,
                     bool report_progress) {
  constexpr int D = P::D;
  app::Stopwatch clock;
  auto tube = sph::make_shock_tube<D>(scene.tube, scene.smoothing());
  SodRun<D> run{name, {}, tube.exact};
  for (const auto& x : tube.particles.position) run.in_window += std::abs(x[0]) <= 0.5;
  // The simulation: the scheme P, an ideal gas, the time step of eq 7.
  sph::Settings settings;
  settings.smoothing = scene.smoothing();
  settings.courant = scene.courant;
  sph::Simulation<P> sim(tube.particles, tube.box, sph::IdealGas(scene.tube.gamma), terms, settings);
  const auto energy = [](const sph::Particles<D>& p) { return sph::kinetic_energy(p) + sph::thermal_energy(p); };
  const double energy_before = energy(sim.particles());
  // Integrate, with a progress line for the runs we show.
  std::optional<app::Progress> progress;
  if (report_progress) progress.emplace(scene.t_end, name);
  sim.run_until(scene.t_end, [&](const sph::Simulation<P>& s) {
    if (progress) progress->update(s.steps(), s.time(), s.last_limit().dt);
  });
  if (progress) progress->finish();
  // Conservation: momentum to round-off, energy to the accuracy of the integration.
  run.particles = sim.particles();
  double momentum_scale = 0;
  for (std::size_t i = 0; i < run.particles.size(); ++i) {
    momentum_scale += run.particles.mass[i] * run.particles.velocity[i].norm();
  }
  run.momentum_residual = sph::total_momentum(run.particles).norm() / momentum_scale;
  run.energy_change = std::abs(energy(run.particles) - energy_before) / energy_before;
  run.steps = sim.steps();
  run.seconds = clock.seconds();
  return run;
}

/// \section ch03_measure Step 2: what we measure
///
/// \subsection ch03_norms Errors against an exact solution
///
/// The \f$ L_1 \f$ norms of \f$ \rho \f$, \f$ v_x \f$ and \f$ P \f$ over the particles in
/// \f$ -0.5 \le x \le 0.5 \f$ (lib/sph/norms.hpp: particle averages, so that each region counts
/// by its mass).  The reference is any gas whose exact solution we know: Sod's gas, or the
/// equivalent gas of the printed eq 4, whose pressure must be doubled before it is compared
/// with the pressure the run reports.  A `Reference` carries that factor.

struct Reference {
  sph::RiemannSolution solution;
  double pressure_factor = 1;  // reported pressure per unit pressure of `solution`

  sph::GasState at(double x, double t) const {
    sph::GasState w = solution.sample(x, t);
    w.pressure *= pressure_factor;
    return w;
  }
};

/// The equivalent gas of the printed eq 4 (see above): \f$ \gamma' = (\gamma + 1)/2 \f$, both
/// pressures halved, reported pressure twice its own.
Reference printed_equivalent(const sph::ShockTubeSetup& tube) {
  sph::GasState left = tube.left, right = tube.right;
  left.pressure *= 0.5;
  right.pressure *= 0.5;
  return {sph::RiemannSolution(left, right, 0.5 * (tube.gamma + 1.0)), 2.0};
}

struct SodErrors {
  double density = 0, velocity = 0, pressure = 0;
};

template <int D>
SodErrors sod_errors(const sph::Particles<D>& p, const Reference& reference, double t) {
  const auto window = sph::Selection::range(-0.5, 0.5);
  const auto exact = [&](double sph::GasState::*field) {
    return [&, field](const sph::Vec<D>& x) { return reference.at(x[0], t).*field; };
  };
  const auto vx = sph::component<D>(p.velocity, 0);
  return {sph::error_norms<D>("density", p.position, p.density, exact(&sph::GasState::density), window).L1,
          sph::error_norms<D>("velocity", p.position, vx, exact(&sph::GasState::velocity), window).L1,
          sph::error_norms<D>("pressure", p.position, p.pressure, exact(&sph::GasState::pressure), window).L1};
}

/// \subsection ch03_ringing The star region: p*, ringing and heat
///
/// Between the tail of the rarefaction and the shock lies the *star region* of constant
/// pressure \f$ p_* = 0.30313 \f$ and velocity \f$ u_* = 0.92745 \f$, cut in two by the contact
/// discontinuity.  We keep two kernel supports (\f$ 4h \f$) away from the waves that bound it,
/// with h the smoothing length of the post-shock gas, \f$ h = N m/(4\rho_{*R}) \f$, and
/// measure
///  - \f$ p_* \f$ as the **median** pressure of the star region (the median ignores the
///    pressure blip that SPH makes at the contact, which is a subject of its own);
///  - the **ringing** as the RMS of \f$ v_x - u_* \f$ over the post-shock gas between the
///    contact and the shock, where the exact velocity is the constant \f$ u_* \f$: all of it
///    is noise;
///  - the **mean internal energy** of the same particles, to compare with the two values above:
///    the Rankine-Hugoniot \f$ u = 2.853 \f$ of a shock, and the \f$ u = 2.702 \f$ of an
///    adiabatic compression to the same density.

/// These numbers tell the story of the inviscid run better than the error norms.  A gas that
/// cannot make entropy reaches the post-shock density along its adiabat, with
/// \f$ u \approx 2.70 \f$; the shock's energy balance demands \f$ u = 2.85 \f$.  The
/// difference, \f$ \Delta u \approx 0.15 \f$ per unit mass, has to go somewhere, since the
/// equations conserve energy: it stays in the motion, as random velocities about the mean flow
/// with \f$ \tfrac12 \langle (v - u_*)^2 \rangle \approx \Delta u \f$.  That predicts a ringing
/// amplitude of \f$ \sqrt{2\Delta u} \approx 0.55 \f$ -- about 60 % of \f$ u_* \f$, independent of
/// the resolution, since nothing in the argument knows about \f$ \Delta x \f$.  The argument is
/// only as good as the discrete equations are adiabatic, and in the noise behind an inviscid
/// shock, where neighbours differ strongly, the two approximations noted above are no longer
/// small: they move heat between particles and can also create some.  With
/// \f$ h = \Delta x \f$ we find the post-shock gas on its adiabat and the energy budget nearly
/// closed; with \f$ h = 1.2\Delta x \f$ (`--neighbours 4.8`) the post-shock gas ends up near the
/// shock's u, yet still rings at over 40 % of \f$ u_* \f$.  What does not depend on h is that
/// nothing in the inviscid equations damps the ringing.

struct StarRegion {
  double p_star = 0;            // median pressure between rarefaction tail and shock
  double ringing = 0;           // RMS of v - u* between contact and shock
  double internal_energy = 0;   // mean u between contact and shock
  double lower = 0, upper = 0;  // the post-shock window
  int count = 0;                // particles in it
};

template <int D>
StarRegion star_region(const SodRun<D>& run, const SodScene& scene) {
  static_assert(D == 1, "the post-shock smoothing length below is the 1D rule");
  const auto& exact = run.exact;
  const double t = scene.t_end;
  const double margin = 4.0 * scene.neighbours * run.particles.mass[0] / (4.0 * exact.star_density_right());
  StarRegion star;
  star.lower = exact.contact_position(t) + margin;
  star.upper = exact.shock_position(t) - margin;
  // Median pressure over the whole star region; RMS velocity error and mean u over its shocked part.
  std::vector<double> pressures;
  double sum_square = 0, sum_u = 0;
  for (std::size_t i = 0; i < run.particles.size(); ++i) {
    const double x = run.particles.position[i][0];
    if (x > exact.rarefaction_tail_position(t) + margin && x < star.upper) pressures.push_back(run.particles.pressure[i]);
    if (x <= star.lower || x >= star.upper) continue;
    sum_square += std::pow(run.particles.velocity[i][0] - exact.star_velocity(), 2);
    sum_u += run.particles.internal_energy[i];
    ++star.count;
  }
  sph::require(star.count > 0, "star region: no particles between contact and shock (the resolution is too coarse)");
  std::nth_element(pressures.begin(), pressures.begin() + pressures.size() / 2, pressures.end());
  star.p_star = pressures[pressures.size() / 2];
  star.ringing = std::sqrt(sum_square / star.count);
  star.internal_energy = sum_u / star.count;
  return star;
}

/// \subsection ch03_fronts Where the waves are
///
/// To see whether a scheme propagates the waves at the right speeds we locate two fronts in
/// the run and in each exact solution by the *same* rule: the **shock** is where the pressure,
/// scanned from the undisturbed gas at \f$ x = 0.5 \f$ inwards, first rises through the middle
/// of Sod's pressure jump, \f$ (P_R + p_*)/2 \f$; the **rarefaction head** is where the
/// velocity, scanned from \f$ x = -0.5 \f$, first rises through 0.05.  Between the two samples
/// that bracket the crossing we interpolate linearly.  Applied to the exact profile, sampled
/// every \f$ 5\cdot 10^{-5} \f$, the rule finds the front itself (or, in the rarefaction, the
/// point a little behind the head where v reaches 0.05); applied to the particles, it finds
/// the same point of the smoothed front, a fraction of h away.

struct Fronts {
  double head = 0, shock = 0;
};

/// Where f first crosses `level` when the samples (sorted by x) are scanned from one end.
double first_crossing(const std::vector<std::pair<double, double>>& samples, double level, bool from_right) {
  const std::size_t n = samples.size();
  for (std::size_t k = 1; k < n; ++k) {
    const auto& [x_out, f_out] = samples[from_right ? n - k : k - 1];  // the sample outside
    const auto& [x_in, f_in] = samples[from_right ? n - k - 1 : k];    // the next one inwards
    if ((f_out - level) * (f_in - level) <= 0 && f_in != f_out) {
      return x_out + (level - f_out) / (f_in - f_out) * (x_in - x_out);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// The fronts of a profile given as (x, v_x, P) samples in any order.
Fronts fronts(std::vector<std::array<double, 3>> samples, const sph::RiemannSolution& sod) {
  std::sort(samples.begin(), samples.end());
  std::vector<std::pair<double, double>> velocity, pressure;
  for (const auto& [x, v, P] : samples) {
    velocity.emplace_back(x, v);
    pressure.emplace_back(x, P);
  }
  const double shock_level = 0.5 * (sod.right_state().pressure + sod.star_pressure());
  return {first_crossing(velocity, 0.05, false), first_crossing(pressure, shock_level, true)};
}

template <int D>
Fronts fronts_of_run(const SodRun<D>& run) {
  std::vector<std::array<double, 3>> samples;
  for (std::size_t i = 0; i < run.particles.size(); ++i) {
    const double x = run.particles.position[i][0];
    if (std::abs(x) <= 0.5) samples.push_back({x, run.particles.velocity[i][0], run.particles.pressure[i]});
  }
  return fronts(samples, run.exact);
}

Fronts fronts_of_exact(const Reference& reference, const sph::RiemannSolution& sod, double t) {
  std::vector<std::array<double, 3>> samples;
  for (int k = 0; k <= 20000; ++k) {
    const double x = -0.5 + k / 20000.0;
    const sph::GasState w = reference.at(x, t);
    samples.push_back({x, w.velocity, w.pressure});
  }
  return fronts(samples, sod);
}

/// All we measure of one Sod run, against Sod's gas and, for the printed scheme, against its
/// equivalent gas as well.
template <int D>
struct SodResult {
  SodRun<D> run;
  SodErrors errors;        // against Sod's gas
  SodErrors errors_own;    // against the reference the scheme should follow
  StarRegion star;
  Fronts fronts;
};

template <int D>
SodResult<D> measure(SodRun<D> run, const SodScene& scene, const Reference& own) {
  const Reference sod{run.exact, 1.0};
  const SodErrors errors = sod_errors(run.particles, sod, scene.t_end);
  const SodErrors errors_own = sod_errors(run.particles, own, scene.t_end);
  const StarRegion star = star_region(run, scene);
  const Fronts f = fronts_of_run(run);
  return {std::move(run), errors, errors_own, star, f};
}

/// \subsection ch03_figures The figures
///
/// Each run is drawn the way SPLASH draws a shock tube: \f$ \rho \f$, \f$ v_x \f$, \f$ P \f$ and
/// \f$ u \f$ against x, one dot per particle, the exact solution as a line
/// (lib/app/shock_tube_figure.hpp).  The stamp at the foot names the scheme, kernel,
/// neighbour number, particle number and run time, so a figure found on its own still says
/// what made it.  The printed scheme's figure also carries the prediction, drawn into the
/// returned figure's panels before it is saved.

template <int D>
plot::Figure sod_figure(const SodRun<D>& run, const SodScene& scene, const std::string& title, const std::string& scheme,
                        const std::string& exact_label = "exact") {
  const plot::Stamp stamp{.scheme = scheme,
                          .kernel = "M4",
                          .neighbours = scene.neighbours,
                          .particles = run.in_window,
                          .run_time = run.seconds,
                          .extra = "h = N m/(4\\rho), t = " + say("%g", scene.t_end)};
  return app::shock_tube_figure({app::make_profile<D>(run.particles, "SPH")}, run.exact, scene.t_end, title, stamp,
                                {.exact_label = exact_label});
}

/// A reference's exact \f$ \rho, v_x, P, u \f$ as dashed lines in the four panels.
void add_reference_lines(plot::Figure& figure, const Reference& reference, double t, const std::string& label,
                         plot::Color color) {
  std::vector<double> x, rho, v, P, u;
  for (int k = 0; k < 4000; ++k) {
    x.push_back(-0.5 + k / 3999.0);
    const sph::GasState w = reference.at(x.back(), t);
    rho.push_back(w.density);
    v.push_back(w.velocity);
    P.push_back(w.pressure);
    u.push_back(reference.solution.internal_energy(x.back(), t));  // u is what the scheme reports
  }
  const std::vector<double>* values[] = {&rho, &v, &P, &u};
  for (int k = 0; k < 4; ++k) {
    figure.panel(k).line(x, *values[k], {.label = label, .color = color, .style = plot::Dash::dashed, .width = 1.6});
  }
}

/// \section ch03_streams Step 4: two colliding streams
///
/// Two slabs of cold gas (\f$ \rho = 1 \f$, \f$ \gamma = 5/3 \f$, Mach number 10) run into
/// each other at \f$ \pm v_0 = \pm 1 \f$ (lib/sph/setups/colliding_streams.hpp).  The exact
/// solution is two strong shocks running outwards at \f$ v_0(\gamma - 1)/2 = 1/3 \f$, behind
/// which the gas is at rest with density 3.9 (4 in the limit of infinite Mach number).
/// Without viscosity, what could stop the streams?  Only pressure, and a cold gas has almost
/// none: its pressure can rise only by adiabatic compression.  To stop a flow of Mach number
/// \f$ \mathcal M \f$ adiabatically the internal energy must grow from
/// \f$ c_0^2/(\gamma(\gamma-1)) \f$ to \f$ \sim v_0^2/2 \f$, i.e. by a factor
/// \f$ \sim \mathcal M^2 \f$, which takes a compression by \f$ \mathcal M^{2/(\gamma-1)} \f$:
/// a thousandfold for \f$ \mathcal M = 10 \f$.
///
/// What SPH does instead depends on how close two particles may come.  The pressure force
/// between two particles is proportional to the kernel gradient, which *vanishes* at zero
/// separation (chapter 1).  If the smoothing length stays near its initial value --
/// Selhammar's rule, a fixed number of neighbours (here 5: \f$ 2h \f$ half-way between the 5th
/// and 6th neighbour, \f$ h = 1.5\Delta x \f$ on the initial lattice) -- the density of an
/// approaching pair stays finite, the barrier between them is finite, and a fast particle
/// simply goes through.  The streams **interpenetrate**, and the gas between the shocks is two
/// streams on top of each other with density 2, not a shocked gas at rest with density 4.
/// If instead h shrinks with the density (our rule for Sod), then in 1D a pair that approaches
/// raises its own density, shrinks its own h, and the barrier becomes infinite: the particles
/// cannot pass, and the streams **pile up** into a thin sheet compressed by the factor above.
/// The time step, proportional to h, collapses with it; we give that run a budget of steps,
/// and when it runs out the run stops where it is and says so.  The viscous run of chapter 4
/// completes the picture: its \f$ \beta \f$ term converts the approach into heat over a couple
/// of smoothing lengths, which is what a shock does.
///
/// During each run we record the positions of every k-th particle at 200 output times: an
/// x-t diagram of particle paths.

struct StreamsScene {
  sph::CollidingStreamsSetup setup;
  double neighbours = 5;  // the neighbour-number rule of the runs without pile-up
  double t_end = 0.4;
  int outputs = 200;      // points along each path
  int paths = 24;         // paths drawn per stream
};

template <int D>
struct StreamsRun {
  std::string name;
  sph::Particles<D> particles;
  std::vector<sph::Vec<D>> initial;
  int left_count = 0;                      // particles 0 .. left_count-1 move right
  std::vector<std::size_t> tracked;        // the particles whose paths we keep
  std::vector<double> times;               // output times
  std::vector<std::vector<double>> paths;  // paths[k][m]: x of tracked[k] at times[m]
  sph::OrderInversions inversions;
  long steps = 0;
  double seconds = 0, t_reached = 0, last_dt = 0;
  std::string stopped;  // why the run stopped early, or empty
};

template <class P>
StreamsRun<P::D> run_streams(const std::string& name, const StreamsScene& scene, const typename P::Terms& terms,
                             const sph::SmoothingLengthRule& smoothing, long step_budget) {
  constexpr int D = P::D;
  app::Stopwatch clock;
  auto streams = sph::make_colliding_streams<D>(scene.setup);
  StreamsRun<D> run;
  run.name = name;
  run.initial = streams.particles.position;
  run.left_count = streams.left_count;
  // Every k-th particle of each stream, in mirror-image pairs about x = 0.
  for (int k = streams.left_count - 1; k >= 0; k -= std::max(1, streams.left_count / scene.paths)) {
    run.tracked.push_back(static_cast<std::size_t>(k));
    run.tracked.push_back(static_cast<std::size_t>(2 * streams.left_count - 1 - k));
  }
  run.paths.resize(run.tracked.size());
  // The simulation, with a step budget; a run that cannot go on keeps what it has.
  sph::Settings settings;
  settings.smoothing = smoothing;
  settings.max_steps = step_budget;
  sph::Simulation<P> sim(streams.particles, streams.box, sph::IdealGas(scene.setup.gamma), terms, settings);
  const auto record = [&] {
    run.times.push_back(sim.time());
    for (std::size_t k = 0; k < run.tracked.size(); ++k) run.paths[k].push_back(sim.particles().position[run.tracked[k]][0]);
  };
  record();
  try {
    for (int m = 1; m <= scene.outputs; ++m) {
      sim.run_until(scene.t_end * m / scene.outputs);
      record();
    }
  } catch (const sph::Error& e) {
    run.stopped = e.what();
    record();
  }
  run.particles = sim.particles();
  run.inversions = sph::order_inversions<D>(run.initial, run.particles.position, streams.box);
  run.steps = sim.steps();
  run.seconds = clock.seconds();
  run.t_reached = sim.time();
  run.last_dt = sim.last_limit().dt;
  return run;
}

/// \subsection ch03_inversions Counting particles that have passed each other
///
/// sph::order_inversions (lib/sph/penetration.hpp) sorts the particles by their initial x and
/// counts the pairs whose order has flipped.  It reports two counts, and the difference
/// matters here.  *Adjacent* inversions -- initially neighbouring particles now in reverse
/// order -- catch any local overturning, but two streams that pass through each other keep
/// their own order: only the one pair that met first is adjacent and inverted.  *All*
/// inversions count every pair that has crossed, and grow like the square of the overlap; with
/// n particles per stream that have passed each other there are about \f$ n^2 \f$ of them.
/// The deepest penetration, the furthest any particle has gone past one that started ahead of
/// it, is the third number: for streams that never stop it is \f$ 2 v_0 t \f$.
///
/// The x-t diagram draws the paths of each run, the right-moving stream in blue and the
/// left-moving one in red, so that crossing paths are penetration.

template <int D>
void draw_paths(plot::Axes& axes, const StreamsRun<D>& run, double t_end) {
  for (std::size_t k = 0; k < run.tracked.size(); ++k) {
    const bool right_moving = static_cast<int>(run.tracked[k]) < run.left_count;
    const std::string label = k >= 2 ? "" : (right_moving ? "moving right" : "moving left");
    axes.line(run.paths[k], run.times, {.label = label, .color = right_moving ? plot::blue : plot::red, .width = 1.2});
  }
  axes.xlim(-0.6, 0.6).ylim(0.0, t_end).xlabel("x  [code units]").ylabel("t  [code units]").title(run.name);
  if (run.t_reached < t_end) {
    axes.hline(run.t_reached, {.color = plot::grey, .style = plot::Dash::dotted, .width = 1.2});
    axes.text(-0.55, run.t_reached + 0.04 * t_end, say("stopped at t = %.3f", run.t_reached),
              {.color = plot::grey, .size = 0.9});
  }
}

/// The streams figure: three x-t diagrams, and the final density of the two runs that
/// finished against the exact solution.
template <int D>
void streams_figure(const std::vector<const StreamsRun<D>*>& runs, const StreamsScene& scene, const std::string& path) {
  plot::Figure figure(2, 2, {.width = 1500, .height = 1200});
  figure.title(say("Two cold streams colliding at Mach %g (\\gamma = 5/3)", scene.setup.mach));
  double seconds = 0;
  for (const auto* run : runs) seconds += run->seconds;
  const int stride = std::max(1, runs[0]->left_count / scene.paths);
  figure.stamp(plot::Stamp{.scheme = "SPH, Hernquist-Katz",
                           .kernel = "M4",
                           .particles = static_cast<long long>(runs[0]->particles.size()),
                           .run_time = seconds,
                           .extra = say("N_{ngb} = %g in (a), (c); h = m/\\rho in (b); every %dth particle drawn",
                                        scene.neighbours, stride)});
  for (int k = 0; k < 3; ++k) draw_paths(figure.panel(k), *runs[k], scene.t_end);
  figure.panel(1).legend(plot::Corner::upper_right);
  // Panel (d): the density of the runs that reached the end, and the exact solution.
  plot::Axes& density = figure.panel(3);
  const auto exact = sph::make_colliding_streams<D>(scene.setup).exact;
  std::vector<double> xs, rho;
  for (int k = 0; k <= 2400; ++k) {
    xs.push_back(-0.6 + k / 2000.0);
    rho.push_back(exact.sample(xs.back(), scene.t_end).density);
  }
  for (const auto* run : {runs[0], runs[2]}) {
    std::vector<double> x;
    for (const auto& r : run->particles.position) x.push_back(r[0]);
    density.scatter(x, run->particles.density, {.label = run->name, .color = run == runs[0] ? plot::black : plot::blue, .size = 3.5});
  }
  density.line(xs, rho, {.label = "exact", .color = plot::red, .width = 1.6});
  density.xlim(-0.6, 0.6).ylim(0, 5.5).xlabel("x  [code units]").ylabel("\\rho  [code units]");
  density.title(say("density at t = %.2f", scene.t_end)).legend(plot::Corner::upper_right);
  figure.save_png(path);
}

/// \section ch03_error Step 5: error against run time
///
/// The last question of every chapter with a reference solution: how does the error fall as
/// we pay for more particles?  We run Sod's tube at left spacings \f$ \Delta x = 1/100 \f$ to
/// \f$ 1/3200 \f$, without and with viscosity, and hand each run to sph::ErrorVsTime
/// (lib/sph/convergence.hpp), which prints the table, fits the order p in
/// \f$ L_1 \propto \Delta x^p \f$ and the cost slope s in \f$ L_1 \propto t_\mathrm{run}^s \f$.
/// For a shock tube p = 1 is the best one can hope for: the shock is smeared over a few h, and
/// \f$ h \propto \Delta x \f$.  In 1D the cost grows like \f$ N^2 \f$ (N particles, and a time
/// step \f$ \propto h \propto 1/N \f$), so first order in \f$ \Delta x \f$ is \f$ s = -1/2 \f$.
/// The number of particles N recorded for each run is the number in the window we measure.
///
/// We already know what to expect without viscosity.  Nothing damps the ringing, and its
/// amplitude is set by the energy budget of the shock, \f$ \sim\sqrt{2\Delta u} \f$, not by the
/// resolution; more particles only sample the same noise more finely, and the region it fills, between the
/// contact and the shock, does not shrink either.  So the inviscid \f$ L_1 \f$ error should
/// stay where it is however many particles we pay for.  With viscosity, the shock is a smooth
/// transition a few h wide, and the error should fall as \f$ \Delta x^1 \f$.

template <class P>
void sweep_sod(sph::ErrorVsTime& study, const std::string& method, SodScene scene, const typename P::Terms& terms,
               const std::vector<int>& cells) {
  for (int n : cells) {
    scene.tube.left_spacing = 1.0 / n;
    const auto run = run_sod<P>(method, scene, terms, false);
    const SodErrors e = sod_errors(run.particles, Reference{run.exact, 1.0}, scene.t_end);
    study.add({method, run.in_window, scene.tube.left_spacing, run.seconds,
               {{"L1(rho)", e.density}, {"L1(v)", e.velocity}, {"L1(P)", e.pressure}}});
    std::printf("  %-20s dx = 1/%-5d N = %4d  %5ld steps  %6.2f s  L1(rho) = %.3e\n", method.c_str(), n,
                run.in_window, run.steps, run.seconds, e.density);
  }
}

/// The error figure of lib/app/error_figure.hpp, with a guide line \f$ \propto t^{-1/2} \f$
/// through the finest viscous run and the legends moved to where the curves are not.
void save_error_figure(const sph::ErrorVsTime& study, const SodScene& scene, int finest, const std::string& path) {
  app::ErrorFigureOptions options;
  options.title = "Sod's shock tube, t = 0.2: L_1 error against run time, no viscosity and AV (\\alpha = 1, \\beta = 2)";
  options.quantities = {"L1(rho)", "L1(v)"};
  options.width = 1700;
  options.height = 720;
  options.stamp = plot::format_stamp({.scheme = "SPH, Hernquist-Katz, without and with Monaghan-Gingold AV",
                                      .kernel = "M4",
                                      .neighbours = scene.neighbours,
                                      .extra = say("dx = 1/100 ... 1/%d", finest)});
  plot::Figure figure = app::error_figure(study, options);
  for (int k = 0; k < 2; ++k) {
    const sph::ErrorCurve c = study.curve("Monaghan-Gingold AV", options.quantities[k]);
    const std::vector<double> t = {c.seconds.front(), c.seconds.back()};
    const std::vector<double> e = {c.error.back() * std::sqrt(t[1] / t[0]), c.error.back()};
    figure.panel(k).line(t, e, {.label = "\\propto t^{-1/2}", .color = plot::grey, .style = plot::Dash::dotted, .width = 1.3});
    figure.panel(k).legend(plot::Corner::lower_left);
  }
  figure.save_png(path);
}

}  // namespace

/// \section ch03_main The main program
///
/// Everything above is a function of a scene; main() chooses the dimension and the scenes,
/// runs them, prints what they measured, draws the figures and checks the chapter's claims.
///
/// The parameters of the scenes are options (`--help` lists them); `--quick` halves the
/// resolution of the shock tube and the streams and stops the error sweep at
/// \f$ \Delta x = 1/400 \f$, so that the whole chapter runs in a few seconds under the tests,
/// with the same checks.  Then the steps run in turn, each printing its numbers.

int main(int argc, char** argv) {
  return app::run_main([&] {
    constexpr int dim = 1;
    app::Chapter chapter("03-equations-of-motion", "Chapter 3: the equations of motion", argc, argv);
    SodScene sod;
    StreamsScene streams;
    int cells = 800, stream_cells = 200, levels = 6;
    double alpha = 1.0, beta = 2.0;
    long pileup_budget = 20000;
    chapter.parameter("--cells", cells, "shock tube: lattice cells per unit length on the left (dx = 1/cells)")
        .check(app::at_least(300));  // coarser, the post-shock window holds no particle
    chapter.parameter("--neighbours", sod.neighbours, "shock tube: N in h = N m/(4 rho) (4: h = dx)")
        .check(app::between(2.5, 12));
    chapter.parameter("--courant", sod.courant, "Courant factor epsilon of eq 7").check(app::between(0.01, 0.9));
    chapter.parameter("--alpha", alpha, "viscosity of the contrast runs: alpha").check(app::non_negative());
    chapter.parameter("--beta", beta, "viscosity of the contrast runs: beta").check(app::non_negative());
    chapter.parameter("--mach", streams.setup.mach, "colliding streams: Mach number").check(app::at_least(1.0));
    chapter.parameter("--stream-cells", stream_cells, "colliding streams: particles per unit length")
        .check(app::at_least(20));
    chapter.parameter("--stream-neighbours", streams.neighbours, "colliding streams: neighbour number")
        .check(app::between(3, 12));
    chapter.parameter("--pileup-steps", pileup_budget, "colliding streams: step budget of the h-from-density run")
        .check(app::at_least(100));
    chapter.parameter("--levels", levels, "error sweep: resolutions dx = 1/100, 1/200, ... (7: a few minutes)")
        .check(app::between(2, 8));
    if (int rc = chapter.parse(); rc >= 0) return rc;
    if (chapter.quick()) {
      cells = 400;
      stream_cells = 100;
      pileup_budget = 4000;
      levels = 3;
    }
    sod.tube.left_spacing = 1.0 / cells;
    streams.setup.spacing = 1.0 / stream_cells;
    const sph::MonaghanGingold1983 viscosity(alpha, beta);
    const std::string output = chapter.output_dir().string();

    /// \subsection ch03_main_sod Steps 1-3: three runs of Sod's tube
    ///
    /// The same tube, three schemes.  Each is measured against Sod's gas; the printed scheme
    /// also against its equivalent gas.  Each run's final state is written as a SPLASH
    /// snapshot (lib/sph/snapshot.hpp): `splash sod_no_viscosity_00001.dat` shows it.

    const sph::RiemannSolution sod_exact(sod.tube.left, sod.tube.right, sod.tube.gamma);
    const Reference sod_gas{sod_exact, 1.0}, printed_gas = printed_equivalent(sod.tube);
    std::printf("Sod's shock tube: rho 1 | 0.125, P 1 | 0.1, v = 0, gamma = %.1f, t = %.1f\n  exact: %s\n",
                sod.tube.gamma, sod.t_end, sod_exact.describe().c_str());
    std::printf("  1D, M4 kernel, h = N m/(4 rho) with N = %g (h = %g dx), left spacing 1/%d\n\n", sod.neighbours,
                sod.neighbours / 4, cells);
    const auto inviscid =
        measure(run_sod<HernquistKatz<dim>>("Hernquist-Katz, no viscosity", sod, {}, true), sod, sod_gas);
    const auto viscous =
        measure(run_sod<WithViscosity<dim>>("Hernquist-Katz + Monaghan-Gingold AV", sod, {{}, viscosity}, true), sod, sod_gas);
    const auto printed =
        measure(run_sod<AsPrinted<dim>>("eq 4 as printed, no viscosity", sod, {}, true), sod, printed_gas);
    const std::pair<const SodResult<dim>*, const char*> sod_runs[] = {
        {&inviscid, "sod_no_viscosity"}, {&viscous, "sod_monaghan_gingold"}, {&printed, "sod_as_printed"}};
    for (const auto& [result, stem] : sod_runs) {
      sph::write_snapshot<dim>(sph::snapshot_path(output, stem, 1), result->run.particles, sod.t_end, sod.tube.gamma);
    }

    /// The numbers, in three small tables.  The first gives the \f$ L_1 \f$ errors and the two
    /// conservation checks of each run, and for the printed scheme also its errors against
    /// the gas it should describe.  The second looks into the star region: \f$ p_* \f$, the
    /// ringing, and the heat budget of the post-shock gas (heat missing against the shock's
    /// u, kinetic energy of the ringing per unit mass: by the argument above the two should
    /// be close).  The third gives the positions of the waves, exact and measured.

    std::printf("\nL1 errors in -0.5 <= x <= 0.5 (N = %d particles) against Sod's exact solution\n",
                inviscid.run.in_window);
    std::printf("  %-36s %6s  %8s  %-9s  %-9s  %-9s  %-7s  %-8s\n", "run", "steps", "wall [s]", "L1(rho)", "L1(v)",
                "L1(P)", "|dE|/E", "|sum mv|");
    for (const auto& [r, stem] : sod_runs) {
      std::printf("  %-36s %6ld  %8.2f  %.3e  %.3e  %.3e  %.1e  %.1e\n", r->run.name.c_str(), r->run.steps,
                  r->run.seconds, r->errors.density, r->errors.velocity, r->errors.pressure, r->run.energy_change,
                  r->run.momentum_residual);
    }
    std::printf("  %-36s %6s  %8s  %.3e  %.3e  %.3e   (against the gamma' = 1.2 gas)\n", "eq 4 as printed", "", "",
                printed.errors_own.density, printed.errors_own.velocity, printed.errors_own.pressure);

    const double u_shock = sod_exact.internal_energy(0.5 * (inviscid.star.lower + inviscid.star.upper), sod.t_end);
    const double u_adiabat = sph::internal_energy(sod.tube.right, sod.tube.gamma) *
                             std::pow(sod_exact.star_density_right() / sod.tube.right.density, sod.tube.gamma - 1);
    std::printf("\nStar region (exact p* = %.5f, u* = %.5f); post-shock window %.3f < x < %.3f\n",
                sod_exact.star_pressure(), sod_exact.star_velocity(), inviscid.star.lower, inviscid.star.upper);
    std::printf("  post-shock u: %.4f behind a shock (Rankine-Hugoniot), %.4f after adiabatic compression\n", u_shock,
                u_adiabat);
    for (const auto* r : {&inviscid, &viscous}) {
      const StarRegion& s = r->star;
      std::printf("  %-36s p* = %.4f (%+.2f %%), ringing = %.4f (%.2f %% of u*, %d particles)\n", r->run.name.c_str(),
                  s.p_star, 100 * (s.p_star / sod_exact.star_pressure() - 1), s.ringing,
                  100 * s.ringing / sod_exact.star_velocity(), s.count);
      std::printf("  %-36s mean u = %.4f: heat missing %.4f, kinetic energy of the ringing %.4f\n", "", s.internal_energy,
                  u_shock - s.internal_energy, 0.5 * s.ringing * s.ringing);
    }

    const Fronts f_sod = fronts_of_exact(sod_gas, sod_exact, sod.t_end);
    const Fronts f_printed_gas = fronts_of_exact(printed_gas, sod_exact, sod.t_end);
    std::printf("\nWave fronts at t = %.1f: rarefaction head (v = 0.05) and shock (P = %.4f)\n", sod.t_end,
                0.5 * (sod.tube.right.pressure + sod_exact.star_pressure()));
    const std::pair<const char*, Fronts> front_rows[] = {
        {"exact, Sod's gas (gamma = 1.4)", f_sod},
        {"exact, equivalent gas of eq 4 as printed", f_printed_gas},
        {inviscid.run.name.c_str(), inviscid.fronts},
        {viscous.run.name.c_str(), viscous.fronts},
        {printed.run.name.c_str(), printed.fronts}};
    for (const auto& [name, f] : front_rows) std::printf("  %-42s head %8.4f   shock %7.4f\n", name, f.head, f.shock);

    /// The three figures: the inviscid run, with the post-shock window marked in the velocity
    /// panel; the viscous run; and the printed run against both exact solutions.  In the first,
    /// look at the rarefaction (\f$ -0.24 < x < 0 \f$), which the particles follow to the
    /// line, and then at everything to the right of the contact.

    auto figure = sod_figure(inviscid.run, sod, "Sod's shock tube without viscosity (Hernquist & Katz form)",
                             "SPH, Hernquist-Katz, no viscosity");
    for (double x : {inviscid.star.lower, inviscid.star.upper}) {
      figure.panel(1).vline(x, {.color = plot::grey, .style = plot::Dash::dotted, .width = 1.2});
    }
    figure.save_png(chapter.figure_path("sod_no_viscosity.png").string());
    sod_figure(viscous.run, sod, "Sod's shock tube with Monaghan-Gingold viscosity (\\alpha = 1, \\beta = 2)",
               "SPH, Hernquist-Katz, Monaghan-Gingold AV")
        .save_png(chapter.figure_path("sod_monaghan_gingold.png").string());
    figure = sod_figure(printed.run, sod,
                        "Selhammar's eq 4 as printed: Sod's exact solution (red) and the prediction (blue)",
                        "SPH, bracket P_{ij}/\\rho_{ij}^2 (eq 4 as printed), no viscosity",
                        "exact, Sod (\\gamma = 1.4)");
    add_reference_lines(figure, printed_gas, sod.t_end, "prediction: \\gamma' = 1.2, P' = P/2", plot::blue);
    figure.save_png(chapter.figure_path("sod_as_printed.png").string());

    /// \subsection ch03_main_streams Step 4: the colliding streams
    ///
    /// Three runs: inviscid with h from the neighbour number, inviscid with h from the density
    /// (with its step budget), and viscous with h from the neighbour number.  For each we print
    /// the cost, the time reached, the highest density, and the three counts of
    /// sph::order_inversions.  The x-t diagrams and the final densities go into one figure;
    /// the final states of the two complete runs into snapshots.

    std::printf("\nColliding streams: rho = 1, v = +-1, Mach %g, gamma = 5/3, %d particles per stream, t = %.2f\n",
                streams.setup.mach, stream_cells, streams.t_end);
    const auto neighbour_rule = sph::SmoothingLengthRule::neighbour_number(streams.neighbours);
    const long unlimited = 10'000'000;
    const auto passing = run_streams<HernquistKatz<dim>>(say("no viscosity, %g neighbours", streams.neighbours),
                                                         streams, {}, neighbour_rule, unlimited);
    const auto pileup = run_streams<HernquistKatz<dim>>("no viscosity, h from density", streams, {},
                                                        sph::SmoothingLengthRule::from_density(4.0), pileup_budget);
    const auto stopped = run_streams<WithViscosity<dim>>(say("Monaghan-Gingold AV, %g neighbours", streams.neighbours),
                                                         streams, {{}, viscosity}, neighbour_rule, unlimited);
    const double dx_stream = streams.setup.length / passing.left_count;
    std::printf("  (of %zu pairs; deepest: how far a particle has passed one that started ahead of it)\n",
                passing.inversions.pairs());
    std::printf("  %-34s %6s  %8s  %7s  %9s  %14s  %8s  %12s\n", "run", "steps", "wall [s]", "t", "rho_max",
                "inverted pairs", "adjacent", "deepest [dx]");
    for (const auto* run : {&passing, &pileup, &stopped}) {
      const double rho_max = *std::max_element(run->particles.density.begin(), run->particles.density.end());
      std::printf("  %-34s %6ld  %8.2f  %7.4f  %9.3g  %14zu  %8zu  %12.1f\n", run->name.c_str(), run->steps,
                  run->seconds, run->t_reached, rho_max, run->inversions.all, run->inversions.adjacent,
                  run->inversions.deepest / dx_stream);
      if (!run->stopped.empty()) std::printf("  %34s stopped: %s; last step %.2e\n", "", run->stopped.c_str(), run->last_dt);
    }
    sph::write_snapshot<dim>(sph::snapshot_path(output, "streams_no_viscosity", 1), passing.particles, passing.t_reached,
                             streams.setup.gamma);
    sph::write_snapshot<dim>(sph::snapshot_path(output, "streams_monaghan_gingold", 1), stopped.particles,
                             stopped.t_reached, streams.setup.gamma);
    streams_figure<dim>({&passing, &pileup, &stopped}, streams, chapter.figure_path("colliding_streams.png").string());

    /// \subsection ch03_main_error Step 5: the error sweep

    std::printf("\nError against run time, Sod's tube at t = %.1f\n", sod.t_end);
    const std::vector<int> sweep_cells = sph::geometric_series(100, 2, levels);
    sph::ErrorVsTime study("Sod's shock tube at t = 0.2: L1 errors in -0.5 <= x <= 0.5, N = particles there");
    sweep_sod<HernquistKatz<dim>>(study, "no viscosity", sod, {}, sweep_cells);
    sweep_sod<WithViscosity<dim>>(study, "Monaghan-Gingold AV", sod, {{}, viscosity}, sweep_cells);
    std::printf("\n%s", study.table().c_str());
    save_error_figure(study, sod, sweep_cells.back(), chapter.figure_path("sod_error_vs_time.png").string());

    /// \subsection ch03_checks The checks
    ///
    /// The chapter's claims, each tested on the numbers this run has just measured; a claim
    /// that fails makes the program exit non-zero.  In order:
    ///  1. the pair forces conserve momentum to round-off, and the leapfrog energy to
    ///     \f$ 2\cdot 10^{-3} \f$, in all three runs;
    ///  2. without viscosity the waves still travel at Sod's speeds: the rarefaction head
    ///     within 0.005, the shock within 0.02 (a few post-shock smoothing lengths);
    ///  3. ... but the post-shock velocity rings, with an RMS above 10 % of \f$ u_* \f$ and ten
    ///     times that of the viscous run, and (with \f$ h = \Delta x \f$; see above for
    ///     \f$ 1.2\Delta x \f$) the post-shock gas lies nearer its adiabat than the Hugoniot
    ///     value of u;
    ///  4. with viscosity \f$ p_* \f$ and the post-shock u are right to 1 %, and
    ///     \f$ L_1(\rho) \f$ is at least four times smaller;
    ///  5. eq 4 as printed moves both fronts more than 20 % too slowly, follows the predicted
    ///     \f$ \gamma' = 1.2 \f$ gas to within 0.01 (head) and 0.02 (shock), and is more than
    ///     twice as close to it as to Sod's gas in \f$ L_1(\rho) \f$;
    ///  6. inviscid streams with a fixed neighbour number pass through each other (inversions,
    ///     and particles more than 10 \f$ \Delta x \f$ past one that started ahead); with h from
    ///     the density they do not; with viscosity the inversions are fewer than 1 % of the
    ///     inviscid ones;
    ///  7. without viscosity \f$ L_1(\rho) \f$ does not converge (fitted order below 0.3); with
    ///     it, it converges at nearly first order (above 0.7).

    std::printf("\n");
    for (const auto& [r, stem] : sod_runs) {
      chapter.check(r->run.momentum_residual < 1e-12,
                    say("%s: momentum %.2e of its scale, not round-off", r->run.name.c_str(), r->run.momentum_residual));
      chapter.check(r->run.energy_change < 2e-3,
                    say("%s: energy changed by %.2e (> 2e-3)", r->run.name.c_str(), r->run.energy_change));
    }
    chapter.check(std::abs(inviscid.fronts.head - f_sod.head) < 0.005 && std::abs(inviscid.fronts.shock - f_sod.shock) < 0.02,
                  say("inviscid waves: head %.4f, shock %.4f; Sod's %.4f, %.4f", inviscid.fronts.head,
                      inviscid.fronts.shock, f_sod.head, f_sod.shock));
    chapter.check(std::abs(inviscid.star.internal_energy - u_adiabat) < std::abs(inviscid.star.internal_energy - u_shock),
                  say("inviscid post-shock u = %.4f is not nearer the adiabat %.4f than the shock's %.4f",
                      inviscid.star.internal_energy, u_adiabat, u_shock));
    chapter.check(inviscid.star.ringing > 0.1 * sod_exact.star_velocity() && inviscid.star.ringing > 10 * viscous.star.ringing,
                  say("inviscid ringing %.4f should exceed 10 %% of u* and 10x the viscous %.4f", inviscid.star.ringing,
                      viscous.star.ringing));
    chapter.check(std::abs(viscous.star.p_star / sod_exact.star_pressure() - 1) < 0.01 &&
                      std::abs(viscous.star.internal_energy / u_shock - 1) < 0.01,
                  say("viscous p* = %.4f and post-shock u = %.4f should be within 1 %% of %.5f and %.4f",
                      viscous.star.p_star, viscous.star.internal_energy, sod_exact.star_pressure(), u_shock));
    chapter.check(viscous.errors.density < 0.25 * inviscid.errors.density,
                  say("viscous L1(rho) = %.3e is not 4x below the inviscid %.3e", viscous.errors.density,
                      inviscid.errors.density));
    chapter.check(std::abs(printed.fronts.shock - f_sod.shock) > 0.2 * f_sod.shock &&
                      std::abs(printed.fronts.head - f_sod.head) > 0.2 * std::abs(f_sod.head),
                  say("eq 4 as printed: head %.4f, shock %.4f are not 20 %% slow", printed.fronts.head, printed.fronts.shock));
    chapter.check(std::abs(printed.fronts.head - f_printed_gas.head) < 0.01 &&
                      std::abs(printed.fronts.shock - f_printed_gas.shock) < 0.02,
                  say("eq 4 as printed: head %.4f, shock %.4f; predicted %.4f, %.4f", printed.fronts.head,
                      printed.fronts.shock, f_printed_gas.head, f_printed_gas.shock));
    chapter.check(printed.errors_own.density < 0.5 * printed.errors.density,
                  say("eq 4 as printed: L1(rho) %.3e against the prediction, %.3e against Sod", printed.errors_own.density,
                      printed.errors.density));
    chapter.check(passing.inversions.all > 0 && passing.inversions.deepest > 10 * dx_stream,
                  "inviscid streams should pass through each other: " + passing.inversions.summary());
    chapter.check(pileup.inversions.all == 0, "streams with h from density should not pass: " + pileup.inversions.summary());
    chapter.check(stopped.inversions.all * 100 <= passing.inversions.all,
                  "viscous streams: more than 1 % of the inviscid inversions: " + stopped.inversions.summary());
    const double order_inviscid = study.order("no viscosity", "L1(rho)");
    const double order_viscous = study.order("Monaghan-Gingold AV", "L1(rho)");
    chapter.check(order_inviscid < 0.3, say("inviscid L1(rho) converges at order %.2f (expected < 0.3)", order_inviscid));
    chapter.check(order_viscous > 0.7, say("viscous L1(rho) converges at order %.2f (expected > 0.7)", order_viscous));

    chapter.summary("error", say("L1(rho) = %.4f (no AV), %.5f (AV), %.4f (eq 4 as printed), N = %d",
                                 inviscid.errors.density, viscous.errors.density, printed.errors.density,
                                 inviscid.run.in_window));
    chapter.summary("ringing", say("%.4f (no AV), %.4f (AV)", inviscid.star.ringing, viscous.star.ringing));
    chapter.summary("inversions", say("%zu (no AV), %zu (AV)", passing.inversions.all, stopped.inversions.all));
    return chapter.finish();
  });
}

/// \section ch03_next What comes next
///
/// The inviscid equations are right where the flow is smooth and wrong at every shock,
/// because they cannot make entropy: the energy a shock should turn into heat stays in the
/// particles' motion, and where streams collide nothing stops them but an adiabatic pile-up.
/// Chapter 4 (\ref ch04) adds the term that can make entropy -- the artificial viscosity of
/// Monaghan & Gingold (1983), of which we have already seen the effect -- and measures what it
/// costs and what it buys.
