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
/// smoothing length that shrinks as particles crowd together, piles them into a sheet
/// thousands of times denser than it should be, until the time step collapses.  These
/// failures are the reason artificial viscosity exists, and chapter 4 adds it.  To let the
/// reader see what is coming, every test is also run once with the Monaghan & Gingold (1983)
/// viscosity of chapter 4 switched on.
///
/// Along the way we meet a misprint.  Selhammar (1997) eq 4 prints the pressure term of the
/// momentum equation as \f$ \bar P_{ij}/\bar\rho_{ij}^2 \f$; the Hernquist & Katz (1989) form
/// it cites is \f$ P_i/\rho_i^2 + P_j/\rho_j^2 \f$.  We do not quietly substitute one for the
/// other: we run both, work out exactly what the printed form does, and show that the
/// simulation agrees with that prediction.
///
/// The program has seven steps, each a function below with its own heading, and `main` at the
/// end calls them in order:
///  1. Sod's tube at the resolution at which chapter 4 meets a mature code (450 particles in
///     the window \f$ -0.5 \le x \le 0.5 \f$), run three times: without viscosity, with the
///     Monaghan-Gingold viscosity, and with eq 4 as printed;
///  2. the \f$ L_1 \f$ errors of the three runs, and how well each conserves energy and
///     momentum;
///  3. a closer look at the gas behind the shock: its pressure, the ringing, and where the
///     heat that the shock should have made has gone;
///  4. where the waves are, in the runs and in two exact solutions -- Sod's, and that of the
///     gas the printed eq 4 describes;
///  5. the three shock-tube figures;
///  6. the colliding streams, with a diagnostic that counts particles that have passed one
///     another;
///  7. the error of Sod's tube against run time at six resolutions, with and without
///     viscosity: does the inviscid error converge?  (It does not.)
///
/// After the steps, the program checks the chapter's claims on the numbers it has just
/// measured.
///
/// \section ch03_equations The equations of motion
///
/// \subsection ch03_momentum Momentum
///
/// The Euler equation \f$ d\mathbf v/dt = -\nabla P/\rho \f$ can be discretised in many ways;
/// the one that conserves momentum exactly starts from the identity
/// \f[ \frac{\nabla P}{\rho} = \nabla\!\left(\frac P\rho\right) + \frac{P}{\rho^2}\nabla\rho , \f]
/// replaces each gradient by its SPH sum \f$ \nabla A_i \approx \sum_j m_j (A_j/\rho_j)
/// \nabla_i W_{ij} \f$ (chapter 1), and gets the symmetric form of Hernquist & Katz (1989).
/// This is how we read Selhammar (1997) eq 4: with the bracket of the paper it cites, not with
/// the bracket it prints (the section after next explains the difference; the page
/// \ref papers "Reading the two papers" lists this reading with every other one the course
/// makes, equation by equation):
/// \f[ \frac{d\mathbf v_i}{dt} = -\sum_j m_j \left( \frac{P_i}{\rho_i^2} + \frac{P_j}{\rho_j^2}
///       \right) \nabla_i W(r_{ij}, \bar h_{ij}), \qquad \bar h_{ij} = \tfrac12 (h_i + h_j). \f]
/// (Chapter 4 adds \f$ \Pi_{ij} \f$ to the bracket; here it is zero.)
///
/// **Sign conventions.** We write \f$ \mathbf r_{ij} = \mathbf r_i - \mathbf r_j \f$ and
/// \f$ \mathbf v_{ij} = \mathbf v_i - \mathbf v_j \f$.  The kernel gradient is
/// \f$ \nabla_i W_{ij} = W'(r_{ij})\,\mathbf r_{ij}/r_{ij} \f$ with \f$ W' < 0 \f$, so it points
/// from i towards j; the minus sign in front of the sum then pushes i *away* from j, as a
/// pressure must.  Selhammar prints \f$ \mathbf v_{ij} = \mathbf v_j - \mathbf v_i \f$ in eq 4
/// (with a minus sign in front of its energy equation, so that the two together still heat a
/// compressed gas), which contradicts his own eq 6, where an approaching pair has
/// \f$ \mathbf r_{ij}\cdot\mathbf v_{ij} < 0 \f$; we use \f$ \mathbf v_i - \mathbf v_j \f$
/// throughout, and the energy equation with a plus sign
/// (\ref papers_selhammar_eq4 "see our reading").
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
/// \mathbf v_{ij}/r_{ij} > 0 \f$: compression heats, as it should.  The kinetic energy the pair
/// force takes from the relative motion, \f$ m_i m_j(\dots)\,\mathbf v_{ij}\cdot\nabla_i W_{ij}
/// \f$, is exactly what the two particles gain in internal energy, so
/// \f$ E = \sum_i m_i (\tfrac12 v_i^2 + u_i) \f$ is conserved by the equations; the time
/// integration conserves it to \f$ O(\delta t^2) \f$, and we check that too.
///
/// These equations are adiabatic: in the continuum limit \f$ du/dt \f$ is exactly the
/// \f$ P\,dV \f$ work, and nothing in them can raise the entropy \f$ P/\rho^\gamma \f$ of the
/// gas.  (The discrete form is adiabatic only approximately.  It shares the work of each pair
/// equally between the two particles, which is exact only when
/// \f$ P_i/\rho_i^2 = P_j/\rho_j^2 \f$; and with h varying from particle to particle, the
/// density sum changes by terms in \f$ \partial W/\partial h \f$ that the energy equation does
/// not contain -- the "grad-h" terms of later SPH formulations.  Both errors are small in a
/// smooth flow.)  A shock, however, *must* raise the entropy: the Rankine-Hugoniot conditions
/// put the gas behind Sod's shock on a higher adiabat, with \f$ P/\rho^\gamma \f$ 5.5 % above
/// that of the gas in front and internal energy \f$ u = 2.854 \f$ instead of the
/// \f$ u_R(\rho_{*R}/\rho_R)^{\gamma-1} = 2.704 \f$ an adiabatic compression to the same
/// density would give.  Keep that in mind when we look at the results.
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
/// \f$ \gamma' = 1.2 \f$ -- and predict the printed scheme's result before running it.  Steps
/// 2 and 4 do both.  (The argument uses \f$ \rho_i \approx \rho_j \f$; at the contact
/// discontinuity, where the density jumps, the two brackets differ in other ways as well.)
///
/// \section ch03_integration Time integration
///
/// Selhammar's eq 8 is the leapfrog: velocities and energies at half steps, positions at whole
/// steps.  The library writes it in the equivalent kick-drift-kick form
/// (lib/sph/simulation.hpp),
/// \f[ \mathbf v^{n+1/2} = \mathbf v^n + \tfrac12\delta t\,\mathbf a^n, \quad
///     \mathbf r^{n+1} = \mathbf r^n + \delta t\,\mathbf v^{n+1/2}, \quad
///     \mathbf v^{n+1} = \mathbf v^{n+1/2} + \tfrac12\delta t\,\mathbf a^{n+1}, \f]
/// and the same for u, which produces the same trajectory for a constant step but also has
/// \f$ \mathbf v \f$ and \f$ u \f$ at whole steps for the snapshots, and allows the step to
/// change.  The step is eq 7 with \f$ \varepsilon = 0.3 \f$ (`--courant`),
/// \f[ \delta t = \min_i \frac{\varepsilon h_i}{|\mathbf v_i| + c_i
///       + 1.2(\alpha c_i + \beta\mu_{i,\max})}, \f]
/// in which the viscous term vanishes for the inviscid runs (\f$ \alpha = \beta = 0 \f$), plus
/// the limits \f$ \varepsilon\sqrt{h_i/|\mathbf a_i|} \f$ on the acceleration and
/// \f$ \varepsilon\, u_i/|\dot u_i| \f$ on the cooling, where \f$ \dot u_i < 0 \f$.  The idea
/// behind eq 7 is the Courant condition of every explicit scheme: in one step no signal -- the
/// particle itself, a sound wave, the viscous response -- may travel more than a fraction \f$
/// \varepsilon \f$ of a smoothing length, or the particles would react to a neighbour that is no
/// longer where its force was computed.  One step for all particles, the smallest of the limits, is
/// what the papers use, and it is what makes the leapfrog's error analysis hold: the scheme is
/// second order in \f$ \delta t \f$, so halving the step should cut the energy error of Step 2
/// about fourfold (`--courant`; the results page tries it: the viscous run's falls 3.3-fold, the
/// two noisy inviscid ones' 7-8-fold, their noise itself changing with the step).
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
/// `--neighbours 4.8` for \f$ h = 1.2\Delta x \f$; the results page says what changes.)
///
/// \section ch03_exact The exact solution, and how to read it
///
/// Every number this chapter prints is measured against the exact solution of the Riemann problem
/// (lib/sph/reference/riemann.hpp, the exact solver of Toro's book), so it is worth knowing its
/// shape before we look at any run.  Released at \f$ t = 0 \f$, Sod's interface breaks into four
/// waves, whose speeds Step 1 prints: the head and the tail of a **rarefaction** running left into
/// the dense gas (speeds \f$ -1.183 \f$ and \f$ -0.070 \f$), a **contact discontinuity** moving
/// right with the gas (\f$ u_* = 0.927 \f$), and a **shock** running right into the thin gas
/// (1.752).  At \f$ t = 0.2 \f$ they stand at \f$ x = -0.237 \f$, \f$ -0.014 \f$, \f$ 0.185 \f$ and
/// \f$ 0.350 \f$.  Between the tail and the shock lies the *star region*, where pressure and
/// velocity are constant, \f$ p_* = 0.303 \f$ and \f$ u_* = 0.927 \f$, and only the density jumps,
/// at the contact, from \f$ \rho_{*L} = 0.426 \f$ (gas that came from the left, expanded) to
/// \f$ \rho_{*R} = 0.266 \f$ (gas that came from the right, shocked).  All four waves stay inside
/// the window \f$ -0.5 \le x \le 0.5 \f$ in which we measure, and the waves of the periodic tube's
/// second interface at \f$ x = \pm 1 \f$ do not reach it.
///
/// The gas behind the shock is where the chapter's story happens.  Its density
/// \f$ \rho_{*R} = 2.12\,\rho_R \f$ and pressure \f$ p_* \f$ give it, by the ideal-gas law
/// \f$ u = P/((\gamma - 1)\rho) \f$, the internal energy \f$ u = 2.854 \f$ of the energy section;
/// a gas compressed to the same density without a shock would have only 2.704, and the
/// difference is the heat the shock makes.  Smooth parts of the solution -- the rarefaction
/// fan and the plateaus -- are what any consistent scheme should get right; the three jumps
/// are where a scheme shows what it does with discontinuities.
///
/// \section ch03_program The program
///
/// The chapter uses the library's shock-tube set-up (a periodic tube of period 2 whose second
/// interface at \f$ x = \pm 1 \f$ stays far from the window we measure, masses calibrated as in
/// chapter 2), the exact Riemann solver, the simulation loop, and a few additions: the
/// colliding-stream set-up `lib/sph/setups/colliding_streams.hpp`, the penetration diagnostic
/// `lib/sph/measures/penetration.hpp`, and two runners that build a scene, integrate it and keep
/// what we measure, `lib/app/shock_tube_run.hpp` (which chapter 4 shares) and
/// `lib/app/colliding_streams_run.hpp`.  Two files of the chapter's own help draw its figures,
/// and this page shows each where a step first uses it: `figure_lines.hpp`, lines added to a
/// finished figure, at the end of Step 5, and `colliding_streams_figure.hpp`, the figure of
/// Step 6, at the end of that step.
///
/// The steps hand their results on.  Step 1 makes the three runs of Sod's tube and returns
/// them; Steps 2 to 5 only look at those runs, each from its own angle, and return what they
/// measured; Steps 6 and 7 make runs of their own.  Nothing is measured twice, and the checks
/// at the end read the numbers the steps returned, the same numbers the steps printed.  Each
/// step begins its output with a line "Step N: ..." that matches its heading here, so that the
/// output on the results page can be read side by side with the code.

