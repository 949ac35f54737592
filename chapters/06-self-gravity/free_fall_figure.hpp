#pragma once
/// \file
/// \brief The free-fall figure: the radii of three mass shells of a collapsing cold sphere
/// against the analytic collapse, and their relative error.
///
/// Left panel: each shell's radius over its starting radius, \f$ r/r_0 \f$, every 40th record
/// as markers, over the analytic \f$ r/r_0 = \cos^2\beta \f$ that every shell of a uniform
/// pressureless sphere follows.  Right panel: the relative error of each shell, with a dotted
/// line at 0.9 \f$ t_\mathrm{ff} \f$, beyond which the shells come within a few softening
/// lengths of the centre.
///
/// Header-only: the program that includes it links sph_plot.

#include "plot/figure.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace app {

/// A recorded free fall: the record times in units of the free-fall time, the analytic
/// \f$ r/r_0 \f$ at those times, and the measured \f$ r/r_0 \f$ of the shells holding 10 %,
/// 50 % and 75 % of the mass.
struct FreeFallHistory {
  std::vector<double> t, exact, ratio[3];
};

/// Draws the free fall \p history of \p particles particles (pressureless, softening 0.02, a
/// fixed step of \f$ t_\mathrm{ff}/1000 \f$, a tree at opening angle \p theta) and writes the
/// PNG to \p path.
inline void save_free_fall_figure(const std::string& path, const FreeFallHistory& history,
                                  int particles, double theta) {
  const std::vector<double>& t = history.t;
  const std::vector<double>& exact = history.exact;
  const auto& ratio = history.ratio;
  plot::Figure figure(1, 2, {.width = 1600, .height = 700});
  figure.title("Free fall of a cold uniform sphere: the tree against the analytic collapse");
  char extra[128];
  std::snprintf(extra, sizeof extra,
                "no pressure; softening 0.02; fixed step t_{ff}/1000; \\theta = %.2g", theta);
  figure.stamp(plot::Stamp{.kernel = "M4", .particles = particles, .extra = extra});
  const plot::Color colors[] = {plot::red, plot::blue, plot::green};
  const char* names[] = {"10 % of the mass", "50 %", "75 %"};
  /// The analytic curve is drawn wide and first, so that the shells' markers, which lie on it
  /// almost to the end of the fall, stay visible on top of it.
  plot::Axes& left = figure.panel(0);
  left.xlabel("t / t_{ff}").ylabel("r / r_0").xlim(0, 1).ylim(0, 1.05).title("shell radii");
  left.line(t, exact, {.label = "analytic r/r_0 = cos^2\\beta", .color = plot::black, .width = 4});
  for (int k = 0; k < 3; ++k) {
    std::vector<double> ts, rs;  // every 40th step as markers
    for (std::size_t i = 0; i < t.size(); i += 40) {
      ts.push_back(t[i]);
      rs.push_back(ratio[k][i]);
    }
    left.scatter(ts, rs,
                 {.label = names[k],
                  .color = colors[k],
                  .size = 7,
                  .marker = k == 0 ? plot::Marker::circle
                                   : (k == 1 ? plot::Marker::square : plot::Marker::triangle)});
  }
  left.legend(plot::Corner::lower_left);
  plot::Axes& right = figure.panel(1);
  right.xlabel("t / t_{ff}").ylabel("(r/r_0) / analytic - 1").xlim(0, 1).title("relative error");
  for (int k = 0; k < 3; ++k) {
    std::vector<double> e(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) e[i] = ratio[k][i] / exact[i] - 1;
    right.line(t, e, {.label = names[k], .color = colors[k], .width = 1.8});
  }
  right.vline(0.9, {.color = plot::Color{0.6, 0.6, 0.6}, .style = plot::Dash::dotted});
  right.legend(plot::Corner::lower_left);
  figure.save_png(path);
}

}  // namespace app
