/// \page ch02 Chapter 2: Neighbours, density and the smoothing length
/// \builds_on ch01
///
/// \section ch02_intro What this chapter adds
///
/// Chapter 1 looked at one kernel in isolation.  Now we put kernels on particles and add them
/// up.  The density of particle i is the first sum every SPH step computes,
/// \f[ \rho_i = \sum_j m_j\, W(r_{ij}, h_i) \qquad\text{(gather; Watkins et al. 1996 eq A1)}, \f]
/// \f[ \rho_i = \sum_j \bar m_{ij}\, W(r_{ij}, \bar h_{ij}), \quad
///     \bar m_{ij} = \tfrac12(m_i + m_j),\ \bar h_{ij} = \tfrac12(h_i + h_j)
///     \qquad\text{(pair-averaged; Selhammar 1997 eqs 1, 5)}, \f]
/// where the sum includes the particle itself (the *self term* \f$ m_i W(0, h_i) \f$) unless we
/// say otherwise.  With one h and one mass for all particles, as in this chapter, the two forms
/// are the same number.  (Our reading notes on these equations: \ref papers_watkins_eqA1
/// "Watkins eq A1", \ref papers_selhammar_eq1 "Selhammar eqs 1-2" and
/// \ref papers_selhammar_eq5 "eq 5".)
///
/// Three pieces of machinery make the sum affordable and well defined, and they are the new
/// library code of this chapter:
///  - the **cell grid** (`lib/sph/neighbours/cell_grid.hpp`) sorts the particles into cubes
///    about half a kernel radius wide, so that the candidates of a particle are the few cells
///    around it, with periodic images handled by shifting whole cells;
///  - the **neighbour search** (`lib/sph/neighbours.hpp`) chooses each h by a rule and builds a
///    symmetric list of pairs closer than \f$ 2\max(h_i, h_j) \f$, shared by every later pass;
///    the list does not depend on the number of threads, so neither does anything computed
///    from it;
///  - the **initial conditions** (`lib/sph/setups/initial_conditions.hpp`,
///    `lib/sph/setups/relax.hpp`) place particles on lattices, at random, or in a *settled*
///    glass, and can calibrate the masses so that the SPH density is exactly what we intend.
///
/// We use them to reproduce the density panels of Watkins et al. (1996) Figs 1a and 3a, and
/// then ask a question the papers do not: how large is the density error of a lattice or a
/// glass, what does it depend on, and what does it cost to reduce it?  The program is a
/// sequence of seven steps, each a function below with its own heading; `main` at the end calls
/// them in order:
///  1. what h means in Watkins et al., and its value for their static tests;
///  2. a random set of particles (their Fig. 3a), against the Poisson theory of its scatter;
///  3. the same set settled to a uniform density (their Fig. 1a);
///  4. the density of a lattice, and why Poisson summation says it cannot be exact;
///  5. masses calibrated so that an initial condition has the density we intend;
///  6. the three rules for the smoothing length on the settled and the random set;
///  7. the density error of lattices and glasses against the run time of the density step.
///
/// Everything later rests on this chapter: each step of every later chapter starts with the
/// neighbour search and the density sum built here, and the initial conditions of every scene
/// -- lattices, glasses, calibrated masses -- come from Steps 3 and 5.

#include "app/chapter.hpp"
#include "density_figures.hpp"
#include "density_timing.hpp"
#include "uniform_set_measures.hpp"
#include "sample_statistics.hpp"
#include "app/stopwatch.hpp"
#include "app/text.hpp"
#include "plot/figure.hpp"
#include "sph/density.hpp"
#include "sph/measures/convergence.hpp"
#include "sph/neighbours.hpp"
#include "sph/setups/initial_conditions.hpp"
#include "sph/setups/relax.hpp"
#include "sph/setups/watkins_static.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace {

using sph::Vec;

/// The parameters of the static tests, set from the command line in `main`.
struct Setup {
  int particles = 5000;    // Watkins: 5000
  double neighbours = 60;  // Watkins: 60 in 3D
  int draws = 20;          // random sets drawn in Step 2
  bool quick = false;
};

/// \section ch02_h Step 1: what h means in Watkins et al.
///
/// Watkins et al. give all particles of their static tests "a uniform, constant h based on the
/// density set to give them on average … 60 neighbours for the 3D case", and Appendix A says
/// how: the mass inside the kernel's full radius \f$ 2h \f$ is \f$ N_{\rm kernel} m \f$,
/// \f[ m N_{\rm kernel} = \tfrac43 \pi (2h)^3 \rho \quad\Longrightarrow\quad
///     h = \left(\frac{3 m N_{\rm kernel}}{32 \pi \rho}\right)^{1/3}
///     \qquad\text{(eqs A5-A6)}. \f]
/// (\ref papers_watkins_eqA5 "our reading of eqs A5-A7").
/// So their h is the same as ours and Selhammar's -- half the support radius -- and
/// \f$ N_{\rm kernel} \f$ is the *expected* number of particles within \f$ 2h \f$.  For 5000
/// particles of mass \f$ 1/5000 \f$ in the unit box and \f$ N_{\rm kernel} = 60 \f$ this gives
/// \f$ h = 0.0710 \f$, a kernel radius of 0.142, 2.4 mean spacings.
/// `sph::setups::watkins_smoothing_length` (lib/sph/setups/watkins_static.hpp) is eq A6 in D
/// dimensions (eq A7 in 2D), \f$ h = \frac12 (N m / V_D \rho)^{1/D} \f$ with \f$ V_D \f$ the
/// volume of the unit ball.
///
/// One consequence is worth writing down, because it holds at every particle number.  With the
/// mean spacing \f$ \Delta x \f$ defined by \f$ m = \rho\, \Delta x^3 \f$, eq A5 reads
/// \f$ \frac43\pi (2h)^3 = N_{\rm kernel}\, \Delta x^3 \f$, so
/// \f[ \frac{2h}{\Delta x} = \left(\frac{3 N_{\rm kernel}}{4\pi}\right)^{1/3}, \f]
/// 2.43 for 60 neighbours whatever N is.  How far the kernel reaches, counted in particles, is
/// fixed by the neighbour number alone: more particles make h smaller, not the kernel fuller.
/// Half that ratio is the \f$ \eta = h/\Delta x \f$ with which Step 4 describes lattices, 1.214
/// for 60 neighbours; it returns as the \f$ \eta \f$ of the lattice that Step 5 calibrates.
///
/// <b>What to look for.</b>  The one line of output: \f$ h = 0.0710 \f$ for 5000 particles and
/// 60 neighbours, a kernel radius \f$ 2h \f$ of 2.4 mean spacings.  Keep that picture: a kernel
/// reaches two to three particles in every direction, no further.  (The step prints the kernel
/// radius in mean spacings as \f$ 2h/m^{1/3} \f$: at density one a particle's volume is its
/// mass, and the mean spacing is the side of that volume.)

///
/// Every set in this chapter fills the periodic unit box with equal masses that make the mean
/// density one, and starts with Watkins' constant h (`sph::setups::unit_box_particles`, which
/// chapter 7 uses for the same sets).

using sph::setups::unit_box;

/// The density step itself is two library calls -- the neighbour search with the fixed h, then
/// the sum -- which `app::timed_density_step` (`density_timing.hpp`, shown in Step 2) makes and
/// times. Steps 2 and 7 use it; Steps 4 to 6 write the two calls out, with their own box or rule.

void step1_smoothing_length(const Setup& s) {
  const double mass = 1.0 / s.particles,
               h = sph::setups::watkins_smoothing_length<3>(mass, s.neighbours, 1.0);
  std::printf(
      "Step 1: Watkins' constant h (eq A6): N = %d, m = %.3e, N_kernel = %g\n"
      "  -> h = %.5f, 2h = %.4f = %.2f mean spacings\n\n",
      s.particles, mass, s.neighbours, h, 2 * h, 2 * h / std::cbrt(mass));
}