#include "app/chapter.hpp"
#include "app/colliding_streams_run.hpp"
#include "app/curve_reading.hpp"
#include "colliding_streams_figure.hpp"
#include "app/error_figure.hpp"
#include "figure_lines.hpp"
#include "app/shock_tube_figure.hpp"
#include "app/shock_tube_run.hpp"
#include "app/text.hpp"
#include "plot/figure.hpp"
#include "sph/measures/convergence.hpp"
#include "sph/measures/norms.hpp"
#include "sph/measures/penetration.hpp"
#include "sph/measures/snapshot.hpp"
#include "sph/setups/colliding_streams.hpp"
#include "sph/setups/shock_tube.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/pressure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace {

using app::format;

/// \subsection ch03_schemes The three schemes
///
/// A scheme is a type, a *scene*: it derives from sph::Scene, which supplies the defaults
/// (the M4 kernel, an ideal gas, the leapfrog, no gravity, no boundaries), and names its list
/// of terms.  The simulation compiles only what the scene names.  The inviscid scheme has the
/// pressure force alone and contains no viscosity code at all; the printed scheme differs from
/// it in one pure function, the `bracket` of lib/sph/terms/pressure.hpp; the viscous scheme of
/// chapter 4 adds sph::MonaghanGingold1983 to the terms.  The dimension is a template
/// parameter; this chapter runs in one.
///
/// A run is handed the *values* of its terms as a `Terms` object, in the order of the list:
/// `{}` for a scheme whose only term, the pressure force, has no parameters, and
/// `{{}, viscosity}` for the viscous scheme, whose second term carries \f$ \alpha \f$ and
/// \f$ \beta \f$.  That is all the calls of the steps below need to say about a scheme.

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

constexpr int dim = 1;

/// \subsection ch03_parameters The parameters
///
/// Two scenes make up the chapter.  Sod's tube is a shock-tube set-up, a smoothing-length
/// rule (h from the density with N neighbours, so \f$ h = N\Delta x/4 \f$), a Courant factor and
/// an end time.  The colliding streams are a set-up of their own, run with a fixed neighbour
/// number, and sampled at 200 output times so that we can draw the paths of the particles.

struct SodScene {
  sph::ShockTubeSetup tube = sph::ShockTubeSetup::sod();
  double neighbours = 4;  // N in h = N m / (4 rho): h = dx for N = 4
  double courant = 0.3;   // epsilon of eq 7
  double t_end = 0.2;

  sph::SmoothingLengthRule smoothing() const {
    return sph::SmoothingLengthRule::from_density(neighbours);
  }
};

struct StreamsScene {
  sph::CollidingStreamsSetup setup;
  double neighbours = 5;  // the neighbour-number rule of the runs without pile-up
  double t_end = 0.4;
  int outputs = 200;  // points along each path
  int paths = 24;     // paths drawn per stream
};

/// Every number a reader may want to change is a command-line option, declared below with
/// its range (`--help` lists them with their defaults).  The ranges are not decoration; each
/// keeps the chapter's measurements meaningful:
///  - `--cells` from 300 to 3200: coarser, the post-shock window of Step 3, four smoothing
///    lengths from the contact and from the shock, holds no particle at all; finer, the run
///    grows as the square of the resolution (more particles, shorter steps);
///  - `--neighbours` between 2.7 and 8, and no more than the resolution allows.  Below
///    \f$ N = 8/3 \f$ the rule \f$ h = Nm/(4\rho) \f$ has no fixed point: as \f$ h \f$ shrinks,
///    the density tends to a particle's own term \f$ 2m/(3h) \f$, and the rule then gives
///    \f$ 3Nh/8 < h \f$, so \f$ h \f$ collapses to zero.  Above 8, the coarsest tube of
///    Step 7's sweep, 100 particles per unit length on the left and 12.5 on the right, has no
///    particle 1.5 kernel supports from both ends of its right side, where the tube's masses are
///    calibrated.  And many neighbours smooth the waves over so many particles that the
///    post-shock window, 0.165 wide at \f$ t = 0.2 \f$ and keeping \f$ 4h \f$ from both of its
///    ends, holds no particle: the program asks for
///    \f$ 0.165\,\rho_*\,\mathrm{cells} \ge 2N + 3 \f$ (three particles in the window) and
///    says which `--cells` a given `--neighbours` needs;
///  - `--courant` up to 0.8: eq 7 is a stability condition, and a factor near one leaves no
///    margin for the step-to-step change of the signal speed -- at 0.9 the inviscid tube's
///    post-shock oscillations grow until a particle's internal energy turns negative;
///  - `--mach` from 1 to 100: the colliding streams are meant to collide supersonically;
///  - `--levels` from 2 to 8: two resolutions are the least from which an order can be fitted,
///    and each further level makes the sweep about four times as long.
///
/// `--quick` halves the resolution of the tube and of the streams, gives the pile-up run 4000
/// steps instead of 20000, and stops the error sweep of Step 7 at \f$ \Delta x = 1/400 \f$, so
/// that the whole chapter runs in a few seconds under the tests, with the same checks.  These
/// are the quick defaults of `--cells`, `--stream-cells`, `--pileup-steps` and `--levels`: an
/// option given on the command line keeps its value with `--quick` too.

struct Parameters {
  SodScene sod;
  StreamsScene streams;
  int cells = 800;             // Sod: lattice cells per unit length on the left (dx = 1/cells)
  int stream_cells = 200;      // streams: particles per unit length
  int levels = 6;              // Step 7: resolutions dx = 1/100, 1/200, ...
  double alpha = 1, beta = 2;  // the viscosity of the contrast runs
  long pileup_steps = 20000;   // streams: the step budget of the run with h from the density

  sph::MonaghanGingold1983 viscosity() const { return {alpha, beta}; }
  /// The viscous runs' name in tables, legends and titles: the paper's viscosity, or the
  /// coefficients that ran, so that a run with other values (`--alpha 0 --beta 0`: no viscosity
  /// at all) is never labelled as Monaghan-Gingold's.
  std::string viscous_name() const {
    return alpha == 1 && beta == 2 ? "Monaghan-Gingold AV"
                                   : format("AV alpha %g, beta %g", alpha, beta);
  }
  /// The coefficients as a formula, for titles.
  std::string viscous_coefficients() const {
    return format("\\alpha = %g, \\beta = %g", alpha, beta);
  }
};

/// `declare_parameters` binds each option to its member of `Parameters`, whose initial value is
/// the default, and adds the `--quick` default where there is one and the range.  A count such
/// as `--cells` is checked with app::count_between, which refuses a value too large with the
/// memory it would need.  The first two options fix the tube's resolution and smoothing
/// length.  Whether Step 3's post-shock window holds any particle depends on both, so a
/// condition that the program checks after reading all options ties the two together.
void declare_parameters(app::Chapter& chapter, Parameters& par) {
  // (coarser than 300, the post-shock window holds no particle; the tube holds 1.125 cells
  // particles per unit length, two units long, and its cost grows as cells^2)
  chapter
      .parameter("--cells", par.cells,
                 "shock tube: lattice cells per unit length on the left (dx = 1/cells)", 400)
      .check(
          app::count_between(300, 3200, [](double n) { return app::particle_bytes(1, 2.25 * n); }));
  // (below N = 8/3 the rule h = N m/(4 rho) has no fixed point: as h shrinks, the density tends
  // to a particle's own term 2m/(3h), and h = 3N h/8 shrinks further, to zero)
  chapter
      .parameter("--neighbours", par.sod.neighbours,
                 "shock tube: N in h = N m/(4 rho) (4: h = dx; below 8/3, h collapses to zero; "
                 "above 8, Step 7's coarsest tube has no interior)")
      .check(app::between(2.7, 8));
  // Step 3's post-shock window keeps 4h from the contact and from the shock, 0.165 apart at
  // t = 0.2, where h = N / (4 rho* cells) with rho* = 0.266: it holds three particles only
  // when 0.165 rho* cells >= 2N + 3.
  chapter.require(
      [&par] { return 0.165 * 0.266 * par.cells >= 2 * par.sod.neighbours + 3; },
      [&par] {
        return "--neighbours " + app::show(par.sod.neighbours) + " needs --cells " +
               app::show(std::ceil((2 * par.sod.neighbours + 3) / (0.165 * 0.266))) +
               " or more (Step 3's post-shock window, 4h from the contact and from the shock, " +
               "holds no particle otherwise), got " + app::show(par.cells);
      });
  /// The remaining options set the time step, the viscosity of the contrast runs, the colliding
  /// streams of Step 6 and the length of Step 7's sweep.  `set_resolution` below turns the two
  /// resolutions, given as counts per unit length, into the spacings the set-ups use.
  // (at 0.9 the inviscid tube's post-shock oscillations grow until a particle's energy turns
  // negative)
  chapter.parameter("--courant", par.sod.courant, "Courant factor epsilon of eq 7")
      .check(app::between(0.01, 0.8));
  chapter.parameter("--alpha", par.alpha, "viscosity of the contrast runs: alpha")
      .check(app::between(0.0, 10.0));
  chapter.parameter("--beta", par.beta, "viscosity of the contrast runs: beta")
      .check(app::between(0.0, 20.0));
  chapter.parameter("--mach", par.streams.setup.mach, "colliding streams: Mach number")
      .check(app::between(1.0, 100.0));
  chapter
      .parameter("--stream-cells", par.stream_cells, "colliding streams: particles per unit length",
                 100)
      .check(app::count_between(20, 1600, [](double n) { return app::particle_bytes(1, 2 * n); }));
  chapter
      .parameter("--stream-neighbours", par.streams.neighbours,
                 "colliding streams: neighbour number")
      .check(app::between(3, 12));
  chapter
      .parameter("--pileup-steps", par.pileup_steps,
                 "colliding streams: step budget of the h-from-density run", 4000)
      .check(app::between(100, 1e6));
  chapter
      .parameter("--levels", par.levels,
                 "error sweep: resolutions dx = 1/100, 1/200, ... (7: a few minutes)", 3)
      .check(app::between(2, 8));
}

