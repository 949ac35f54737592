#pragma once
/// \file
/// \brief The figures of the Evrard collapse: the energies against time for several viscosities
/// over the 1D reference, with the change of the total energy (app::save_evrard_energy_figure,
/// Selhammar's Fig 5), and one run's radial velocity, density and pressure at t = 0.8 over the
/// finite-volume reference (app::save_evrard_profile_figure, his Figs 6-7).
///
/// Header-only: the program that includes it links sph_plot.

#include "evrard_reference.hpp"
#include "app/evrard_run.hpp"
#include "radial_profile.hpp"
#include "plot/figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

namespace app {

namespace evrard_figure_detail {

/// One run's four energies in a panel, over the reference's as wide grey lines.
inline void draw_energies(plot::Axes& ax, const EvrardRun& run, const EvrardReference& ref) {
  const plot::Color light{0.72, 0.72, 0.72};
  std::vector<double> ref_total(ref.t.size()), total(run.t.size());
  for (std::size_t i = 0; i < ref.t.size(); ++i)
    ref_total[i] = ref.kinetic[i] + ref.thermal[i] + ref.potential[i];
  for (std::size_t i = 0; i < run.t.size(); ++i) total[i] = total_at(run, i);
  ax.line(ref.t, ref.thermal, {.label = "1D reference", .color = light, .width = 6});
  for (const std::vector<double>* series :
       std::initializer_list<const std::vector<double>*>{&ref.kinetic, &ref.potential, &ref_total})
    ax.line(ref.t, *series, {.color = light, .width = 6});
  ax.line(run.t, run.thermal, {.label = "E_{th}", .color = plot::red, .width = 2});
  ax.line(run.t, run.kinetic, {.label = "E_{kin}", .color = plot::blue, .width = 2});
  ax.line(run.t, total, {.label = "E_{tot}", .color = plot::black, .width = 2});
  ax.line(run.t, run.potential, {.label = "E_{pot}", .color = plot::green, .width = 2});
  ax.legend(plot::Corner::lower_right);
}

/// The change of the total energy of each run relative to its start: the runs in \p runs
/// (softening \p softening: "h" or a length) and, if given, \p fixed (a fixed softening length
/// \p fixed_softening).
inline void draw_energy_change(plot::Axes& ax, const std::vector<EvrardRun>& runs,
                               const std::string& softening, const EvrardRun* fixed,
                               double fixed_softening) {
  // the change of the total energy relative to its start, and the range of all four curves
  double lowest = 0, highest = 0;
  const auto change = [&](const EvrardRun& run) {
    std::vector<double> e(run.t.size());
    for (std::size_t i = 0; i < e.size(); ++i) {
      e[i] = (total_at(run, i) - total_at(run, 0)) / std::abs(total_at(run, 0));
      lowest = std::min(lowest, e[i]);
      highest = std::max(highest, e[i]);
    }
    return e;
  };
  const plot::Color colors[] = {plot::blue, plot::red, plot::green};
  for (std::size_t k = 0; k < runs.size(); ++k) {
    ax.line(runs[k].t, change(runs[k]),
            {.label = runs[k].name + ", softening " + softening, .color = colors[k], .width = 2});
  }
  if (fixed) {
    char label[96];
    std::snprintf(label, sizeof label, "standard, fixed softening %.3g", fixed_softening);
    ax.line(fixed->t, change(*fixed),
            {.label = label, .color = plot::black, .style = plot::Dash::dashed, .width = 2});
  }
  ax.hline(0, {.color = plot::Color{0.6, 0.6, 0.6}, .style = plot::Dash::dotted});
  const double span = std::max(highest - lowest, 1e-6);
  // (room below the curves for the legend, which would otherwise hide the modified run's dip)
  ax.ylim(lowest - 0.35 * span, highest + 0.05 * span);
  ax.legend(plot::Corner::lower_right);
}

}  // namespace evrard_figure_detail

/// Draws the energies of the three \p runs in panels (a)-(c) over the reference \p ref, and in
/// panel (d) the change of their total energy and, if given, that of \p fixed, a run with the
/// fixed softening length \p fixed_softening.  \p softening is the runs' softening ("h" or a
/// length) and \p integration how they were integrated, for the stamp and the labels; writes the
/// PNG to \p path.
inline void save_evrard_energy_figure(const std::string& path, const std::vector<EvrardRun>& runs,
                                      const EvrardRun* fixed, const EvrardReference& ref,
                                      double fixed_softening, const std::string& softening,
                                      const std::string& integration) {
  plot::Figure figure(2, 2, {.width = 1600, .height = 1300});
  figure.title("Evrard collapse: energies (Selhammar Fig 5)");
  figure.stamp(plot::Stamp{.kernel = "M4",
                           .neighbours = 64,
                           .particles = runs[0].particles,
                           .extra = "R = M = G = 1, u = 0.05, \\gamma = 5/3; tree gravity, "
                                    "softening = " +
                                    softening + "; " + integration});
  const double t_end = runs[0].t.back();
  for (std::size_t k = 0; k < runs.size(); ++k) {
    plot::Axes& ax = figure.panel(static_cast<int>(k));
    ax.title(runs[k].name + " viscosity").xlabel("t  [code units]").ylabel("energy  [code units]");
    ax.xlim(0, t_end).ylim(-3.8, 2.6);
    evrard_figure_detail::draw_energies(ax, runs[k], ref);
  }
  plot::Axes& ax = figure.panel(3);
  ax.title(fixed ? "total energy: the cost of softening with h"
                 : "total energy: softening " + softening + ", " + integration)
      .xlabel("t  [code units]")
      .ylabel("[E_{tot}(t) - E_{tot}(0)] / |E_{tot}(0)|")
      .xlim(0, t_end);
  evrard_figure_detail::draw_energy_change(ax, runs, softening, fixed, fixed_softening);
  figure.save_png(path);
}

/// Draws the radial velocity, density and pressure of every particle of \p run at t = 0.8
/// against its distance from the centre of mass, over the finite-volume reference of \p ref,
/// under the title \p title, with the run's softening \p softening ("h" or a length) and
/// \p integration (how it was integrated) in the stamp; writes the PNG to \p path.
inline void save_evrard_profile_figure(const std::string& path, const EvrardRun& run,
                                       const EvrardReference& ref, const std::string& title,
                                       const std::string& softening,
                                       const std::string& integration) {
  const RadialProfile prof = radial_profile(run.at_08, run.centre_08);
  plot::Figure figure(1, 3, {.width = 1800, .height = 640});
  figure.title(title);
  figure.stamp(plot::Stamp{.kernel = "M4",
                           .neighbours = 64,
                           .particles = run.particles,
                           .run_time = run.seconds_08,
                           .extra = "t = 0.8; tree gravity, softening = " + softening + "; " +
                                    integration + "; reference: 1D finite volume, 8000 cells"});
  const std::vector<double>* particle_values[] = {&prof.v, &prof.rho, &prof.pressure};
  const std::vector<double>* reference_values[] = {&ref.v, &ref.rho, &ref.pressure};
  const char* labels[] = {"v_r  [code units]", "\\rho  [code units]", "P  [code units]"};
  const char* titles[] = {"radial velocity", "density", "pressure"};
  /// The radius axis is logarithmic, so that the core and the shock get as much room as the
  /// infalling envelope; so are density and pressure, which span decades from the core out.
  for (int panel = 0; panel < 3; ++panel) {
    plot::Axes& ax = figure.panel(panel);
    ax.xscale(plot::Scale::log).xlim(0.005, 1.2).xlabel("r  [code units]").ylabel(labels[panel]);
    ax.title(titles[panel]);
    if (panel == 0) {
      ax.ylim(-1.9, 0.6);
    } else {
      ax.yscale(plot::Scale::log);
      ax.ylim(panel == 1 ? 0.05 : 1e-3, panel == 1 ? 3e3 : 1e3);
    }
    ax.scatter(prof.r, *particle_values[panel],
               {.label = "SPH particles",
                .color = plot::Color{0.25, 0.25, 0.25},
                .size = 2.0,
                .alpha = 0.6});
    ax.line(ref.r, *reference_values[panel],
            {.label = "1D reference", .color = plot::red, .width = 2.2});
    ax.legend(plot::Corner::upper_right);
  }
  figure.save_png(path);
}

}  // namespace app