/// \section ch02_random Step 2: a random distribution (Watkins Fig. 3a)
///
/// 5000 particles placed independently and uniformly in the box -- a Poisson set.  Watkins et
/// al. leave out the self term here, following Whitworth et al. (1995) and Wood (1981), and
/// the reason is worth a moment.  In a random set the other particles do not know where
/// particle i is: each of the \f$ N - 1 \f$ others is uniform in the box, so
/// \f[ \mathrm E[\rho_i] = (N-1)\, m \int W\, dV = \frac{N-1}{N} \approx 1 \f]
/// *without* the self term.  Adding \f$ m W(0, h) = m/(\pi h^3) = 0.18 \f$ would bias every
/// density by 18 %.  (In a settled or lattice distribution the opposite holds: the others keep
/// their distance, leaving a hole around i that the self term fills.)  The scatter follows from
/// the same independence: the density is a sum of \f$ N-1 \f$ independent terms, so
/// \f[ \sigma_\rho^2 = (N-1)\, m^2 \left(\int W^2 dV - 1\right) \approx m \int W^2\, dV
///     = \frac{4 m}{\pi h^3} \int_0^2 q^2 w^2\, dq, \f]
/// about \f$ 0.26^2 \f$ for 60 neighbours: a random set is a poor fluid, with density errors of
/// a quarter.  Because \f$ m/h^3 \propto 1/N_{\rm kernel} \f$, the scatter falls only as
/// \f$ N_{\rm kernel}^{-1/2} \f$.
///
/// The integral is a plain number: for the M4, \f$ \int_0^2 q^2 w^2\, dq = \frac{491}{5040} \f$,
/// and eq A6 gives \f$ m/h^3 = 32\pi / (3 N_{\rm kernel}) \f$, so
/// \f[ \sigma_\rho \approx \left(\frac{128}{3 N_{\rm kernel}} \cdot \frac{491}{5040}\right)^{1/2}
///     \approx \frac{2.04}{\sqrt{N_{\rm kernel}}} , \f]
/// 0.263 at 60 neighbours, 0.372 at 30 and 0.186 at 120.  The program keeps the exact form,
/// \f$ (N-1)\, m^2 (\int W^2 dV - 1) \f$, whose correction for a finite N is small, and
/// integrates \f$ W^2 \f$ by the midpoint rule (`random_scatter_theory` below).
///
/// One random set is one draw.  To judge the paper's numbers we draw several sets and
/// report the spread of their mean and \f$ \sigma_\rho \f$.  Each draw has its own seed
/// (1, 2, ...), so the sets are independent and every run draws the same ones.  Over the draws
/// we take the mean and the sample standard deviation (`app::sample_statistics`, with the
/// \f$ n - 1 \f$ of an unbiased variance), and the two answer different questions.  The
/// spread is how far a *single* draw scatters -- the yardstick for the paper, which drew one
/// set -- so the paper's distance from our averages is quoted in units of it.  The average
/// itself is known much better, to the standard error \f$ \text{spread}/\sqrt{n} \f$, and that
/// is what the check on the mean density uses.
///
/// The first draw is measured a second time with the self term included, and the table prints
/// the self term \f$ m W(0, h) \f$ beside the resulting mean, so that the 18 % of the argument
/// above can be read off directly.
///
/// <b>What to look for.</b>  The average over the draws against the Poisson theory: they should
/// agree to well within the spread between draws (they do, to 0.0006 in \f$ \sigma_\rho \f$).
/// Then the paper's numbers against one draw: Watkins' 1.013 and 0.281 lie about two standard
/// deviations of a single draw from our averages -- plausible for the one set they drew, though
/// their mean is a little high.  And the line with the self term: every density 18 % too high.

///
/// The Poisson scatter of the density without self term,
/// \f$ \sqrt{(N-1) m^2 (\int W^2 dV - 1)} \f$, with \f$ \int W^2 dV \f$ by the midpoint rule over
/// the kernel radius.
double random_scatter_theory(int n, double h) {
  using K = sph::Kernel<3>;
  const int steps = 20000;
  double integral = 0;
  for (int k = 0; k < steps; ++k) {
    const double r = (k + 0.5) * 2.0 * h / steps;
    integral += 4.0 * std::numbers::pi * r * r * K::value(r, h) * K::value(r, h) * 2.0 * h / steps;
  }
  const double m = 1.0 / n;
  return std::sqrt((n - 1) * m * m * (integral - 1.0));
}

/// Every draw runs its density step through `app::timed_density_step`, the first function of
/// density_timing.hpp, shown here at its first call (Step 2 has no use for the time it
/// returns).  The rest of the file serves Step 7's cost study -- a guard that holds OpenMP to
/// one thread, the record of the runs and of what their glasses cost to build, the timing of
/// one set as the best of three runs, and the sweep over lattices and glasses -- and Step 7
/// comes back to it.
///
/// \show_file density_timing.hpp
///
/// Each draw adds one number to each of two columns, its mean density and its
/// \f$ \sigma_\rho \f$; the file sample_statistics.hpp turns a column into an average and a
/// spread.
///
/// \show_file sample_statistics.hpp

/// The step draws the sets, prints the paper's numbers, one draw, the average and spread over
/// the draws, and the theory, and returns the first draw (which Step 3 settles).  It checks
/// that the average mean density is \f$ (N-1)/N \f$ within four standard errors of the average,
/// and that the average \f$ \sigma_\rho \f$ is within 10 % of the theory -- loose enough for four
/// draws in `--quick` mode, tight enough to catch a wrong self term (18 %) or a wrong h.
/// The tolerance on the mean is four standard errors plus an absolute margin of
/// \f$ 10^{-3} \f$: four draws may by chance agree closely with one another, and a spread that
/// came out small would then make the check fail on a difference no larger than that margin.

struct RandomSets {
  sph::Particles<3> first;
  double first_mean = 0, first_sigma = 0;
};

RandomSets step2_random(app::Chapter& chapter, const Setup& s) {
  std::vector<double> means, sigmas;
  RandomSets result;
  double mean_with_self = 0;
  for (int draw = 0; draw < s.draws; ++draw) {
    auto p = sph::setups::watkins_random_set<3>(s.particles, s.neighbours, 1 + draw);
    app::timed_density_step(p, unit_box<3>(), sph::DensityForm::watkins(false));
    const auto scatter = sph::density_scatter(p.density);
    means.push_back(scatter.mean);
    sigmas.push_back(scatter.sigma);
    if (draw > 0) continue;
    result = {p, scatter.mean, scatter.sigma};
    app::timed_density_step(p, unit_box<3>(), sph::DensityForm::watkins(true));
    mean_with_self = sph::density_scatter(p.density).mean;
  }
  /// The table sets the averages and spreads beside the paper and the theory.  The theory needs
  /// only N and h, and h is the same in every draw: eq A6 sets it from N and the neighbour
  /// number alone, so the first draw's h stands for all.
  const app::SampleStatistics mean_stats = app::sample_statistics(means),
                              sigma_stats = app::sample_statistics(sigmas);
  const double h = result.first.smoothing_length[0], mass = result.first.mass[0];
  const double expected_mean = (s.particles - 1.0) / s.particles,
               sigma_theory = random_scatter_theory(s.particles, h);
  std::printf("Step 2: random distribution, constant h, self term excluded (Watkins Fig. 3a)\n");
  std::printf("  %-38s %10s %10s\n", "", "mean rho", "sigma_rho");
  std::printf("  %-38s %10.3f %10.3f\n", "Watkins et al. (1996)", 1.013, 0.281);
  std::printf("  %-38s %10.4f %10.4f\n", "this run, first draw", means[0], sigmas[0]);
  std::printf("  %-38s %10.4f %10.4f\n",
              ("this run, " + std::to_string(s.draws) + " draws: average").c_str(), mean_stats.mean,
              sigma_stats.mean);
  std::printf("  %-38s %10.4f %10.4f\n", "                  spread between draws",
              mean_stats.spread, sigma_stats.spread);
  std::printf("  %-38s %10.4f %10.4f\n", "Poisson theory", expected_mean, sigma_theory);
  std::printf("  first draw with the self term: mean %.4f (the self term m W(0,h) = %.4f)\n",
              mean_with_self, mass * sph::Kernel<3>::value(0, h));
  std::printf(
      "  the paper's mean lies %.1f, its sigma %.1f standard deviations of a single draw from our "
      "averages\n\n",
      (1.013 - mean_stats.mean) / mean_stats.spread,
      (0.281 - sigma_stats.mean) / sigma_stats.spread);
  chapter.check(
      std::abs(mean_stats.mean - expected_mean) < 4 * mean_stats.spread / std::sqrt(s.draws) + 1e-3,
      "random sets: average mean density " + app::format("%.4f", mean_stats.mean) +
          " differs from (N-1)/N");
  chapter.check(std::abs(sigma_stats.mean / sigma_theory - 1.0) < 0.1,
                "random sets: average sigma " + app::format("%.4f", sigma_stats.mean) +
                    " differs from the Poisson theory " + app::format("%.4f", sigma_theory) +
                    " by more than 10 %");
  return result;
}