void set_resolution(Parameters& par) {
  par.sod.tube.left_spacing = 1.0 / par.cells;
  par.streams.setup.spacing = 1.0 / par.stream_cells;
}

/// \section ch03_sod Step 1: Sod's tube, three ways
///
/// We run the same tube three times and change only the scene: the Hernquist & Katz pressure
/// force alone, which is the scheme this chapter is about; the same with the Monaghan-Gingold
/// viscosity of chapter 4 (\f$ \alpha = 1 \f$, \f$ \beta = 2 \f$; `--alpha` and `--beta`);
/// and eq 4 with its bracket as printed.  Every run goes through app::run_shock_tube, the
/// runner that chapter 4 uses as well.  It builds the tube with sph::make_shock_tube --
/// lattices of equal-mass particles, 800 per unit length on the left (`--cells`), masses
/// calibrated so that each side's SPH density is its nominal density (chapter 2) -- integrates
/// it to \f$ t = 0.2 \f$, and returns what the later steps measure: the particles, the exact
/// solution, the number of steps, the wall time of the integration, and the two conservation
/// checks of the equations above.  These are the relative change of the total energy, and the
/// total momentum measured against the momentum scale \f$ \sum_i m_i|\mathbf v_i| \f$
/// (sph::momentum_scale): the gas starts at rest, so its momentum starts at zero and no
/// relative change can be formed.
///
/// The step prints the exact solution first -- the speeds of the four waves and the star state
/// between them, read as the section on the exact solution explains, and referred to by Steps 3 and
/// 4 -- and then one line per run as it ends, with its steps and wall time.  (In a terminal a
/// progress line on standard error shows a run while it goes.)  Look at the step counts.  The
/// viscous run takes about twice as many steps as the inviscid one, for a reason that has nothing
/// to do with the shock: eq 7 adds the viscous signal speed \f$ 1.2\,\alpha c_i \f$ to the sound
/// speed of *every* particle, so even the gas at rest gets a step 2.2 times shorter.
///
/// Each run's final state is also written as a snapshot in SPLASH's ASCII format
/// (lib/sph/measures/snapshot.hpp): `splash sod_no_viscosity_00001.dat` in the output directory
/// shows the first run, particle by particle.
///
/// The mass calibration has nothing to correct in these runs: at \f$ h = \Delta x \f$ the lattice
/// sum of the M4 kernel is exact (chapter 4, Step 2), so the interior of each side already has
/// its nominal density.  It starts to matter with `--neighbours 4.8`, where the uncorrected
/// sum would be 0.18 % high.
///
/// The code is short because the runner does the work.  `SodRuns` keeps the three runs under
/// the names the later steps use.  `run_sod` adapts the runner to a scene of this chapter --
/// the tube, its smoothing-length rule, the Courant factor and the end time -- and says what
/// a run prints: the three runs here report their steps and time when they end, the sweep of
/// Step 7 only shows its progress line.  The runs are made in the order of the braced list
/// that initialises `SodRuns`, an order C++ guarantees, so their report lines come out in the
/// order of the tables that follow.

struct SodRuns {
  app::TubeRun<dim> inviscid, viscous, printed;

  std::array<const app::TubeRun<dim>*, 3> all() const { return {&inviscid, &viscous, &printed}; }
};

template <class Scheme>
app::TubeRun<dim> run_sod(const std::string& name, const SodScene& scene,
                          const typename Scheme::Terms& terms,
                          app::RunReport report = app::RunReport::live_and_final) {
  return app::run_shock_tube<Scheme>(
      scene.tube, scene.smoothing(), terms,
      {.t_end = scene.t_end, .courant = scene.courant, .label = name, .report = report});
}

/// The step itself prints the exact solution and the resolution, makes the three runs, and
/// writes each final state as a snapshot whose file name says which scheme made it.
SodRuns step1_sod_runs(const app::Chapter& chapter, const Parameters& par) {
  const SodScene& sod = par.sod;
  const sph::RiemannSolution exact(sod.tube.left, sod.tube.right, sod.tube.gamma);
  std::printf("Step 1: Sod's shock tube, rho 1 | 0.125, P 1 | 0.1, v = 0, gamma = %.1f, t = %.1f\n",
              sod.tube.gamma, sod.t_end);
  std::printf("%s\n", app::wrap("  exact: " + exact.describe()).c_str());
  std::printf("  1D, M4 kernel, h = N m/(4 rho) with N = %g (h = %g dx), left spacing 1/%d\n\n",
              sod.neighbours, sod.neighbours / 4, par.cells);
  SodRuns runs{run_sod<HernquistKatz<dim>>("no viscosity", sod, {}),
               run_sod<WithViscosity<dim>>(par.viscous_name(), sod, {{}, par.viscosity()}),
               run_sod<AsPrinted<dim>>("eq 4 as printed", sod, {})};
  const std::pair<const app::TubeRun<dim>*, const char*> stems[] = {
      {&runs.inviscid, "sod_no_viscosity"},
      {&runs.viscous, "sod_monaghan_gingold"},
      {&runs.printed, "sod_as_printed"}};
  for (const auto& [run, stem] : stems) {
    sph::write_snapshot<dim>(chapter.figure_path(sph::snapshot_path("", stem, 1)).string(),
                             run->particles, sod.t_end, sod.tube.gamma);
  }
  return runs;
}

/// \section ch03_errors Step 2: errors against an exact solution, and what is conserved
///
/// The first measure of a run is its distance from the exact solution: the \f$ L_1 \f$ norms
/// of \f$ \rho \f$, \f$ v_x \f$ and \f$ P \f$ over the particles in \f$ -0.5 \le x \le 0.5 \f$
/// (lib/sph/measures/norms.hpp).  They are particle averages,
/// \f[ L_1(\rho) = \frac1N \sum_{|x_i| \le 0.5} |\rho_i - \rho_{\rm exact}(x_i, t)| , \f]
/// so each region counts by the number of particles in it, which is to say by its mass.  The
/// reference is any gas whose exact solution we know: Sod's gas, or the equivalent gas of the
/// printed eq 4, whose pressure must be doubled before it is compared with the pressure the
/// run reports (the run's P is the printed P, twice the P' of the equivalent gas).  A
/// `Reference` carries that factor.

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

/// `sod_errors` hands sph::error_norms the three functions of position it compares with:
/// `exact(field)` makes a function that samples the reference at x and picks one member of
/// sph::GasState (a pointer to member), so one line serves density, velocity and pressure.
/// The window is sph::shock_tube_window(), the same for every run of the chapter.

struct SodErrors {
  double density = 0, velocity = 0, pressure = 0;
};

template <int D>
SodErrors sod_errors(const sph::Particles<D>& p, const Reference& reference, double t) {
  const auto window = sph::shock_tube_window();
  const auto exact = [&](double sph::GasState::*field) {
    return [&, field](const sph::Vec<D>& x) { return reference.at(x[0], t).*field; };
  };
  const auto vx = sph::component<D>(p.velocity, 0);
  const auto l1 = [&](const char* name, const std::vector<double>& values,
                      double sph::GasState::*field) {
    return sph::error_norms<D>(name, p.position, values, exact(field), window).L1;
  };
  return {l1("density", p.density, &sph::GasState::density),
          l1("velocity", vx, &sph::GasState::velocity),
          l1("pressure", p.pressure, &sph::GasState::pressure)};
}

/// Why \f$ L_1 \f$, and not the \f$ L_2 \f$ or maximum norms?  Near a discontinuity a smoothed
/// profile is wrong by an amount of order one over a width of a few h.  The maximum error is
/// therefore of order one at every resolution; the \f$ L_2 \f$ error, the square root of an
/// area \f$ \sim h \f$, falls like \f$ h^{1/2} \f$; only \f$ L_1 \f$, the area itself, falls like
/// h, at the first order that is the best a shock-capturing scheme can do.  \f$ L_1 \f$ is also
/// the norm the SPH literature quotes for shock tubes, so our numbers compare with theirs.
///
/// The step measures each run against Sod's gas, and the printed run also against its own
/// gas, and prints one table: steps, wall time, the three \f$ L_1 \f$ norms and the two
/// conservation checks, \f$ |\Delta E|/E \f$ and \f$ |\sum m\mathbf v| \f$ against its scale.
///
/// What to look for.  The momentum column should read \f$ 10^{-16} \f$ to \f$ 10^{-15} \f$ in
/// every row: that is round-off, and it says the pair forces are equal and opposite whatever
/// the scheme.  The energy column is the leapfrog's error, second order in the step, and it is
/// largest for the inviscid run, whose noisy post-shock gas has the largest accelerations.  In
/// the errors, the viscous run is an order of magnitude closer to Sod's solution than the
/// inviscid one (at the default resolution \f$ L_1(\rho) \f$ = 1.234e-03 against 2.299e-02, a
/// factor of nineteen); Step 3 shows where the difference comes from.  The printed run is far
/// from Sod's solution, but its last line, against the gas the analysis says it simulates,
/// should look like the inviscid run against Sod's: the same scheme, errors of the same kind.
/// It does: its \f$ L_1(\rho) \f$ falls from 5.824e-02 against Sod's gas to 1.640e-02 against
/// its own, the size of the inviscid run's 2.299e-02 against Sod's.

