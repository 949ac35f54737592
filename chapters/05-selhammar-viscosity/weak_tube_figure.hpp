#pragma once
/// \file
/// \brief The figure of a weak-tube run in the layout of Selhammar's Figs 1-2: \f$ v_z \f$, P
/// and \f$ \rho \f$ against z, one panel each, the particles as dots, the Lagrangian reference
/// as a red line and the Riemann solution of the initial jump as a dashed grey line.
///
/// The program's step3_weak_tube(), just above, calls it once per viscosity.  Every particle is
/// drawn at its z, so the scatter of a column of particles about the line is seen as in the
/// paper.  Each panel's scale is that of the gas (particles and reference): the Riemann
/// solution, drawn over the whole window, would otherwise set it with the states it keeps
/// beyond the ends of the expanded gas.
///
/// Header-only: a chapter that includes it links sph_plot.

#include "weak_tube_run.hpp"
#include "plot/figure.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace app {

/// Draws \p run against the profile \p ref and the Riemann solution \p riemann, at time \p t,
/// and writes the figure to \p path; the stamp names the run's viscosity, particles and wall
/// time.
inline void save_weak_tube_figure(const WeakTubeRun& run, const sph::LagrangianProfile& ref,
                                  const sph::RiemannSolution& riemann, double t,
                                  const std::string& path, const std::string& title) {
  plot::Figure figure(3, 1, {.width = 1100, .height = 1300});
  figure.title(title);
  figure.stamp(plot::Stamp{.scheme = run.name + " viscosity",
                           .kernel = "M4",
                           .neighbours = 64,
                           .particles = static_cast<long long>(run.particles.size()),
                           .run_time = run.seconds,
                           .extra = "t = 20"});
  /// The data first: the particles' \f$ v_z \f$, P and \f$ \rho \f$ at their z, and the
  /// Riemann solution on a grid of its own, much finer than the particles' spacing -- it is a
  /// formula, and can be evaluated anywhere.
  // The particles' values at their z.
  std::vector<double> z, v, P, rho;
  for (std::size_t i = 0; i < run.particles.size(); ++i) {
    z.push_back(run.particles.position[i][2]);
    v.push_back(run.particles.velocity[i][2]);
    P.push_back(run.particles.pressure[i]);
    rho.push_back(run.particles.density[i]);
  }
  // The Riemann solution on a fine grid over the whole window.
  std::vector<double> zs, rv, rP, rrho;
  for (double x = -9; x <= 9; x += 0.005) {
    zs.push_back(x);
    const sph::GasState w = riemann.sample(x, t);
    rv.push_back(w.velocity);
    rP.push_back(w.pressure);
    rrho.push_back(w.density);
  }
  /// The three panels differ only in the quantity, so a small table pairs each axis label with
  /// its three curves and one loop draws them all.  The reference is drawn last, over the dots
  /// and the dashed Riemann curve, so that it stays visible where the particles crowd.
  struct Panel {
    const char* label;
    const std::vector<double>& particles;
    const std::vector<double>& reference;
    const std::vector<double>& riemann;
  };
  const Panel panels[] = {{"v_z  [code units]", v, ref.velocity, rv},
                          {"P  [code units]", P, ref.pressure, rP},
                          {"\\rho  [code units]", rho, ref.density, rrho}};
  for (int k = 0; k < 3; ++k) {
    plot::Axes& ax = figure.panel(k);
    ax.xlabel("z  [code units]").ylabel(panels[k].label).xlim(-9, 9);
    // The scale of the gas (the Riemann curve, past the gas's ends, must not set it).
    double lo = 0, hi = 0;
    for (double q : panels[k].reference) lo = std::min(lo, q), hi = std::max(hi, q);
    for (double q : panels[k].particles) lo = std::min(lo, q), hi = std::max(hi, q);
    ax.ylim(lo - 0.05 * (hi - lo), hi + 0.15 * (hi - lo));
    ax.scatter(z, panels[k].particles,
               {.label = "SPH particles", .color = plot::black, .size = 2.0});
    ax.line(zs, panels[k].riemann,
            {.label = "Riemann solution (valid only early)",
             .color = plot::grey,
             .style = plot::Dash::dashed,
             .width = 1.2});
    ax.line(ref.radius, panels[k].reference,
            {.label = "1D Lagrangian reference", .color = plot::red, .width = 1.6});
    if (k == 0) ax.legend(plot::Corner::upper_left);
  }
  figure.save_png(path);
}

}  // namespace app