/// \section ch02_settled Step 3: a settled distribution (Watkins Fig. 1a)
///
/// Watkins et al. "settled" their random particles "to a uniform density distribution" without
/// saying how.  `sph::relax_to_uniform_density` does it by moving every particle a little, each
/// iteration, along an SPH pressure force computed with the pressure \f$ P \propto \rho^\gamma \f$:
/// \f[ \mathbf u_i \leftarrow \mu\,\mathbf u_i - \epsilon\, h^2 \sum_j m_j
///       \left(\frac{P_i}{\rho_i^2} + \frac{P_j}{\rho_j^2}\right) \nabla_i W_{ij}, \qquad
///     \mathbf x_i \leftarrow \mathbf x_i + \mathbf u_i . \f]
/// For equal masses and fixed h this is gradient descent (with a little momentum \f$ \mu \f$) on
/// \f$ E = \sum_i m_i u(\rho_i) \approx \int \rho\, u(\rho)\, dV \f$, which for any
/// \f$ \gamma > 0 \f$ is a convex functional of \f$ \rho \f$, smallest when the density is uniform.
/// Two details matter in practice, and both are documented in `lib/sph/setups/relax.hpp`:
///  - the M4 gradient vanishes as \f$ r \to 0 \f$ (chapter 1, Fig. b), so two particles that
///    start close together barely repel; the relaxing force keeps the kernel's steepest slope
///    inside \f$ q = 2/3 \f$ (Thomas & Couchman 1992), and pairs separate;
///  - we stop when \f$ \sigma_\rho/\bar\rho \f$ has not improved by 1 % in 20 iterations, and
///    return the best set seen.
///
/// We tried the tempting alternative of descending on the scatter itself,
/// \f$ \sum_i (\rho_i - \bar\rho)^2 \f$: the scatter falls to \f$ 10^{-5} \f$ because the particles
/// pair up on top of each other (closest pairs at 0.004 spacings), a degenerate "uniform" state
/// that a pressure never allows.  The step compares three exponents \f$ \gamma \f$, all started
/// from the first random set of Step 2, and reports for each the mean and scatter of the
/// density, the iterations and time it took, and the closest pair of particles in mean
/// spacings.  It checks that every relaxation reached a scatter below 1 % without pairing
/// (closest pair above 0.3 spacings), and that the default \f$ \gamma = 2 \f$ has its mean
/// density within 0.5 % of one.
///
/// <b>What to look for.</b>  A scatter of about 0.36 % for \f$ \gamma = 2 \f$, the paper's
/// 0.004; the closest pair at about half a mean spacing (no pairs have formed); and a stiffer
/// pressure, larger \f$ \gamma \f$, settling further in fewer iterations.  In the figure the
/// settled densities fill a band of \f$ \pm 1\% \f$ with no trend in y, and the random ones
/// scatter from 0.3 to 2.
///
/// How close did the random start put its particles?  Among the \f$ \frac12 N^2 \f$ pairs of a
/// Poisson set in the unit box, each closer than r with probability \f$ \frac43 \pi r^3 \f$,
/// about one pair lies within \f$ r = (3 / 2\pi N^2)^{1/3} \f$, that is
/// \f$ r/\Delta x = (3/2\pi N)^{1/3} \f$: 0.05 mean spacings for N = 5000.  The relaxation has
/// to push such pairs apart by a factor of ten, against a kernel whose slope vanishes at the
/// centre, and the closest-pair column shows whether it did.  We measure the closest pair with
/// the neighbour list of the fixed h (`app::closest_separation`): any pair closer than the
/// kernel's radius is in that list, and a pair that matters here is far closer.  It is quoted
/// in mean spacings, \f$ \Delta x = N^{-1/3} \f$, so that the check's 0.3 means the same at
/// every N.
///
/// `app::closest_separation` is the first of the measures of a uniform set that the chapter
/// keeps in uniform_set_measures.hpp, shown here where the program first calls it.  Step 6
/// takes the neighbour counts and the spread of h from the same file, and Step 7 the two
/// density errors it records for every lattice and glass.
///
/// \show_file uniform_set_measures.hpp
///
/// Each relaxation starts from its own copy of the first random set, so that the three
/// exponents are compared from one start.  `settle` keeps the relaxed set, the library's report
/// (the iterations, the scatter at each of them, the mean and scatter of the best set), the
/// wall time and the closest pair.

struct Settled {
  sph::Particles<3> particles;
  sph::RelaxReport report;
  double gamma = 0, seconds = 0;
  double closest = 0;  // closest pair, in mean spacings
};

Settled settle(const sph::Particles<3>& start, double gamma) {
  Settled s{start, {}, gamma, 0, 0};
  sph::RelaxOptions options;
  options.gamma = gamma;
  const app::Stopwatch clock;
  s.report = sph::relax_to_uniform_density(s.particles, unit_box<3>(), options);
  s.seconds = clock.seconds();
  s.closest = app::closest_separation(s.particles, unit_box<3>()) /
              sph::root<3>(1.0 / static_cast<double>(s.particles.size()));
  return s;
}

/// The step returns the three settled sets in the order of \f$ \gamma \f$.  The second,
/// `settled[1]`, is the \f$ \gamma = 2 \f$ glass: only its mean density is checked, and it is
/// the set that the figure draws and Steps 5 and 6 take over.

std::vector<Settled> step3_settled(app::Chapter& chapter, const RandomSets& random) {
  std::printf("Step 3: the first random set settled to uniform density (Watkins Fig. 1a)\n");
  std::printf("  %-24s %10s %10s %10s %8s %9s %12s\n", "", "mean rho", "sigma_rho", "sigma/mean",
              "iter", "time [s]", "closest/dx");
  std::printf("  %-24s %10.3f %10.3f\n", "Watkins et al. (1996)", 0.999, 0.004);
  std::vector<Settled> settled;
  for (double gamma : {1.0, 2.0, 3.0}) {
    const Settled& s = settled.emplace_back(settle(random.first, gamma));
    const std::string who = "settled (gamma " + app::format("%.0f", gamma) + ")";
    std::printf("  %-24s %10.4f %10.4f %10.2e %8d %9.2f %12.2f\n",
                ("relaxed, P ~ rho^" + app::format("%.0f", gamma)).c_str(), s.report.final.mean,
                s.report.final.sigma, s.report.final.relative, s.report.iterations, s.seconds,
                s.closest);
    chapter.check(
        s.report.final.relative < 0.01,
        who + ": sigma/mean " + app::format("%.2e", s.report.final.relative) + " is not below 1 %");
    chapter.check(s.closest > 0.3, who + ": closest pair " + app::format("%.2f", s.closest) +
                                       " spacings: particles paired up");
  }
  const sph::DensityScatter& glass = settled[1].report.final;
  chapter.check(
      std::abs(glass.mean - 1.0) < 0.005,
      "settled: mean density " + app::format("%.4f", glass.mean) + " is not within 0.5 % of 1");
  std::printf("  (the rows use the set with the smallest scatter; the figure shows gamma = 2)\n\n");
  chapter.summary("error", "settled sigma = " + app::format("%.4f", glass.sigma) +
                               " (paper 0.004), random sigma = " +
                               app::format("%.3f", random.first_sigma) + " (paper 0.281)");
  return settled;
}