struct ErrorTable {
  SodErrors inviscid, viscous, printed;  // against Sod's gas
  SodErrors printed_own;                 // the printed run against its equivalent gas
};

ErrorTable step2_errors(const SodRuns& runs, const Parameters& par) {
  const double t = par.sod.t_end;
  const Reference sod_gas{runs.inviscid.exact, 1.0}, printed_gas = printed_equivalent(par.sod.tube);
  const ErrorTable e{sod_errors(runs.inviscid.particles, sod_gas, t),
                     sod_errors(runs.viscous.particles, sod_gas, t),
                     sod_errors(runs.printed.particles, sod_gas, t),
                     sod_errors(runs.printed.particles, printed_gas, t)};
  std::printf(
      "\nStep 2: L1 errors in -0.5 <= x <= 0.5 (N = %d particles) against Sod's exact "
      "solution\n",
      runs.inviscid.in_window);
  std::printf("  %-22s %6s  %8s  %-9s  %-9s  %-9s  %-7s  %-8s\n", "run", "steps", "wall [s]",
              "L1(rho)", "L1(v)", "L1(P)", "|dE|/E", "|sum mv|");
  const std::pair<const app::TubeRun<dim>*, const SodErrors*> rows[] = {
      {&runs.inviscid, &e.inviscid}, {&runs.viscous, &e.viscous}, {&runs.printed, &e.printed}};
  for (const auto& [run, err] : rows) {
    std::printf("  %-22s %6ld  %8.2f  %.3e  %.3e  %.3e  %.1e  %.1e\n", run->name.c_str(),
                run->steps, run->seconds, err->density, err->velocity, err->pressure,
                run->energy_change, run->momentum_drift);
  }
  std::printf("  %-22s %6s  %8s  %.3e  %.3e  %.3e\n", "  against gamma' = 1.2", "", "",
              e.printed_own.density, e.printed_own.velocity, e.printed_own.pressure);
  return e;
}

/// \section ch03_star Step 3: the star region -- p*, ringing and heat
///
/// Between the tail of the rarefaction and the shock lies the *star region* of constant
/// pressure \f$ p_* = 0.30313 \f$ and velocity \f$ u_* = 0.92745 \f$, cut in two by the contact
/// discontinuity.  We keep two kernel supports (\f$ 4h \f$) away from the waves that bound it,
/// with h the smoothing length of the post-shock gas, \f$ h = N m/(4\rho_{*R}) \f$, and
/// measure
///  - \f$ p_* \f$ as the **median** pressure of the star region (the median ignores the
///    pressure blip that SPH makes at the contact: there the density is smoothed over a few h
///    while the internal energy of each particle jumps, so \f$ P = (\gamma - 1)\rho u \f$
///    overshoots on one side -- a subject of its own, for a later chapter);
///  - the **ringing** as the RMS of \f$ v_x - u_* \f$ over the post-shock gas between the
///    contact and the shock, where the exact velocity is the constant \f$ u_* \f$: all of it
///    is noise;
///  - the **mean internal energy** of the same particles, to compare with the two values of
///    the energy section: the Rankine-Hugoniot \f$ u = 2.854 \f$ of a shock, and the
///    \f$ u = 2.704 \f$ of an adiabatic compression to the same density.
///
/// These numbers tell the story of the inviscid run better than the error norms.  A gas that
/// cannot make entropy reaches the post-shock density along its adiabat, with
/// \f$ u \approx 2.70 \f$; the shock's energy balance demands \f$ u = 2.85 \f$.  The
/// difference, \f$ \Delta u \approx 0.15 \f$ per unit mass, has to go somewhere, since the
/// equations conserve energy: it stays in the motion, as random velocities about the mean flow
/// with \f$ \tfrac12 \langle (v - u_*)^2 \rangle \approx \Delta u \f$.  That predicts a ringing
/// amplitude of \f$ \sqrt{2\Delta u} \approx 0.55 \f$ -- about 60 % of \f$ u_* \f$, independent
/// of the resolution, since nothing in the argument knows about \f$ \Delta x \f$.  The argument
/// is only as good as the discrete equations are adiabatic, and in the noise behind an
/// inviscid shock, where neighbours differ strongly, the two approximations noted above are no
/// longer small: they move heat between particles and can also create some.  With
/// \f$ h = \Delta x \f$ we find the post-shock gas's mean u at the adiabat's value (for the exact
/// post-shock density) and the energy budget nearly closed; with \f$ h = 1.2\Delta x \f$
/// (`--neighbours 4.8`) the post-shock gas ends up near the shock's u, yet still rings at over 40 %
/// of \f$ u_* \f$.  What does not depend on h is that nothing in the inviscid equations damps the
/// ringing.
///
/// In code, the margin is four smoothing lengths of the post-shock gas, computed from a
/// particle's mass and \f$ \rho_{*R} \f$ with the 1D rule \f$ h = N m/(4\rho) \f$; the
/// function therefore holds in 1D only, which a `static_assert` says.  The median is found with
/// std::nth_element, which puts the middle value in its place without sorting the rest.  A
/// window without particles -- a resolution too coarse for the margins -- stops the program
/// with a message instead of dividing by zero.

struct StarRegion {
  double p_star = 0;            // median pressure between rarefaction tail and shock
  double ringing = 0;           // RMS of v - u* between contact and shock
  double internal_energy = 0;   // mean u between contact and shock
  double lower = 0, upper = 0;  // the post-shock window
  int count = 0;                // particles in it
};

/// `StarRegion` keeps the window with the measurements, so that Step 5 can mark it in the
/// figure of the inviscid run.  Both samples keep the margin from the waves: the pressures are
/// taken from the rarefaction's tail to the shock, the velocities and energies only in the
/// shocked gas between the contact and the shock, where the exact state is a single constant.
template <int D>
StarRegion star_region(const app::TubeRun<D>& run, const SodScene& scene) {
  static_assert(D == 1, "the post-shock smoothing length below is the 1D rule");
  const auto& exact = run.exact;
  const double t = scene.t_end;
  const double margin =
      4.0 * scene.neighbours * run.particles.mass[0] / (4.0 * exact.star_density_right());
  StarRegion star;
  star.lower = exact.contact_position(t) + margin;
  star.upper = exact.shock_position(t) - margin;
  // Median pressure over the whole star region; RMS velocity error and mean u over its
  // shocked part.
  std::vector<double> pressures;
  double sum_square = 0, sum_u = 0;
  for (std::size_t i = 0; i < run.particles.size(); ++i) {
    const double x = run.particles.position[i][0];
    if (x > exact.rarefaction_tail_position(t) + margin && x < star.upper) {
      pressures.push_back(run.particles.pressure[i]);
    }
    if (x <= star.lower || x >= star.upper) continue;
    sum_square += std::pow(run.particles.velocity[i][0] - exact.star_velocity(), 2);
    sum_u += run.particles.internal_energy[i];
    ++star.count;
  }
  sph::require(star.count > 0,
               "star region: no particles between contact and shock "
               "(the resolution is too coarse)");
  std::nth_element(pressures.begin(), pressures.begin() + pressures.size() / 2, pressures.end());
  star.p_star = pressures[pressures.size() / 2];
  star.ringing = std::sqrt(sum_square / star.count);
  star.internal_energy = sum_u / star.count;
  return star;
}

/// The step measures the inviscid and the viscous run (the printed run has a different star
/// state, and Step 4 deals with it) and prints, for each, \f$ p_* \f$ and its error, the
/// ringing in absolute terms and as a fraction of \f$ u_* \f$, and the heat budget: the heat
/// missing against the shock's u, and the kinetic energy per unit mass of the ringing,
/// \f$ \tfrac12 \langle (v - u_*)^2 \rangle \f$.
///
/// What to look for.  Without viscosity the ringing is about half of \f$ u_* \f$ and the mean u of
/// the post-shock gas sits at the adiabat's value, not at the Hugoniot's; the two numbers of the
/// heat budget are close to each other, which is the energy argument above in figures.  At the
/// default resolution the ringing is 0.5094, 54.92 % of \f$ u_* \f$, near the predicted 0.55; the
/// mean u is 2.7058, against 2.7036 on the adiabat; and of the 0.1478 of heat missing per unit
/// mass, 0.1297 is the kinetic energy of the ringing.  With viscosity the ringing is four orders of
/// magnitude smaller, \f$ p_* \f$ is right to a fraction of a per cent, and u has reached the
/// Hugoniot value: the viscosity has turned the kinetic energy into heat, which is what a shock
/// does.  The two numbers of the inviscid heat budget need not agree exactly: what the ringing's
/// kinetic energy does not account for has been made into heat after all, by the approximations of
/// the discrete energy equation that the energy section described, and with \f$ h = \Delta x \f$
/// that share is small.  The window holds only some thirty particles at this resolution, so these
/// are estimates from a small sample; Step 7 looks at the same failure with the error norms over
/// the whole window.

struct StarTable {
  StarRegion inviscid, viscous;
  double u_shock = 0;    // the exact u behind the shock (Rankine-Hugoniot)
  double u_adiabat = 0;  // u after an adiabatic compression to the same density
};

