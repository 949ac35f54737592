#pragma once
/// \file
/// \brief The figure of Step 8: the thermal and the kinetic energy of the Evrard collapse
/// against time, one curve per viscosity, over the one-dimensional reference.
///
/// Header-only: the program that includes it links sph_plot.

#include "app/evrard_run.hpp"
#include "plot/figure.hpp"

#include <string>
#include <vector>

namespace app::bulk {

/// One curve of the figure: a run, its colour, and whether it is dashed (a run that repeats
/// another with other numerics, drawn over it).
struct CollapseCurve {
  const EvrardRun* run;
  plot::Color color;
  bool dashed = false;
};

/// Draws the thermal energy (left) and the kinetic energy (right) of every run in \p curves
/// against time over the 1D reference \p reference, a wide grey line.  \p neighbours goes into
/// the stamp; writes the PNG to \p path.
inline void save_collapse_figure(const std::string& path, const std::vector<CollapseCurve>& curves,
                                 const EvrardLagrangian& reference, double neighbours) {
  plot::Figure figure(1, 2, {.width = 1600, .height = 700});
  figure.title("Evrard collapse: the bulk viscosity against the standard viscosity");
  const EvrardRun& first = *curves.front().run;
  figure.stamp(plot::Stamp{.kernel = "M4",
                           .neighbours = neighbours,
                           .particles = first.particles,
                           .extra = "R = M = G = 1, u = 0.05, \\gamma = 5/3; tree gravity, "
                                    "softening = h"});
  const std::vector<double> EvrardRun::*series[] = {&EvrardRun::thermal, &EvrardRun::kinetic};
  const std::vector<double>* reference_series[] = {&reference.thermal, &reference.kinetic};
  const char* names[] = {"thermal energy", "kinetic energy"};
  const char* ylabels[] = {"E_{th}  [code units]", "E_{kin}  [code units]"};
  for (int panel = 0; panel < 2; ++panel) {
    plot::Axes& ax = figure.panel(panel);
    ax.title(names[panel]).xlabel("t  [code units]").ylabel(ylabels[panel]);
    ax.xlim(0, first.t.back());
    ax.line(
        reference.t, *reference_series[panel],
        {.label = "1D Lagrangian reference", .color = plot::Color{0.72, 0.72, 0.72}, .width = 7});
    for (const CollapseCurve& c : curves) {
      ax.line(c.run->t, (*c.run).*series[panel],
              {.label = c.run->name,
               .color = c.color,
               .style = c.dashed ? plot::Dash::dashed : plot::Dash::solid,
               .width = c.dashed ? 2.5 : 2});
    }
    ax.legend(plot::Corner::upper_left);
  }
  figure.save_png(path);
}

}  // namespace app::bulk