/// The figure of Steps 2 and 3 shows what Watkins' Figs 1a and 3a show -- the density at every
/// particle against its y coordinate -- with the same vertical ranges for both sets as a
/// reader of the paper would want: \f$ \pm 2\% \f$ for the settled set, 0 to 2.2 for the random
/// one.  A third panel shows the scatter during the three relaxations against the paper's 0.004.
///
/// Against y, because the paper plots against y; any coordinate would do, since the box is
/// periodic and the same in every direction.  What such a plot can show that the table cannot
/// is a *trend*: a relaxation that swept particles towards one side, or a random generator with
/// a preference, would tilt the band.  The drawing is `app::save_density_against_y_figure`
/// (`density_figures.hpp`, shown after the code below); the chapter supplies the sets, their
/// ranges and titles, the relaxation histories and the paper's value as the reference line.

void draw_watkins_figure(app::Chapter& chapter, const Setup& s, const RandomSets& random,
                         const std::vector<Settled>& settled) {
  const sph::DensityScatter& glass = settled[1].report.final;
  std::vector<app::RelaxationCurve> relaxations;
  for (const Settled& r : settled)
    relaxations.push_back({"P \\propto \\rho^" + app::format("%.0f", r.gamma), r.report.history});
  app::save_density_against_y_figure<3>(
      chapter.figure_path("watkins_density.png"),
      "Density at the particle positions, " + std::to_string(s.particles) +
          " particles in a periodic unit box (Watkins et al. 1996, Figs 1a and 3a)",
      plot::Stamp{.scheme = "gather density, constant h (eq A6)",
                  .kernel = "M4",
                  .neighbours = s.neighbours,
                  .particles = s.particles,
                  .run_time = chapter.seconds()},
      {settled[1].particles, "settled, self term included", 0.98, 1.02,
       "settled: mean " + app::format("%.4f", glass.mean) +
           ", \\sigma = " + app::format("%.4f", glass.sigma) + " (paper 0.999, 0.004)"},
      {random.first, "random, self term excluded", 0, 2.2,
       "random: mean " + app::format("%.3f", random.first_mean) +
           ", \\sigma = " + app::format("%.3f", random.first_sigma) + " (paper 1.013, 0.281)"},
      relaxations, {0.004, "Watkins: \\sigma = 0.004"});
}

/// The drawing of all three of the chapter's figures is in density_figures.hpp, shown here with
/// its first use; Steps 4 and 7 call its other two functions.
///
/// \show_file density_figures.hpp

/// \section ch02_lattice Step 4: the density of a lattice, and why it is not exact
///
/// A lattice looks like the ideal uniform fluid, yet its SPH density is not the density we
/// meant.  Put particles of mass \f$ m = \rho_0 \Delta x^D \f$ on a cubic lattice of spacing
/// \f$ \Delta x \f$; every particle then has the same density, but it is
/// \f$ \rho_0 \Delta x^D \sum_{\mathbf n} W(|\mathbf n| \Delta x, h) \f$, a *sum* standing in for
/// the integral \f$ \rho_0 \int W\, dV = \rho_0 \f$.  Poisson's summation formula says exactly
/// how far apart they are: the lattice sum equals the sum of the kernel's Fourier transform over
/// the reciprocal lattice,
/// \f[ \frac{\rho_{\rm SPH}}{\rho_0}
///     = \sum_{\mathbf k} \hat W\!\left(\frac{2\pi\mathbf k}{\Delta x}\right)
///     = 1 + \sum_{\mathbf k \ne 0} \hat W\!\left(\frac{2\pi\mathbf k}{\Delta x}\right). \f]
/// The error is the kernel's Fourier transform at the lattice's wavenumbers -- the "aliases" of
/// the lattice.  In 1D, chapter 1 gave \f$ \hat W(k) = (\sin(kh/2)/(kh/2))^4 \f$, so with
/// \f$ \eta = h/\Delta x \f$
/// \f[ \frac{\rho_{\rm SPH}}{\rho_0} - 1 = 2 \sum_{k \ge 1}
///     \left(\frac{\sin \pi k \eta}{\pi k \eta}\right)^4 \ \ge 0, \f]
/// +0.18 % at the common \f$ \eta = 1.2 \f$, zero at \f$ \eta = 1 \f$ and \f$ \eta = 2 \f$ (where
/// the B-spline's knots fall on the particles), and bounded by \f$ 2\zeta(4)/(\pi\eta)^4 \approx
/// 2.2/(\pi\eta)^4 \f$ in between.  In 2D and 3D the M4 is not a product of 1D splines, there
/// are no zeros fixed by the knots (only where a curve happens to cross zero), and \f$ \hat W \f$
/// can be negative (chapter 1, Fig. d), so the bias can take either sign.
///
/// Which wavenumbers enter depends on the lattice.  For the cubic lattice of spacing a the
/// reciprocal vectors are \f$ 2\pi\mathbf n/a \f$ with integer \f$ \mathbf n \f$: six shortest ones
/// of length \f$ 2\pi/a \f$.  The body-centred cubic lattice (two particles per cube of side a) has
/// a face-centred reciprocal lattice whose twelve shortest vectors have length
/// \f$ 2\sqrt2\,\pi/a \f$; the hexagonal lattice of spacing a has six of length
/// \f$ 4\pi/(\sqrt3\, a) \f$.  Measured in mean spacings these shortest wavenumbers are
/// \f$ 2\pi \f$ (cubic), \f$ 2.24\pi \f$ (bcc) and \f$ 2.15\pi \f$ (hexagonal): the denser
/// packings push their first aliases further out along \f$ \hat W \f$ but have more of them, and
/// where the transform oscillates about zero, as the M4's does in 3D, "further out" does not
/// simply mean "smaller".  There is no lattice without a bias; there are only values of
/// \f$ \eta \f$ where a given lattice happens to be lucky.
///
/// The program measures the bias with the library itself -- a periodic lattice, the neighbour
/// search, the density pass -- for cubic lattices in 1D, 2D and 3D, the hexagonal lattice in
/// 2D and the body-centred cubic lattice in 3D, over a range of \f$ \eta \f$.  To compare
/// lattices, \f$ \Delta x \f$ is the *mean* spacing \f$ (V/N)^{1/D} \f$, and the neighbour number
/// is \f$ N_{\rm ngb} = V_D (2\eta)^D \f$ as in eq A5.
///
/// <b>What to look for.</b>  The 1D column and the "1D Poisson" column are the same numbers:
/// the library's density pass against the formula above, two independent computations.  Zeros
/// at \f$ \eta = 1 \f$ and 2 in 1D and +0.18 % at 1.2; in 2D and 3D both signs, no lattice
/// better than the others at every \f$ \eta \f$, and at the common 3D choice
/// \f$ \eta = 1.2 \f$ (58 neighbours) biases from \f$ -0.49\% \f$ (bcc) to +0.08 % (cubic).
/// The last line shows the density equal at every particle of a lattice to \f$ 10^{-15} \f$:
/// the periodic images are seamless.
///
/// A lattice of the scan is named by its dimension and its type, so that the scan is one loop
/// over one table of lattices; the measurement is a template in D, written once, and the
/// dimension is turned into its template parameter in one place.

struct LatticeCase {
  const char* name;
  int dimension;
  sph::LatticeType type;
};