/// The two reference values of u come from the exact solution and the initial state.  The
/// Hugoniot value is the exact u sampled in the middle of the post-shock window; the adiabatic
/// one carries the right state's u along \f$ u \propto \rho^{\gamma-1} \f$ (which holds
/// \f$ P/\rho^\gamma \f$ constant) up to the exact post-shock density \f$ \rho_{*R} \f$.
StarTable step3_star_region(const SodRuns& runs, const Parameters& par) {
  const SodScene& sod = par.sod;
  const sph::RiemannSolution& exact = runs.inviscid.exact;
  StarTable star{star_region(runs.inviscid, sod), star_region(runs.viscous, sod)};
  const double middle = 0.5 * (star.inviscid.lower + star.inviscid.upper);
  const double compression = exact.star_density_right() / sod.tube.right.density;
  star.u_shock = exact.internal_energy(middle, sod.t_end);
  star.u_adiabat = sph::internal_energy(sod.tube.right, sod.tube.gamma) *
                   std::pow(compression, sod.tube.gamma - 1);
  std::printf("\nStep 3: the star region, exact p* = %.5f, u* = %.5f\n", exact.star_pressure(),
              exact.star_velocity());
  std::printf("  post-shock window %.3f < x < %.3f\n", star.inviscid.lower, star.inviscid.upper);
  std::printf(
      "  post-shock u: %.4f behind a shock (Rankine-Hugoniot), %.4f after adiabatic "
      "compression\n",
      star.u_shock, star.u_adiabat);
  const std::pair<const app::TubeRun<dim>*, const StarRegion*> rows[] = {
      {&runs.inviscid, &star.inviscid}, {&runs.viscous, &star.viscous}};
  for (const auto& [run, s] : rows) {
    std::printf("  %-20s p* = %.4f (%+.2f %%), ringing = %.4f (%.2f %% of u*, %d particles)\n",
                run->name.c_str(), s->p_star, 100 * (s->p_star / exact.star_pressure() - 1),
                s->ringing, 100 * s->ringing / exact.star_velocity(), s->count);
    std::printf("  %-20s mean u = %.4f: heat missing %.4f, kinetic energy of the ringing %.4f\n",
                "", s->internal_energy, star.u_shock - s->internal_energy,
                0.5 * s->ringing * s->ringing);
  }
  return star;
}

/// \section ch03_fronts Step 4: where the waves are
///
/// The \f$ L_1 \f$ norm adds up two different faults: a wave smeared over a few h, and a wave
/// in the wrong place.  The first is what any SPH scheme does; the second means the scheme
/// solves the wrong equations -- which is what we suspect of the printed eq 4.  So we separate
/// them.  To see whether a scheme propagates the waves at the right speeds we locate two fronts in
/// the run and in each exact solution by the *same* rule: the **shock** is where the pressure,
/// scanned from the undisturbed gas at \f$ x = 0.5 \f$ inwards, first rises through the middle
/// of Sod's pressure jump, \f$ (P_R + p_*)/2 \f$; the **rarefaction head** is where the
/// velocity, scanned from \f$ x = -0.5 \f$, first rises through 0.05.  Between the two samples
/// that bracket the crossing we interpolate linearly.  Applied to the exact profile, sampled
/// every \f$ 5\cdot 10^{-5} \f$, the rule finds the front itself (or, in the rarefaction, the
/// point a little behind the head where v reaches 0.05); applied to the particles, it finds
/// the same point of the smoothed front, a fraction of h away.  Using one rule for both is
/// what makes the comparison fair: a smoothed front and a sharp one are compared at the same
/// level, not at their "edges", which a smoothed front does not have.
///
/// In code, the scan is app::first_crossing (lib/app/curve_reading.hpp): it walks the samples
/// in pairs from one end inwards and returns the first place where \f$ f - \text{level} \f$
/// changes sign, interpolated linearly between the two samples.  It skips pairs with equal
/// values, and returns NaN when f never reaches the level, so that a check comparing a missing
/// front fails instead of passing by accident.  `fronts` sorts the samples by x, splits them
/// into a velocity and a pressure profile, and applies the two rules; `fronts_of_run` samples
/// the particles in the window, and `fronts_of_exact` a reference at 20001 evenly spaced
/// points.  The two levels are chosen with the runs' errors in mind.  The shock level lies
/// half-way up a pressure jump of 0.2, five times the 0.02 by which the inviscid run misses
/// \f$ p_* \f$ (Step 3); the head level, 0.05, is about 5 % of \f$ u_* \f$ -- low enough to
/// sit near the head, yet well above the gas ahead of it, which is still at rest.

struct Fronts {
  double head = 0, shock = 0;
};

/// The fronts of a profile given as (x, v_x, P) samples in any order.
Fronts fronts(std::vector<std::array<double, 3>> samples, const sph::RiemannSolution& sod) {
  std::sort(samples.begin(), samples.end());
  std::vector<std::pair<double, double>> velocity, pressure;
  for (const auto& [x, v, P] : samples) {
    velocity.emplace_back(x, v);
    pressure.emplace_back(x, P);
  }
  const double shock_level = 0.5 * (sod.right_state().pressure + sod.star_pressure());
  return {app::first_crossing(velocity, 0.05, false),
          app::first_crossing(pressure, shock_level, true)};
}