/// The measurement returns the relative density error \f$ \rho_{\rm SPH}/\rho_0 - 1 \f$ of a
/// periodic lattice at \f$ h = \eta \Delta x \f$, and the spread of the density over the
/// particles (zero up to round-off for a seamless lattice).  A small box will do.  Every
/// particle of a periodic lattice sees the same infinite lattice, because the neighbour search
/// supplies as many periodic images as the kernel reaches, so 8 cells per side are enough even
/// at \f$ \eta = 2.4 \f$, where the kernel reaches 4.8 spacings.  The hexagonal box is
/// \f$ \sqrt3/2 \f$ as high as it is wide, so that its rows close on themselves across the
/// periodic boundary.  The masses are \f$ \rho_0 V/N \f$ with \f$ \rho_0 = 1 \f$, so the bias is
/// simply the density of particle 0 less one.
template <int D>
std::pair<double, double> lattice_bias(sph::LatticeType type, double eta) {
  const int cells = 8;
  Vec<D> upper = Vec<D>::Ones();
  if constexpr (D == 2) {
    if (type == sph::LatticeType::hexagonal) upper[1] = std::sqrt(3.0) / 2.0;  // regular rows
  }
  const auto x = sph::lattice<D>(type, Vec<D>::Zero(), upper, 1.0 / cells);
  const double volume = upper.prod(),
               spacing = sph::root<D>(volume / static_cast<double>(x.size()));
  sph::Particles<D> p = sph::make_particles<D>(x, volume / static_cast<double>(x.size()));
  std::fill(p.smoothing_length.begin(), p.smoothing_length.end(), eta * spacing);
  sph::NeighbourSearch<D> search;
  search.update(p, sph::Box<D>::periodic_box(Vec<D>::Zero(), upper),
                sph::SmoothingLengthRule::fixed());
  sph::compute_density(p, search.list(), sph::DensityForm::watkins());
  const auto [lo, hi] = std::minmax_element(p.density.begin(), p.density.end());
  return {p.density[0] - 1.0, *hi - *lo};
}

std::pair<double, double> lattice_bias(const LatticeCase& c, double eta) {
  if (c.dimension == 1) return lattice_bias<1>(c.type, eta);
  if (c.dimension == 2) return lattice_bias<2>(c.type, eta);
  return lattice_bias<3>(c.type, eta);
}

/// The 1D bias by Poisson summation, independent of the density code
/// (`sph::m4_lattice_density_1d`).
double poisson_bias_1d(double eta) { return sph::m4_lattice_density_1d(eta) - 1.0; }

/// The step tabulates the bias at five values of \f$ \eta \f$ next to the Poisson sum -- 1 and
/// 2, the zeros of the 1D sum; 1.2, the common choice (58 neighbours in 3D); 1.24, the 64
/// neighbours of Selhammar and of Step 7; 1.5, where every lattice is biased high -- and
/// checks three things: the 1D bias equals the Poisson sum to \f$ 10^{-12} \f$ (two independent
/// routes to one number), it is the +0.18 % quoted in the text, and the density of each lattice
/// is the same at every particle to \f$ 10^{-10} \f$ (a lattice that did not tile its periodic box
/// would show a seam).

struct LatticeScan {
  std::vector<LatticeCase> lattices;
  std::vector<double> eta;
  std::vector<std::vector<double>> bias;  // [lattice][eta]
  double bias_1d_at_1_2 = 0;
};

LatticeScan step4_lattice_bias(app::Chapter& chapter, const Setup& s) {
  LatticeScan scan;
  scan.lattices = {{"1D", 1, sph::LatticeType::cubic},
                   {"2D square", 2, sph::LatticeType::cubic},
                   {"2D hexagonal", 2, sph::LatticeType::hexagonal},
                   {"3D cubic", 3, sph::LatticeType::cubic},
                   {"3D bcc", 3, sph::LatticeType::body_centred}};
  const double step = s.quick ? 0.05 : 0.01;
  for (int k = 0; 0.9 + k * step <= 2.4 + 1e-9; ++k) scan.eta.push_back(0.9 + k * step);
  double worst_spread = 0;
  for (const LatticeCase& lattice : scan.lattices) {
    auto& row = scan.bias.emplace_back();
    for (double eta : scan.eta) {
      const auto [bias, spread] = lattice_bias(lattice, eta);
      row.push_back(bias);
      worst_spread = std::max(worst_spread, spread);
    }
  }
  /// The figure uses the whole scan.  The table measures its five values of \f$ \eta \f$ again
  /// rather than look them up, so that they are exact whatever the step of the scan (with
  /// `--quick` the scan misses 1.24).  Its last column is eq A5's neighbour number in 3D,
  /// \f$ \tfrac43\pi(2\eta)^3 \f$.
  std::printf(
      "Step 4: density bias rho_SPH/rho_0 - 1 of periodic lattices, m = rho_0 dx^D,\n"
      "  h = eta dx (dx = mean spacing)\n");
  std::printf("  %5s", "eta");
  for (const auto& l : scan.lattices) std::printf(" %12s", l.name);
  std::printf(" %12s %9s\n", "1D Poisson", "N_ngb(3D)");
  for (double eta : {1.0, 1.2, 1.24, 1.5, 2.0}) {
    std::printf("  %5.2f", eta);
    for (const LatticeCase& lattice : scan.lattices)
      std::printf(" %11.4f%%", 100 * lattice_bias(lattice, eta).first);
    std::printf(" %11.4f%% %9.1f\n", 100 * poisson_bias_1d(eta),
                4.0 / 3.0 * std::numbers::pi * std::pow(2 * eta, 3));
  }
  scan.bias_1d_at_1_2 = lattice_bias(scan.lattices[0], 1.2).first;
  std::printf("  largest spread of the density over one lattice: %.1e (a seamless lattice)\n\n",
              worst_spread);
  const double poisson = poisson_bias_1d(1.2), bias = scan.bias_1d_at_1_2;
  chapter.check(std::abs(bias - poisson) < 1e-12,
                "1D lattice bias at eta = 1.2: " + app::format("%.3e", bias) + ", Poisson sum " +
                    app::format("%.3e", poisson));
  chapter.check(std::abs(bias - 0.0018) < 0.0001, "1D lattice bias at eta = 1.2 is " +
                                                      app::format("%.4f %%", 100 * bias) +
                                                      ", expected +0.18 %");
  chapter.check(worst_spread < 1e-10, "a lattice density varies over the particles by " +
                                          app::format("%.1e", worst_spread));
  return scan;
}

/// The lattice figure has the signed bias in per cent on the left, where the sign changes of
/// the 2D and 3D lattices show, and its magnitude on a log scale on the right, with the 1D
/// bound as the reference line.  The scan is finer than the table, steps of 0.01 in
/// \f$ \eta \f$ (0.05 with `--quick`), because the 3D curves turn quickly: the cubic lattice
/// goes from +0.08 % at \f$ \eta = 1.2 \f$ to \f$ -0.11\% \f$ at 1.24.  Look for the 1D curve
/// touching zero at \f$ \eta = 1 \f$ and 2 and never crossing it, for the 2D and 3D curves that
/// do cross, and, on the right, for every curve staying under the dotted bound from
/// \f$ \eta = 1.5 \f$ on.  The drawing is `app::save_lattice_bias_figure`, in
/// density_figures.hpp (shown at the end of Step 3).

void draw_lattice_figure(app::Chapter& chapter, const LatticeScan& scan) {
  std::vector<app::LatticeBiasCurve> lattices;
  for (std::size_t c = 0; c < scan.lattices.size(); ++c)
    lattices.push_back({scan.lattices[c].name, scan.bias[c]});
  std::vector<double> bound;
  for (double eta : scan.eta) bound.push_back(100 * 2.2 / std::pow(std::numbers::pi * eta, 4));
  app::save_lattice_bias_figure(
      chapter.figure_path("lattice_bias.png"),
      "Density bias of a uniform lattice, \\rho_{SPH}/\\rho_0 - 1, against h / \\Delta x",
      plot::Stamp{.scheme = "gather density with self term, m = \\rho_0 \\Delta x^D",
                  .kernel = "M4",
                  .run_time = chapter.seconds()},
      scan.eta, lattices,
      {1.2, 100 * scan.bias_1d_at_1_2,
       "1D, \\eta = 1.2: +" + app::format("%.2f %%", 100 * scan.bias_1d_at_1_2)},
      "2.2/(\\pi\\eta)^4 (1D bound)", bound);
}

/// \section ch02_calibrate Step 5: building an initial condition with the density we intend
///
/// Why care about 0.2 %?  Because the density sets the pressure, and a lattice with a biased
/// density is a fluid at the wrong pressure.  In a uniform periodic box nothing happens -- all
/// particles are biased alike -- but where two lattices meet (the two sides of a shock tube,
/// chapters 3-4) each side carries its own bias, the pressure jump at the interface is not the
/// one we set, and the error this causes does not shrink as we refine: \f$ \eta \f$, not
/// \f$ \Delta x \f$, sets the bias.  It becomes a floor under every convergence study.
///
/// The cure is to measure the kernel sum on the particle set we actually built and divide it out.
/// `sph::calibrate_mass_to_density` keeps h and the neighbour list fixed and iterates
/// \f$ m_i \leftarrow m_i\, \rho_{\rm target}(\mathbf x_i)/\rho_i \f$.  On a uniform lattice one
/// sweep is exact -- it is \f$ m = \rho_0 / \sum_j W_{ij} \f$ -- and where two lattices meet at a
/// density jump (the shock tubes) it converges geometrically with the pair-averaged sum (the tests
/// check both).
///
/// On a glass the same iteration is a different matter.  Asking every particle of a disordered
/// set for exactly \f$ \rho_0 \f$ means solving \f$ \sum_j W_{ij} m_j = \rho_0 \f$ for the masses:
/// a *deconvolution* by the kernel, whose matrix has eigenvalues near zero (the Fourier transform
/// of chapter 1 at short wavelengths, negative lobe included).  The program runs it for 30 sweeps
/// and prints what happens.  For a glass the sensible correction is the mean alone,
/// `sph::calibrate_mean_density`: one factor for all masses, which removes the bias and leaves
/// the scatter.  The step checks that the lattice is exact after one sweep (to
/// \f$ 10^{-12} \f$) and that the mean calibration puts the glass's mean density at one.
/// Why one factor is enough for the mean: with h and the neighbours fixed every density is
/// linear in the masses, so multiplying all of them by \f$ \rho_0/\bar\rho \f$ moves the mean
/// exactly to \f$ \rho_0 \f$ and leaves the relative scatter \f$ \sigma_\rho/\bar\rho \f$ as it
/// was -- the printed \f$ 3.59\cdot 10^{-3} \f$ is the \f$ \gamma = 2 \f$ glass's own from Step 3.
///
/// <b>What to look for.</b>  The lattice: error \f$ 1.3\cdot 10^{-4} \f$ before, round-off
/// after one sweep.  The glass: the per-particle iteration stalls at \f$ 3\cdot 10^{-3} \f$
/// after 30 sweeps while the masses spread by 4 % -- the deconvolution at work, trading a
/// density error for a mass error ten times larger.  The mean-only correction: one factor of
/// 1.0012, and the scatter unchanged.
///
/// The lattice is the cubic lattice of the unit box, \f$ 16^3 \f$ particles (\f$ 10^3 \f$ with
/// `--quick`), with Watkins' h for the chapter's 60 neighbours -- so \f$ \eta = 1.214 \f$, as
/// Step 1 predicted, and its bias is the 3D cubic curve of Step 4 at that \f$ \eta \f$, where
/// the curve passes close to zero on its way from +0.08 % to \f$ -0.11\% \f$.  The printed
/// \f$ m N / M \f$ is the calibrated mass as a fraction of the nominal one: one sweep divides
/// the mass by the measured \f$ \rho/\rho_0 \f$.  For the glass the step prints how far the
/// per-particle masses have moved apart, the relative scatter of the masses after the sweeps;
/// a calibration that buys a density error with a larger mass error has not helped.

void step5_calibration(app::Chapter& chapter, const Setup& s, const Settled& glass) {
  std::printf("Step 5: masses calibrated so that the SPH density is exactly rho_0 = 1\n");
  // The lattice: every particle alike, one sweep.
  const int side = s.quick ? 10 : 16;
  const std::array<int, 3> cells{side, side, side};
  auto lattice = sph::setups::unit_box_particles<3>(
      sph::lattice<3>(sph::LatticeType::cubic, Vec<3>::Zero(), Vec<3>::Ones(), cells),
      s.neighbours);
  sph::NeighbourSearch<3> search;
  search.update(lattice, unit_box<3>(), sph::SmoothingLengthRule::fixed());
  const auto on_lattice =
      sph::calibrate_mass_to_density<3>(lattice, search.list(), 1.0, sph::DensityForm::watkins());
  std::printf(
      "  3D cubic lattice, %d^3, eta = %.3f: error %.2e before, %.2e after %d sweep(s);\n"
      "    m N / M = %.6f\n",
      side, lattice.smoothing_length[0] * side, on_lattice.initial_error, on_lattice.final_error,
      on_lattice.iterations, lattice.mass[0] * side * side * side);
  /// The glass is the \f$ \gamma = 2 \f$ set of Step 3, copied twice: one copy for the
  /// per-particle iteration, one for the mean-only correction.  The latter needs no search: it
  /// scales the masses, and the densities the set already carries, by one factor.
  // The glass: per particle (30 sweeps), and the mean alone.
  auto per_particle = glass.particles, mean_only = glass.particles;
  search.update(per_particle, unit_box<3>(), sph::SmoothingLengthRule::fixed());
  const auto on_glass = sph::calibrate_mass_to_density<3>(per_particle, search.list(), 1.0,
                                                          sph::DensityForm::watkins(), 30);
  std::printf(
      "  settled glass, per particle:  error %.2e before, %.2e after %d sweeps;\n"
      "    masses now scatter by %.2e\n",
      on_glass.initial_error, on_glass.final_error, on_glass.iterations,
      sph::density_scatter(per_particle.mass).relative);
  const double factor = sph::calibrate_mean_density(mean_only, 1.0);
  const auto calibrated = sph::density_scatter(mean_only.density);
  std::printf(
      "  settled glass, mean only:     masses x %.6f; mean density %.6f, sigma %.2e "
      "(unchanged)\n\n",
      factor, calibrated.mean, calibrated.relative);
  chapter.check(on_lattice.final_error < 1e-12 && on_lattice.iterations == 1,
                "lattice calibration: error " + app::format("%.2e", on_lattice.final_error) +
                    " after " + std::to_string(on_lattice.iterations) + " sweeps");
  chapter.check(std::abs(calibrated.mean - 1.0) < 1e-12,
                "glass mean calibration: mean density " + app::format("%.15f", calibrated.mean));
}