template <int D>
Fronts fronts_of_run(const app::TubeRun<D>& run) {
  std::vector<std::array<double, 3>> samples;
  for (std::size_t i = 0; i < run.particles.size(); ++i) {
    const double x = run.particles.position[i][0];
    if (std::abs(x) <= 0.5) {
      samples.push_back({x, run.particles.velocity[i][0], run.particles.pressure[i]});
    }
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

/// The step applies the rule to Sod's exact solution, to the exact solution of the printed
/// scheme's equivalent gas (with its pressure doubled, as the run reports it, so that the
/// shock level means the same thing), and to the three runs.
///
/// What to look for.  The inviscid run's rarefaction head is within a few \f$ 10^{-4} \f$ of the
/// exact one -- the smooth part of the flow is right -- and its shock within about 0.01, a
/// couple of post-shock smoothing lengths: the waves travel at Sod's speeds even though the gas
/// behind the shock is wrong.  The printed run is a third slower than Sod's gas in both fronts,
/// and within a few thousandths of the *predicted* fronts of the \f$ \gamma' = 1.2 \f$ gas: the
/// misprint does not make the scheme unstable or noisy, it makes it simulate another gas, and
/// the analysis above says which.

struct FrontTable {
  Fronts sod_gas, printed_gas;        // the two exact solutions
  Fronts inviscid, viscous, printed;  // the runs
};

FrontTable step4_wave_fronts(const SodRuns& runs, const Parameters& par) {
  const SodScene& sod = par.sod;
  const sph::RiemannSolution& exact = runs.inviscid.exact;
  const FrontTable f{fronts_of_exact(Reference{exact, 1.0}, exact, sod.t_end),
                     fronts_of_exact(printed_equivalent(sod.tube), exact, sod.t_end),
                     fronts_of_run(runs.inviscid), fronts_of_run(runs.viscous),
                     fronts_of_run(runs.printed)};
  std::printf(
      "\nStep 4: wave fronts at t = %.1f: rarefaction head (v = 0.05) and shock "
      "(P = %.4f)\n",
      sod.t_end, 0.5 * (sod.tube.right.pressure + exact.star_pressure()));
  const std::pair<const char*, const Fronts*> rows[] = {
      {"exact, Sod's gas (gamma = 1.4)", &f.sod_gas},
      {"exact, equivalent gas of eq 4 as printed", &f.printed_gas},
      {runs.inviscid.name.c_str(), &f.inviscid},
      {runs.viscous.name.c_str(), &f.viscous},
      {runs.printed.name.c_str(), &f.printed}};
  for (const auto& [name, front] : rows) {
    std::printf("  %-42s head %8.4f   shock %7.4f\n", name, front->head, front->shock);
  }
  return f;
}

/// \section ch03_figures Step 5: the figures
///
/// Each run is drawn the way SPLASH draws a shock tube: \f$ \rho \f$, \f$ v_x \f$, \f$ P \f$ and
/// \f$ u \f$ against x, one dot per particle, the exact solution as a line
/// (lib/app/shock_tube_figure.hpp).  The stamp at the foot names the scheme, kernel,
/// neighbour number, particle number and run time, so a figure found on its own still says
/// what made it.  The printed scheme's figure also carries the prediction, drawn into the
/// returned figure's panels before it is saved.
///
/// `sod_figure` fills the stamp and hands the particles to app::shock_tube_figure, which also
/// draws the exact solution of the run's own tube.  app::add_exact_lines
/// (figure_lines.hpp, shown at the end of this step) draws another exact solution into the same
/// four panels, here the equivalent gas with the factor 2 its `Reference` carries.  Its pressure
/// is doubled, like the run's, but its internal energy is not: the printed scheme's
/// \f$ P = (\gamma - 1)\rho u \f$ and the equivalent gas's
/// \f$ P' = P/2 = (\gamma' - 1)\rho u \f$ describe the same u.

template <int D>
plot::Figure sod_figure(const app::TubeRun<D>& run, const SodScene& scene, const std::string& title,
                        const std::string& scheme, const std::string& exact_label = "exact") {
  const plot::Stamp stamp{.scheme = scheme,
                          .kernel = "M4",
                          .neighbours = scene.neighbours,
                          .particles = run.in_window,
                          .run_time = run.seconds,
                          .extra = "h = N m/(4\\rho), t = " + format("%g", scene.t_end)};
  return app::shock_tube_figure({app::make_profile<D>(run.particles, "SPH")}, run.exact,
                                scene.t_end, title, stamp, {.exact_label = exact_label});
}

/// The step draws three figures and prints their names.
///  - `sod_no_viscosity.png`: the inviscid run, with the post-shock window of Step 3 marked by
///    two dotted lines in the velocity panel.  Look first at the rarefaction
///    (\f$ -0.24 < x < 0 \f$), which the particles follow to the line in all four panels, and
///    then at everything to the right of the contact: the velocities scatter about \f$ u_* \f$
///    between the dotted lines, and panel (d) shows u lying below the exact line -- the heat
///    that Step 3 found missing.
///  - `sod_monaghan_gingold.png`: the viscous run.  The scatter is gone; what remains is the
///    smearing of the shock and the contact over a few h, and at the contact the small blip in
///    u and dip in \f$ \rho \f$ that SPH without a heat-conduction term always shows.
///  - `sod_as_printed.png`: the printed run against both exact solutions, Sod's in red and the
///    predicted \f$ \gamma' = 1.2 \f$ gas dashed in blue.  The particles follow the blue line.

void step5_figures(const app::Chapter& chapter, const SodRuns& runs, const StarTable& star,
                   const Parameters& par) {
  std::printf(
      "\nStep 5: the figures sod_no_viscosity.png, sod_monaghan_gingold.png and "
      "sod_as_printed.png\n");
  const SodScene& sod = par.sod;
  plot::Figure figure =
      sod_figure(runs.inviscid, sod, "Sod's shock tube without viscosity (Hernquist & Katz form)",
                 "SPH, Hernquist-Katz, no viscosity");
  for (double x : {star.inviscid.lower, star.inviscid.upper}) {
    figure.panel(1).vline(x, {.color = plot::grey, .style = plot::Dash::dotted, .width = 1.2});
  }
  figure.save_png(chapter.figure_path("sod_no_viscosity.png").string());

  sod_figure(
      runs.viscous, sod,
      "Sod's shock tube with Monaghan-Gingold viscosity (" + par.viscous_coefficients() + ")",
      "SPH, Hernquist-Katz, " + par.viscous_name())
      .save_png(chapter.figure_path("sod_monaghan_gingold.png").string());

  figure = sod_figure(runs.printed, sod,
                      "Selhammar's eq 4 as printed: Sod's exact solution (red) and the prediction "
                      "(blue)",
                      "SPH, bracket P_{ij}/\\rho_{ij}^2 (eq 4 as printed), no viscosity",
                      "exact, Sod (\\gamma = 1.4)");
  const Reference prediction = printed_equivalent(sod.tube);
  app::add_exact_lines(figure, prediction.solution, sod.t_end, prediction.pressure_factor,
                       "prediction: \\gamma' = 1.2, P' = P/2", plot::blue);
  figure.save_png(chapter.figure_path("sod_as_printed.png").string());
}

/// `figure_lines.hpp` holds two small functions that draw into a figure already made:
/// app::add_exact_lines, which drew the prediction's dashed lines just above, and
/// app::add_slope_guide, with which Step 7 lays a line of a given slope on its error figure.
///
/// \show_file figure_lines.hpp
///
/// \section ch03_streams Step 6: two colliding streams
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
/// Selhammar's rule, a fixed number of neighbours (here 5; on the initial lattice the 5th and
/// 6th neighbours lie on one shell, so \f$ 2h \f$ goes just outside it, half-way to the next:
/// \f$ h = 1.75\Delta x \f$, with 6 neighbours inside \f$ 2h \f$) -- the density of an
/// approaching pair stays finite, the barrier between them is finite, and a fast particle
/// simply goes through.  The streams **interpenetrate**, and the gas between the shocks is two
/// streams on top of each other with density 2, not a shocked gas at rest with density 4.
/// If instead h shrinks with the density (our rule for Sod), then in 1D a pair that approaches
/// raises its own density, shrinks its own h, and the barrier becomes infinite: the particles
/// cannot pass, and the streams **pile up** into a thin sheet compressed by the factor above.
/// The time step, proportional to h, collapses with it; we give that run a budget of steps
/// (`--pileup-steps`), and when it runs out the run stops where it is and says so.  The
/// viscous run of chapter 4 completes the picture: its \f$ \beta \f$ term converts the approach
/// into heat over a couple of smoothing lengths, which is what a shock does.
///
/// The exact density between the shocks follows from mass conservation across each shock.  A shock
/// moving outwards at speed s sweeps up gas arriving at \f$ v_0 \f$, so
/// \f$ \rho_0 (v_0 + s) = \rho_2 s \f$ and \f$ \rho_2/\rho_0 = 1 + v_0/s \f$: 4 for the
/// strong-shock speed \f$ s = 1/3 \f$, and 3.93 at Mach 10, where the gas in front is not quite
/// cold, the compression falls a little short of 4, and the shock runs a little faster,
/// \f$ s = 0.34 \f$.  In SPH the first particles to meet are compressed and heated by the viscosity
/// before any shock has formed, more than the shock heats the gas that follows; they end up hotter
/// and, at the same pressure, less dense.  This "wall heating" leaves a dip in the density at
/// \f$ x = 0 \f$, where the streams first met.
///
/// During each run we record the positions of every k-th particle at 200 output times: an
/// x-t diagram of particle paths.  The runner, app::run_colliding_streams
/// (lib/app/colliding_streams_run.hpp), is the shock-tube runner's cousin, with three
/// differences: it stops at every output time to record the paths, it has a step budget, and a
/// run that cannot go on is not an error here but a result -- it keeps what it has, and the
/// reason it stopped.  The tracked particles are every k-th particle of the right-moving stream,
/// counted from its front, each paired with its mirror image in the other stream, so that the
/// diagram is symmetric about \f$ x = 0 \f$.  `run_streams` adapts it to the scene of this
/// chapter.

template <class Scheme>
app::StreamsRun<dim> run_streams(const std::string& name, const StreamsScene& scene,
                                 const typename Scheme::Terms& terms,
                                 const sph::SmoothingLengthRule& smoothing, long step_budget) {
  return app::run_colliding_streams<Scheme>(name, scene.setup, smoothing, terms,
                                            {.t_end = scene.t_end,
                                             .outputs = scene.outputs,
                                             .paths = scene.paths,
                                             .max_steps = step_budget});
}

/// \subsection ch03_inversions Counting particles that have passed each other
///
/// sph::order_inversions (lib/sph/measures/penetration.hpp) sorts the particles by their initial x
/// and counts the pairs whose order has flipped.  It reports two counts, and the difference matters
/// here.  *Adjacent* inversions -- initially neighbouring particles now in reverse order -- catch
/// any local overturning, but two streams that pass through each other keep their own order: only
/// the one pair that met first is adjacent and inverted.  *All* inversions count every pair that
/// has crossed, and grow like the square of the overlap; with n particles per stream that have
/// passed each other there are about \f$ n^2/2 \f$ of them.  The deepest penetration, the furthest
/// any particle has gone past one that started ahead of it, is the third number: for streams that
/// never stop it is \f$ 2 v_0 t \f$.
///
/// The x-t diagram draws the paths of each run, the right-moving stream in blue and the left-moving
/// one in red, so that crossing paths are penetration.  The figure is drawn by
/// app::save_colliding_streams_figure (`colliding_streams_figure.hpp`, shown at the end of this
/// step): the three diagrams in panels (a) to (c), on the same axes, a run that stopped early
/// ending at a dotted line at the time it reached; and in (d) the final densities of the two runs
/// that reached the end, against the exact solution.  The pile-up run is left out of (d): it
/// stopped long before the time the panel shows, and its sheet, thousands of times denser than the
/// streams, lies far above the panel's scale.

/// The step makes three runs: inviscid with h from the neighbour number, inviscid with h from
/// the density (with its step budget), and viscous with h from the neighbour number.  For each
/// it prints the cost, the time reached, the highest density, and the three counts of
/// sph::order_inversions, with the deepest penetration in units of the initial spacing.  The
/// x-t diagrams and the final densities go into `colliding_streams.png`, the final states of
/// the two complete runs into snapshots.
///
/// The number of pairs in the header is \f$ N(N-1)/2 \f$ for the N particles of both streams,
/// the most that could ever be inverted; it puts the counts of the table in proportion.
///
/// What to look for.  In the first run the number of inverted pairs is large -- thousands --
/// while the adjacent count is 1, and the deepest penetration is about \f$ 2 v_0 t = 0.8 \f$,
/// as far as an unhindered particle travels: the front particles of each stream have not been
/// slowed at all (the pressure of the overlap even pushes them a few per cent faster).  Its
/// highest density is about 2, two streams superposed.  The second run has no
/// inversion, but it stops early with its step budget spent, a density in the thousands and a
/// last time step some \f$ 10^{-7} \f$: the adiabatic pile-up.  How far that collapse has
/// gone when the budget runs out depends on round-off, so those numbers may differ from one
/// build to the next; the picture does not.  The viscous run reaches the end without a single
/// inversion, its highest density about 4, near the exact 3.9.
///
/// In the figure, crossing blue and red paths are penetration.  In (a) they cross at x = 0 and
/// run on almost unbent.  In (b) they bend towards each other, bunch at x = 0 and end at the
/// dotted line where the run stopped.  In (c) each path runs straight until a shock reaches it
/// and then stands still: the kinks line up along two fronts moving outwards at 1/3, the
/// shocks themselves.  Panel (d) puts the final densities of (a) and (c) on the exact profile.

template <int D>
struct StreamRuns {
  app::StreamsRun<D> passing, pileup, stopped;
  double dx = 0;  // the initial spacing
};

StreamRuns<dim> step6_colliding_streams(const app::Chapter& chapter, const Parameters& par) {
  const StreamsScene& scene = par.streams;
  std::printf("\nStep 6: colliding streams, rho = 1, v = +-1, Mach %g, gamma = 5/3, t = %.2f\n",
              scene.setup.mach, scene.t_end);
  const auto neighbour_rule = sph::SmoothingLengthRule::neighbour_number(scene.neighbours);
  const long unlimited = 10'000'000;
  StreamRuns<dim> s{
      run_streams<HernquistKatz<dim>>(format("no viscosity, %g neighbours", scene.neighbours),
                                      scene, {}, neighbour_rule, unlimited),
      run_streams<HernquistKatz<dim>>("no viscosity, h from density", scene, {},
                                      sph::SmoothingLengthRule::from_density(4.0),
                                      par.pileup_steps),
      run_streams<WithViscosity<dim>>(
          format("%s, %g neighbours", par.viscous_name().c_str(), scene.neighbours), scene,
          {{}, par.viscosity()}, neighbour_rule, unlimited)};
  s.dx = scene.setup.length / s.passing.left_count;
  /// The table has one row per run.  A run that stopped early gets a second line with the reason
  /// the runner recorded and its last time step: for the pile-up run, the step budget spent and
  /// a step shrunk to almost nothing.
  std::printf(
      "  %d particles per stream, %zu pairs; deepest: how far a particle has passed one\n"
      "  that started ahead of it, in initial spacings\n",
      par.stream_cells, s.passing.inversions.pairs());
  std::printf("  %-33s %6s %8s %7s %9s %9s %8s %8s\n", "run", "steps", "wall [s]", "t", "rho_max",
              "inverted", "adjacent", "deepest");
  for (const auto* run : {&s.passing, &s.pileup, &s.stopped}) {
    const double rho_max =
        *std::max_element(run->particles.density.begin(), run->particles.density.end());
    std::printf("  %-33s %6ld %8.2f %7.4f %9.3g %9zu %8zu %8.1f\n", run->name.c_str(), run->steps,
                run->seconds, run->t_reached, rho_max, run->inversions.all,
                run->inversions.adjacent, run->inversions.deepest / s.dx);
    if (!run->stopped.empty()) {
      const std::string why =
          format("  %33s stopped: %s; last step %.2e", "", run->stopped.c_str(), run->last_dt);
      std::printf("%s\n", app::wrap(why, 100, 38).c_str());
    }
  }
  /// The two runs with a fixed neighbour number, which at the defaults both reach the end, leave
  /// snapshots of their final states.  All three runs go into the figure, and those two also
  /// into its density panel.
  const auto snapshot = [&chapter](const char* stem) {
    return chapter.figure_path(sph::snapshot_path("", stem, 1)).string();
  };
  sph::write_snapshot<dim>(snapshot("streams_no_viscosity"), s.passing.particles,
                           s.passing.t_reached, scene.setup.gamma);
  sph::write_snapshot<dim>(snapshot("streams_monaghan_gingold"), s.stopped.particles,
                           s.stopped.t_reached, scene.setup.gamma);
  app::save_colliding_streams_figure<dim>(
      {&s.passing, &s.pileup, &s.stopped}, {&s.passing, &s.stopped}, scene.setup,
      {.title = format("Two cold streams colliding at Mach %g (\\gamma = 5/3)", scene.setup.mach),
       .smoothing = format("N_{ngb} = %g in (a), (c); h = m/\\rho in (b)", scene.neighbours),
       .t_end = scene.t_end,
       .paths = scene.paths},
      chapter.figure_path("colliding_streams.png").string());
  return s;
}

/// `colliding_streams_figure.hpp` draws an x-t diagram from the paths and times that
/// app::run_colliding_streams recorded for a run; for panel (d) it builds the exact solution
/// from the set-up itself with sph::make_colliding_streams, so the step hands it only the runs,
/// the set-up and the labels.
///
/// \show_file colliding_streams_figure.hpp
///
/// \section ch03_error Step 7: error against run time
///
/// The last question of every chapter with a reference solution: how does the error fall as we pay
/// for more particles?  We run Sod's tube at left spacings \f$ \Delta x = 1/100 \f$ to
/// \f$ 1/3200 \f$ (`--levels` of them, doubling the resolution each time), without and with
/// viscosity, and hand each run to sph::ErrorVsTime (lib/sph/measures/convergence.hpp), which
/// prints the table, fits the order p in \f$ L_1 \propto \Delta x^p \f$ and the cost slope s in
/// \f$ L_1 \propto t_\mathrm{run}^s \f$.  For a shock tube p = 1 is the best one can hope for: the
/// shock is smeared over a few h, and \f$ h \propto \Delta x \f$.  In 1D the cost grows like
/// \f$ N^2 \f$ (N particles, and a time step \f$ \propto h \propto 1/N \f$), so first order in
/// \f$ \Delta x \f$ is \f$ s = -1/2 \f$.  The number of particles N recorded for each run is the
/// number in the window we measure.
///
/// We already know what to expect without viscosity.  Nothing damps the ringing, and its
/// amplitude is set by the energy budget of the shock, \f$ \sim\sqrt{2\Delta u} \f$, not by the
/// resolution; more particles only sample the same noise more finely, and the region it
/// fills, from the rarefaction's tail to the shock (sound waves carry it back across the
/// contact), does not shrink either.  So the inviscid
/// \f$ L_1 \f$ error should stay where it is however many particles we pay for.  With
/// viscosity, the shock is a smooth transition a few h wide, and the error should fall as
/// \f$ \Delta x^1 \f$.
///
/// In code, each level builds its own tube at the new spacing (the scene is passed by value and
/// changed in place), runs it with the live progress line only, measures it against Sod's gas
/// as Step 2 does, and adds one record to the study: the method, N, \f$ \Delta x \f$, the
/// wall time and the three errors.

template <class Scheme>
void sweep_sod(sph::ErrorVsTime& study, const std::string& method, SodScene scene,
               const typename Scheme::Terms& terms, const std::vector<int>& cells) {
  for (int n : cells) {
    scene.tube.left_spacing = 1.0 / n;
    const auto run = run_sod<Scheme>(method, scene, terms, app::RunReport::live);
    const SodErrors e = sod_errors(run.particles, Reference{run.exact, 1.0}, scene.t_end);
    study.add({method,
               run.in_window,
               scene.tube.left_spacing,
               run.seconds,
               {{"L1(rho)", e.density}, {"L1(v)", e.velocity}, {"L1(P)", e.pressure}}});
    std::printf("  %-20s dx = 1/%-5d N = %4d  %5ld steps  %6.2f s  L1(rho) = %.3e\n",
                method.c_str(), n, run.in_window, run.steps, run.seconds, e.density);
  }
}

/// The error figure of lib/app/error_figure.hpp, with a guide line \f$ \propto t^{-1/2} \f$ through
/// the finest viscous run (app::add_slope_guide of figure_lines.hpp, shown in Step 5) and the
/// legends moved to where the curves are not.  A curve parallel to the guide line converges at
/// first order; a flat curve does not converge.  We draw two panels, \f$ L_1(\rho) \f$ and
/// \f$ L_1(v) \f$, of the three quantities measured: the pressure error follows the density error
/// closely in every row of the table, and a third panel would repeat the first.
void save_error_figure(const sph::ErrorVsTime& study, const SodScene& scene, int finest,
                       const Parameters& par, const std::string& path) {
  app::ErrorFigureOptions options;
  options.title = "Sod's shock tube, t = 0.2: L_1 error against run time, no viscosity and AV (" +
                  par.viscous_coefficients() + ")";
  options.quantities = {"L1(rho)", "L1(v)"};
  options.width = 1700;
  options.height = 720;
  options.stamp =
      plot::format_stamp({.scheme = "SPH, Hernquist-Katz, without and with " + par.viscous_name(),
                          .kernel = "M4",
                          .neighbours = scene.neighbours,
                          .extra = format("dx = 1/100 ... 1/%d", finest)});
  plot::Figure figure = app::error_figure(study, options);
  for (int k = 0; k < 2; ++k) {
    app::add_slope_guide(figure.panel(k), study.curve(par.viscous_name(), options.quantities[k]),
                         -0.5, "\\propto t^{-1/2}");
    figure.panel(k).legend(plot::Corner::lower_left);
  }
  figure.save_png(path);
}

/// sph::ErrorVsTime fits both slopes by least squares on the logarithms, over all the levels
/// of a method: the order p from \f$ \ln L_1 \f$ against \f$ \ln \Delta x \f$, the cost slope s
/// from \f$ \ln L_1 \f$ against \f$ \ln t_{\rm run} \f$.  The order depends only on the errors and
/// is the same on every machine; the cost slope depends on the wall times, and so on the
/// machine and its load, most of all for the short runs at the coarse end, which take
/// milliseconds.
///
/// The step prints one line per run as the sweep goes, then the study's table with the fitted
/// orders and cost slopes, and draws `sod_error_vs_time.png`.
///
/// What to look for.  In the viscous rows \f$ L_1(\rho) \f$ halves with every doubling of the
/// resolution and the step count doubles with it; the fitted order is close to 1 and the cost
/// slope close to \f$ -1/2 \f$.  In the inviscid rows \f$ L_1(v) \f$ does not move, and
/// \f$ L_1(\rho) \f$ even grows a little: the fitted orders are near zero or negative.  Each
/// doubling costs four times the wall time and buys nothing.  (The wall times, and so the cost
/// slopes, vary from machine to machine and from run to run; the errors do not.)

sph::ErrorVsTime step7_error_against_run_time(const app::Chapter& chapter, const Parameters& par) {
  std::printf("\nStep 7: error against run time, Sod's tube at t = %.1f\n", par.sod.t_end);
  const std::vector<int> cells = sph::geometric_series(100, 2, par.levels);
  sph::ErrorVsTime study(
      "Sod's shock tube at t = 0.2: L1 errors in -0.5 <= x <= 0.5, "
      "N = particles there");
  sweep_sod<HernquistKatz<dim>>(study, "no viscosity", par.sod, {}, cells);
  sweep_sod<WithViscosity<dim>>(study, par.viscous_name(), par.sod, {{}, par.viscosity()}, cells);
  std::printf("\n%s", study.table().c_str());
  save_error_figure(study, par.sod, cells.back(), par,
                    chapter.figure_path("sod_error_vs_time.png").string());
  return study;
}

/// \section ch03_checks The checks
///
/// The chapter's claims, each tested on the numbers this run has just measured; a claim
/// that fails prints what was found and what was expected, and makes the program exit
/// non-zero.  In order:
///  1. the pair forces conserve momentum to round-off, and the leapfrog energy to
///     \f$ 2\cdot 10^{-3} \f$, in all three runs of Sod's tube (Step 2);
///  2. without viscosity the waves still travel at Sod's speeds: the rarefaction head
///     within 0.005, the shock within 0.02, a few post-shock smoothing lengths (Step 4);
///  3. ... but the post-shock velocity rings, with an RMS above 10 % of \f$ u_* \f$ and ten
///     times that of the viscous run, and (with \f$ h = \Delta x \f$; see Step 3 for
///     \f$ 1.2\Delta x \f$) the post-shock gas lies nearer its adiabat than the Hugoniot
///     value of u (Step 3);
///  4. with viscosity \f$ p_* \f$ and the post-shock u are right to 1 %, and
///     \f$ L_1(\rho) \f$ is at least four times smaller (Steps 2 and 3);
///  5. eq 4 as printed moves both fronts more than 20 % too slowly, follows the predicted
///     \f$ \gamma' = 1.2 \f$ gas to within 0.01 (head) and 0.02 (shock), and is more than
///     twice as close to it as to Sod's gas in \f$ L_1(\rho) \f$ (Steps 2 and 4);
///  6. inviscid streams with a fixed neighbour number pass through each other (inversions,
///     and particles more than 10 \f$ \Delta x \f$ past one that started ahead); with h from
///     the density they do not; with viscosity the inversions are fewer than 1 % of the
///     inviscid ones (Step 6);
///  7. without viscosity \f$ L_1(\rho) \f$ does not converge (fitted order below 0.3); with
///     it, it converges at nearly first order (above 0.7) (Step 7).
///
/// The thresholds are loose enough to hold at the `--quick` resolution too, and tight enough
/// that each fails when the physics it stands for is broken: a sign error in the energy
/// equation breaks 1 and 3, a wrong bracket 5, a viscosity that misses approaching pairs 6.
/// Where they come from:
///  - \f$ 10^{-12} \f$ for momentum: round-off leaves \f$ 10^{-16} \f$ to \f$ 10^{-15} \f$, and a
///    force that is not equal and opposite would leave orders of magnitude more;
///  - \f$ 2\cdot 10^{-3} \f$ for energy is above the inviscid run's \f$ 1.4\cdot 10^{-3} \f$, the
///    largest of the three, and far below what an integrator of the wrong order would lose;
///  - 0.005 for the head is ten times the distance at which the run finds it at the default
///    resolution; 0.02 for the shock is four post-shock smoothing lengths there (two at the
///    `--quick` one), where the inviscid shock lags by about two;
///  - 10 % of \f$ u_* \f$ for the ringing is a fifth of what the inviscid run shows, and a
///    factor ten between the two runs, where the measurement gives thousands, leaves no doubt;
///  - 20 % for the printed fronts is two thirds of the third by which they are slow, and the
///    0.01 and 0.02 allowed from the predicted fronts are ten times the printed run's head
///    offset (0.0010) and twice the inviscid shock's lag (0.0088);
///  - for the streams, ten initial spacings of penetration, nearly six smoothing lengths, is far
///    more than the shuffling within a kernel that a shock may cause; passing streams reach 160;
///  - the orders 0.3 and 0.7 split the fitted orders, near zero and near one, with room on
///    both sides for the scatter of a fit over three `--quick` levels.
/// Finally the key numbers go into `summary.txt` in the output directory, where the figures
/// runner collects them for its table of all chapters.

struct Findings {
  const SodRuns& sod;
  const ErrorTable& errors;
  const StarTable& star;
  const FrontTable& fronts;
  const StreamRuns<dim>& streams;
  const sph::ErrorVsTime& study;
};

/// `Findings` holds references to what the steps returned, so `check_claims` reads the very
/// numbers the steps printed and measures nothing itself.  Claim 1 comes first, for each of the
/// three runs of Sod's tube.
void check_claims(app::Chapter& chapter, const Findings& f) {
  std::printf("\n");
  for (const auto* run : f.sod.all()) {
    chapter.check(run->momentum_drift < 1e-12,
                  format("%s: momentum %.2e of its scale, not round-off", run->name.c_str(),
                         run->momentum_drift));
    chapter.check(run->energy_change < 2e-3, format("%s: energy changed by %.2e (> 2e-3)",
                                                    run->name.c_str(), run->energy_change));
  }
  /// Claims 2 to 4 set the inviscid and the viscous run against Sod's exact solution and
  /// against each other: the fronts of Step 4, the post-shock gas of Step 3, and the density
  /// errors of Step 2.
  const Fronts &sod = f.fronts.sod_gas, &inviscid = f.fronts.inviscid, &printed = f.fronts.printed;
  const StarRegion &star = f.star.inviscid, &viscous = f.star.viscous;
  const sph::RiemannSolution& exact = f.sod.inviscid.exact;
  chapter.check(
      std::abs(inviscid.head - sod.head) < 0.005 && std::abs(inviscid.shock - sod.shock) < 0.02,
      format("inviscid waves: head %.4f, shock %.4f; Sod's %.4f, %.4f", inviscid.head,
             inviscid.shock, sod.head, sod.shock));
  chapter.check(std::abs(star.internal_energy - f.star.u_adiabat) <
                    std::abs(star.internal_energy - f.star.u_shock),
                format("inviscid post-shock u = %.4f is not nearer the adiabat %.4f than the "
                       "shock's %.4f",
                       star.internal_energy, f.star.u_adiabat, f.star.u_shock));
  chapter.check(star.ringing > 0.1 * exact.star_velocity() && star.ringing > 10 * viscous.ringing,
                format("inviscid ringing %.4f should exceed 10 %% of u* and 10x the viscous %.4f",
                       star.ringing, viscous.ringing));
  chapter.check(
      std::abs(viscous.p_star / exact.star_pressure() - 1) < 0.01 &&
          std::abs(viscous.internal_energy / f.star.u_shock - 1) < 0.01,
      format("viscous p* = %.4f and post-shock u = %.4f should be within 1 %% of %.5f "
             "and %.4f",
             viscous.p_star, viscous.internal_energy, exact.star_pressure(), f.star.u_shock));
  chapter.check(f.errors.viscous.density < 0.25 * f.errors.inviscid.density,
                format("viscous L1(rho) = %.3e is not 4x below the inviscid %.3e",
                       f.errors.viscous.density, f.errors.inviscid.density));
  /// Claim 5 asks two things of the printed eq 4: that it is wrong for Sod's gas, and that it
  /// is right for the gas the analysis says it simulates.
  chapter.check(std::abs(printed.shock - sod.shock) > 0.2 * sod.shock &&
                    std::abs(printed.head - sod.head) > 0.2 * std::abs(sod.head),
                format("eq 4 as printed: head %.4f, shock %.4f are not 20 %% slow", printed.head,
                       printed.shock));
  chapter.check(std::abs(printed.head - f.fronts.printed_gas.head) < 0.01 &&
                    std::abs(printed.shock - f.fronts.printed_gas.shock) < 0.02,
                format("eq 4 as printed: head %.4f, shock %.4f; predicted %.4f, %.4f", printed.head,
                       printed.shock, f.fronts.printed_gas.head, f.fronts.printed_gas.shock));
  chapter.check(f.errors.printed_own.density < 0.5 * f.errors.printed.density,
                format("eq 4 as printed: L1(rho) %.3e against the prediction, %.3e against Sod",
                       f.errors.printed_own.density, f.errors.printed.density));
  /// Claims 6 and 7 read the inversion counts of the three stream runs of Step 6 and the orders
  /// that Step 7 fitted to its sweep.
  const StreamRuns<dim>& s = f.streams;
  chapter.check(
      s.passing.inversions.all > 0 && s.passing.inversions.deepest > 10 * s.dx,
      "inviscid streams should pass through each other: " + s.passing.inversions.summary());
  chapter.check(s.pileup.inversions.all == 0,
                "streams with h from density should not pass: " + s.pileup.inversions.summary());
  chapter.check(s.stopped.inversions.all * 100 <= s.passing.inversions.all,
                "viscous streams: more than 1 % of the inviscid inversions: " +
                    s.stopped.inversions.summary());
  const double order_inviscid = f.study.order("no viscosity", "L1(rho)");
  const double order_viscous = f.study.order(f.sod.viscous.name, "L1(rho)");
  chapter.check(order_inviscid < 0.3, format("inviscid L1(rho) converges at order %.2f "
                                             "(expected < 0.3)",
                                             order_inviscid));
  chapter.check(order_viscous > 0.7,
                format("viscous L1(rho) converges at order %.2f (expected > 0.7)", order_viscous));

  /// Last come the summary lines for the table of all chapters: the density errors of Step 2,
  /// the ringing of Step 3 and the inversions of Step 6.
  chapter.summary("error", format("L1(rho) = %.4f (no AV), %.5f (AV), %.4f (eq 4 as printed), "
                                  "N = %d",
                                  f.errors.inviscid.density, f.errors.viscous.density,
                                  f.errors.printed.density, f.sod.inviscid.in_window));
  chapter.summary("ringing", format("%.4f (no AV), %.4f (AV)", star.ringing, viscous.ringing));
  chapter.summary("inversions", format("%zu (no AV), %zu (AV)", s.passing.inversions.all,
                                       s.stopped.inversions.all));
}

}  // namespace

/// \section ch03_main The main program
///
/// `main` is the table of contents: it reads the options, runs the seven steps in order -- each
/// later step measures the runs of Step 1, so they are passed along -- and checks the claims.  Run
/// as `build/chapters/ch03_equations_of_motion --output DIR`, the program writes the figures, the
/// SPLASH snapshots and `summary.txt` into DIR (without `--output`, into
/// `figures/03-equations-of-motion` of the source tree, where the pages of this book find them),
/// and its report on standard output; at the default resolution it takes some fifteen seconds on
/// two cores, most of them in the sweep of Step 7 and the pile-up run of Step 6.  app::run_main
/// turns anything that goes wrong (a bad option value, a run that cannot go on) into a message on
/// standard error and a non-zero exit status.

int main(int argc, char** argv) {
  return app::run_main([&] {
    app::Chapter chapter("03-equations-of-motion", "Chapter 3: the equations of motion", argc,
                         argv);
    Parameters par;
    declare_parameters(chapter, par);
    if (int rc = chapter.parse(); rc >= 0) return rc;
    set_resolution(par);

    const SodRuns sod = step1_sod_runs(chapter, par);
    const ErrorTable errors = step2_errors(sod, par);
    const StarTable star = step3_star_region(sod, par);
    const FrontTable fronts = step4_wave_fronts(sod, par);
    step5_figures(chapter, sod, star, par);
    const StreamRuns<dim> streams = step6_colliding_streams(chapter, par);
    const sph::ErrorVsTime study = step7_error_against_run_time(chapter, par);

    check_claims(chapter, {sod, errors, star, fronts, streams, study});
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
/// costs and what it buys.  It starts from the viscous run of this chapter's Step 1, and the
/// first thing it shows is that, run by the same runner, it gives the same numbers to the last
/// digit; then it asks why \f$ h = \Delta x \f$, what happens in two and three dimensions, and
/// which strength of the viscosity buys the most accuracy per second.