/// \section ch02_rules Step 6: the smoothing-length rules
///
/// The static tests use one constant h.  A real flow needs h to follow the density.  The
/// library offers Watkins' two rules (Appendix A) besides the fixed one:
///  - **neighbour number**: h_i such that particle i has \f$ N \pm \Delta N \f$ neighbours within
///    \f$ 2h_i \f$ (Watkins use \f$ \pm 10\% \f$; Selhammar 64 neighbours).  When the count is out
///    of tolerance, the search places \f$ 2h_i \f$ half-way between the N-th and (N+1)-th nearest
///    neighbour, so the count becomes N exactly without iteration.  On a lattice the N-th and
///    (N+1)-th neighbour can sit on the same shell; then \f$ 2h_i \f$ goes into the gap inside
///    or outside that shell, whichever count is nearer N.  (Placed *on* the shell, \f$ 2h \f$
///    would leave it to round-off which shell members count: a cubic lattice asked for 64 then
///    gets counts from 56 to 74.)
///  - **density**: Newton's method on eq A6 with the particle's own density,
///    \f$ \rho_i(h_i)\, V_D (2h_i)^D = N m_i \f$.  Written with the kernel's shape, the left side
///    is \f$ V_D 2^D \sum_j m_j \sigma_D\, w(r_{ij}/h_i) \f$ -- the \f$ h^{-D} \f$ of the kernel
///    cancels the \f$ h^D \f$ of the volume -- a sum that grows with \f$ h_i \f$ as neighbours
///    enter the kernel, with the derivative \f$ -\sum_j m_j \sigma_D\, w'(q_{ij})\, q_{ij}/h_i \f$
///    computed in the same loop.  A Newton step longer than half of h is replaced by a step of
///    30 % of h in the same direction, so a particle whose first guess is far off (the centre
///    of a dense cluster) walks to its h in a few steps; the candidates are gathered once for a
///    radius a little larger than \f$ 2h \f$ and gathered again only when h grows past it.
///
/// We apply all three to the settled and to the random set, and print the smallest, mean and
/// largest neighbour count, the spread of h, the largest violation of eq A6 and the time.  The
/// step checks what each rule promises: the neighbour-number rule keeps every count within the
/// tolerance, and the density rule satisfies eq A6 at every particle to \f$ 10^{-6} \f$.
/// Why both sets?  The settled set is what a simulation starts from, and on it a good rule
/// should change little.  The random set is the stress test: its densities differ by a quarter
/// from particle to particle (Step 2), and only there do the rules show what they really
/// promise.
///
/// <b>What to look for.</b>  On the settled set the three rules hardly differ (h varies by
/// 8 % at most).  On the random set they part ways: the fixed h gives counts from 35 to 86, the
/// neighbour-number rule forces them into 54-66 by varying h by a factor 1.3, and the density
/// rule satisfies eq A6 to round-off while its counts range from 17 to 101 and its h by a factor
/// 2 -- eq A6 fixes the mass inside the kernel, not the number of particles.
///
/// The column "eq A6 error" is
/// \f$ \max_i |\rho_i V_3 (2h_i)^3 / (N_{\rm kernel}\, m_i) - 1| \f$, with the density the pass
/// has just computed (gather, self term, the particle's own h).  For the fixed h, chosen by eq
/// A6 with \f$ \rho = 1 \f$, it is simply the largest density error \f$ |\rho_i - 1| \f$: on the
/// settled set the same \f$ 1.28\cdot 10^{-2} \f$ that Step 5 calibrates from.  The
/// neighbour-number rule's tolerance is \f$ \pm 10\% \f$ of the target rounded to a whole count,
/// \f$ \pm 6 \f$ for 60.  Each rule's time is that of its search and one density pass, so the
/// time column also shows what the two adaptive rules cost over the fixed one.

struct RuleResult {
  std::string name;
  int min_count = 0, max_count = 0;
  double mean_count = 0, h_spread = 0, seconds = 0, worst_a6 = 0;
};

/// `apply_rule` takes the set by value, so that every rule starts from the same positions and
/// the same h; the counts and the spread of h it reports are measures of uniform_set_measures.hpp
/// (shown in Step 3).

RuleResult apply_rule(sph::Particles<3> p, const std::string& name,
                      const sph::SmoothingLengthRule& rule, double neighbours) {
  RuleResult r{name};
  const app::Stopwatch clock;
  sph::NeighbourSearch<3> search;
  search.update(p, unit_box<3>(), rule);
  sph::compute_density(p, search.list(), sph::DensityForm::watkins());
  r.seconds = clock.seconds();
  const app::NeighbourCounts counts = app::neighbour_counts(p);
  r.min_count = counts.min;
  r.max_count = counts.max;
  r.mean_count = counts.mean;
  r.h_spread = app::smoothing_length_spread(p);
  // How well eq A6 holds with the density the pass computed (gather, self term, own h).
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double kernel_mass =
        p.density[i] * sph::unit_ball_volume<3>() * std::pow(2.0 * p.smoothing_length[i], 3);
    r.worst_a6 = std::max(r.worst_a6, std::abs(kernel_mass / (neighbours * p.mass[i]) - 1.0));
  }
  return r;
}

/// For each set the three rules run in the order of the table, so `results[1]` is the
/// neighbour-number rule and `results[2]` the density rule, the two that are checked; the fixed
/// h promises nothing.

void step6_rules(app::Chapter& chapter, const Setup& s, const Settled& glass,
                 const RandomSets& random) {
  std::printf("Step 6: neighbour counts under the three smoothing-length rules (target %g)\n",
              s.neighbours);
  std::printf("  %-19s %-28s %4s %6s %4s %9s %11s %8s\n", "set", "rule", "min", "mean", "max",
              "h max/min", "eq A6 error", "time [s]");
  const double tolerance = std::round(0.1 * s.neighbours);
  const std::pair<std::string, const sph::Particles<3>*> sets[] = {
      {"settled (gamma = 2)", &glass.particles}, {"random", &random.first}};
  for (const auto& [set_name, set] : sets) {
    const RuleResult results[] = {
        apply_rule(*set, "fixed h (eq A6 with rho = 1)", sph::SmoothingLengthRule::fixed(),
                   s.neighbours),
        apply_rule(*set, "neighbour number +-" + app::format("%.0f", tolerance),
                   sph::SmoothingLengthRule::neighbour_number(s.neighbours, tolerance),
                   s.neighbours),
        apply_rule(*set, "density (eq A6 per particle)",
                   sph::SmoothingLengthRule::from_density(s.neighbours), s.neighbours)};
    for (const RuleResult& r : results) {
      std::printf("  %-19s %-28s %4d %6.2f %4d %9.3f %11.2e %8.4f\n", set_name.c_str(),
                  r.name.c_str(), r.min_count, r.mean_count, r.max_count, r.h_spread, r.worst_a6,
                  r.seconds);
    }
    const RuleResult& count = results[1];
    chapter.check(std::abs(count.min_count - s.neighbours) <= tolerance &&
                      std::abs(count.max_count - s.neighbours) <= tolerance,
                  set_name + ": neighbour-number rule gave counts " +
                      std::to_string(count.min_count) + " to " + std::to_string(count.max_count));
    chapter.check(results[2].worst_a6 < 1e-6, set_name + ": density rule violates eq A6 by " +
                                                  app::format("%.2e", results[2].worst_a6));
  }
  std::printf("\n");
}

/// \section ch02_cost Step 7: density error against run time
///
/// Finally the question every later chapter asks of its scheme: what does accuracy cost?  We
/// measure the density error of 3D lattices and settled glasses at several particle numbers N
/// and three neighbour numbers, and time the step that produces it (neighbour search and
/// density pass, on one thread; the relaxation that builds a glass is a one-off cost and is
/// reported separately).  Two error measures: the root-mean-square of \f$ \rho_i/\rho_0 - 1 \f$
/// over the particles, and the bias of the mean, \f$ |\bar\rho/\rho_0 - 1| \f$.  The neighbour
/// numbers 32, 64, 128 correspond to \f$ \eta = 0.98, 1.24, 1.56 \f$.
///
/// What should the time be?  The search visits, for each particle, the cells overlapping a cube
/// around it (cells half the search radius R wide, so \f$ 5^3 \f$ of them, a cube of side
/// \f$ 2.5R \f$) and tests every particle in them.  With \f$ R = 1.2 \times 2h \f$ (a 20 % margin,
/// so that the neighbour-number rule can move h without searching again) that is
/// \f$ 2.5^3 \cdot 1.2^3 / \tfrac43\pi \approx 6 \f$ candidates per neighbour.  The density
/// pass then evaluates one kernel per neighbour.  Both grow as \f$ N\, N_{\rm ngb} \f$; what
/// does not is the fixed work per particle and per cell visited, so the time per neighbour
/// falls as the kernel fills.  The benchmark program
/// (`bench`, 10^5 particles, 64 neighbours) measures the same pieces in isolation.  The runs go
/// into an `sph::ErrorVsTime` study, which prints the table with the fitted order \f$ p \f$
/// (error \f$ \propto \Delta x^p \f$) and draws the log-log figure.
///
/// <b>What to look for.</b>  The lattice rows: the same error at every N (order 0), because
/// the error is the bias of Step 4, which depends on \f$ \eta \f$ alone.  The glass rows: an
/// error that falls with the neighbour number (0.6 %, 0.3 %, 0.13 % at 32, 64, 128) but not with
/// N at fixed neighbours.  And the times: roughly proportional to N (fitted slopes 1.1-1.2), and
/// growing by a factor of 1.3 to 2.8 with each doubling of the neighbour number (2.0, then 1.6, at
/// N = 32768): on the whole less than the doubling of the pairs, since the search's cost per
/// particle does not all scale with the kernel, and scattered, since the shortest runs take
/// milliseconds.

///
/// The sweep is `app::run_density_cost_sweep` (`density_timing.hpp`, shown in Step 2).  It runs
/// on one thread, so that the times compare across N even on a shared machine (the smallest sets,
/// below `sph::parallel_threshold`, run on one thread anyway).  Each set's density step is run
/// three times and the shortest time kept: other work on the machine can only slow a run down,
/// never speed it up, so the minimum is the best estimate of the step's own cost, and the
/// errors, which do not depend on the time, are those of the last pass.  A glass is relaxed
/// before it is timed, with the relaxation's cost counted apart.  The lattices run to
/// \f$ 32^3 \f$ particles, the glasses only to \f$ 16^3 \f$, because building a glass costs far
/// more than measuring it (the last line of the output says how much).  With `--quick` the
/// lattices have sides 6, 8 and 10 and the glasses 6 and 8: enough points for a slope, and
/// a run of seconds.
///
/// Two slopes summarise each line of the table.  The order p is the least-squares slope of
/// \f$ \ln \text{error} \f$ against \f$ \ln \Delta x \f$; the cost slope s that of
/// \f$ \ln \text{error} \f$ against \f$ \ln t \f$, more negative when a method buys more accuracy
/// per second.  A line that is flat in \f$ \Delta x \f$ has both near zero, whatever its times.

///
/// The step checks the two findings the figure is about: a lattice's error does not change with
/// N at all (to \f$ 10^{-9} \f$ relative: at every N it is the same sum over the same shells,
/// and only round-off differs), and every glass stays below 2 % RMS.  The figure is
/// the shared error-against-time figure of `lib/app/error_figure.hpp`, with the y range widened
/// so that the legend finds room under the lines (`app::save_density_cost_figure`, in
/// density_figures.hpp, shown in Step 3).

void step7_cost(app::Chapter& chapter, const Setup& s) {
  std::printf("Step 7: density error against run time (3D, periodic unit box)\n");
  app::DensityCostStudy cost{sph::ErrorVsTime(
      "Density error of 3D lattices and settled glasses against the run time of the density step")};
  const std::vector<int> lattice_sides =
      s.quick ? std::vector<int>{6, 8, 10} : std::vector<int>{8, 12, 16, 24, 32};
  const std::vector<int> glass_sides =
      s.quick ? std::vector<int>{6, 8} : std::vector<int>{8, 12, 16};
  app::run_density_cost_sweep(cost, {32.0, 64.0, 128.0}, lattice_sides, glass_sides);
  std::printf("\n%s", cost.study.table().c_str());
  std::printf(
      "relaxing the glasses took %.1f s for %ld particles in all (not in the times above)\n",
      cost.relax_seconds, cost.relaxed_particles);
  for (const std::string& method : cost.study.methods()) {
    const sph::ErrorCurve curve = cost.study.curve(method, "rms error");
    const auto [lo, hi] = std::minmax_element(curve.error.begin(), curve.error.end());
    if (method.starts_with("lattice")) {
      chapter.check(*hi <= *lo * (1 + 1e-9), method + ": the lattice error changes with N (" +
                                                 app::format("%.3e", *lo) + " to " +
                                                 app::format("%.3e", *hi) + ")");
    } else {
      chapter.check(*hi < 0.02,
                    method + ": glass rms error " + app::format("%.3e", *hi) + " above 2 %");
    }
  }
  app::save_density_cost_figure(
      chapter.figure_path("density_error_vs_time.png"), cost.study,
      "Density error of 3D lattices and settled glasses against the time of the density step",
      plot::format_stamp(
          {.scheme =
               "gather density with self term, constant h (eq A6), search + density on one thread",
           .kernel = "M4"}),
      1e-4, 1e-5);
}

}  // namespace

/// \section ch02_next What comes next
///
/// The particles so far stand still.  Chapter 3 moves them: the pressure force is the gradient
/// of the same kernel sums, the internal energy changes by the work of that force, and a
/// leapfrog advances positions, velocities and energies together.  Its first scene, Sod's shock
/// tube, is built from two lattices whose densities differ by a factor of eight -- the place
/// where Step 5's calibration matters, because each side's bias (Step 4) would otherwise put a
/// pressure jump at the interface that nobody asked for.

///
/// \section ch02_main The main program
///
/// `main` reads the parameters -- `--particles` and `--neighbours` change the static tests,
/// `--draws` the number of random sets; `--quick` uses 1000 particles, four draws and smaller
/// lattices for the test suite -- and runs the seven steps.  Steps 3 to 6 reuse the sets of
/// the earlier steps: the random set of Step 2 is the start of the relaxations in Step 3, whose
/// \f$ \gamma = 2 \f$ glass is calibrated in Step 5 and measured again in Step 6.
///
/// The neighbour number has a lower limit that is not arbitrary.  With h from the density, a
/// particle whose kernel held no neighbour at all would have only its own term,
/// \f$ \rho = m W(0, h) = m/(\pi h^3) \f$, and eq A6,
/// \f$ h^3 = 3 N_{\rm kernel} m / (32\pi\rho) \f$, would then ask for
/// \f$ h^3 = \frac{3 N_{\rm kernel}}{32} h^3 \f$.  Below \f$ N_{\rm kernel} = 32/3 \f$ the right
/// side is always the smaller: a particle that has lost its neighbours asks for a still smaller h,
/// and the iteration drives h to zero.  The option therefore starts at 11.

int main(int argc, char** argv) {
  return app::run_main([&] {
    app::Chapter chapter("02-density", "Chapter 2: Neighbours, density and the smoothing length",
                         argc, argv);
    Setup s;
    chapter
        .parameter("--particles", s.particles, "particles of the static tests (Watkins: 5000)",
                   1000)
        .check(app::count_between(200, 100000, [](double n) { return app::particle_bytes(3, n); }));
    chapter
        .parameter("--neighbours", s.neighbours,
                   "expected neighbours within 2h, eq A5 (Watkins: 60; below 32/3, h from the "
                   "density collapses to zero)")
        .check(app::between(11, 400));
    chapter
        .parameter("--draws", s.draws, "random sets drawn to measure the spread of mean and sigma",
                   4)
        .check(app::between(2, 200));
    if (int rc = chapter.parse(); rc >= 0) return rc;
    s.quick = chapter.quick();
    step1_smoothing_length(s);
    const RandomSets random = step2_random(chapter, s);
    const std::vector<Settled> settled = step3_settled(chapter, random);
    draw_watkins_figure(chapter, s, random, settled);
    const LatticeScan scan = step4_lattice_bias(chapter, s);
    draw_lattice_figure(chapter, scan);
    step5_calibration(chapter, s, settled[1]);
    step6_rules(chapter, s, settled[1], random);
    step7_cost(chapter, s);
    return chapter.finish();
  });
}
