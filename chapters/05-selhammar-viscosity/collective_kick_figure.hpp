#pragma once
/// \file
/// \brief The figure of one kick of Selhammar's collective term: (a) the speed after the kick
/// against \f$ k\delta t \f$, the explicit and the exact update, as formulas (lines) and as the
/// library computes them (markers); (b) the largest \f$ \eta \f$ for which the explicit kick
/// is monotone, against Mach number.
///
/// The chapter supplies the formulas and the library's numbers as callables, so that the
/// figure holds only the drawing; step1_stiffness(), just above, fills them in.
///
/// A speed is that of a particle of speed 1 whose neighbourhood comes at it with the speed
/// ratio \f$ |a|/w \f$; panel (a) draws the ratios 1 (head on, blue) and 0.1 (green), panel
/// (b) the ratios 1, 0.25 and 0.01, with the paper's \f$ \eta = 1 \f$ dashed.
///
/// Header-only: a chapter that includes it links sph_plot.

#include "plot/figure.hpp"

#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace app {

/// What the figure draws, each a function of \f$ k\delta t \f$ (or Mach number) and the speed
/// ratio \f$ |a|/w \f$.
struct CollectiveKickCurves {
  std::function<double(double, double)> explicit_speed;    ///< the explicit kick, as a formula
  std::function<double(double, double)> exact_speed;       ///< the exact update, as a formula
  std::function<double(double, double)> library_explicit;  ///< the explicit kick, as computed
  std::function<double(double, double)> library_exact;     ///< the exact update, as computed
  std::function<double(double, double)> stable_eta;        ///< of Mach number and ratio
  /// \f$ k\delta t \f$ values marked with a vertical line and a label in panel (a)
  std::vector<std::pair<std::string, double>> marks;
  std::string marks_caption;  ///< a label above the marks' labels
};

namespace collective_kick_detail {

/// Panel (a): lines for the formulas, markers for the library (hollow squares: explicit; dots:
/// exact), a line at zero speed, and the marks.
inline void draw_kick(plot::Axes& kick, const CollectiveKickCurves& curves) {
  kick.xlabel("k \\delta t").ylabel("w after one kick / w before").xlim(0, 12).ylim(-3, 1.1);
  const double ratios[] = {1.0, 0.1};
  const plot::Color colors[] = {plot::blue, plot::green};
  std::vector<double> kdt(241);
  for (std::size_t k = 0; k < kdt.size(); ++k) kdt[k] = 12.0 * double(k) / double(kdt.size() - 1);
  for (int r = 0; r < 2; ++r) {
    // The formulas on a fine grid.
    const double f = ratios[r];
    std::vector<double> explicit_w(kdt.size()), exact_w(kdt.size());
    for (std::size_t k = 0; k < kdt.size(); ++k) {
      explicit_w[k] = curves.explicit_speed(kdt[k], f);
      exact_w[k] = curves.exact_speed(kdt[k], f);
    }
    char label[96];
    std::snprintf(label, sizeof label, "explicit, |a|/w = %g", f);
    kick.line(kdt, explicit_w, {.label = label, .color = colors[r], .style = plot::Dash::dashed});
    std::snprintf(label, sizeof label, "exact, |a|/w = %g", f);
    kick.line(kdt, exact_w, {.label = label, .color = colors[r]});
    // The library's numbers at every unit step, from 0.5.
    std::vector<double> xs, lib_explicit, lib_exact;
    for (double x = 0.5; x <= 12; x += 1.0) {
      xs.push_back(x);
      lib_explicit.push_back(curves.library_explicit(x, f));
      lib_exact.push_back(curves.library_exact(x, f));
    }
    kick.scatter(xs, lib_explicit,
                 {.color = colors[r], .size = 9, .marker = plot::Marker::square, .filled = false});
    kick.scatter(xs, lib_exact, {.color = colors[r], .size = 9});
  }
  kick.hline(0.0);
  for (const auto& [label, at] : curves.marks) {
    kick.vline(at);
    kick.text(at + 0.12, -2.85, label);
  }
  kick.text(4.4, -2.5, curves.marks_caption);
  kick.legend(plot::Corner::upper_right);
}

/// Panel (b): the largest stable \f$ \eta \f$ against Mach number, log-log.
inline void draw_bound(plot::Axes& bound, const CollectiveKickCurves& curves) {
  bound.xlabel("Mach number w/c")
      .ylabel("largest stable \\eta")
      .xscale(plot::Scale::log)
      .yscale(plot::Scale::log);
  std::vector<double> mach;
  for (double m = 0.1; m <= 100.0; m *= 1.05) mach.push_back(m);
  const plot::Color bound_colors[] = {plot::black, plot::blue, plot::green};
  int curve = 0;
  for (double f : {1.0, 0.25, 0.01}) {
    std::vector<double> eta(mach.size());
    for (std::size_t k = 0; k < mach.size(); ++k) eta[k] = curves.stable_eta(mach[k], f);
    char label[64];
    std::snprintf(label, sizeof label, "|a|/w = %g", f);
    bound.line(mach, eta, {.label = label, .color = bound_colors[curve++]});
  }
  bound.hline(1.0,
              {.label = "the paper's \\eta = 1", .color = plot::red, .style = plot::Dash::dashed});
  bound.legend(plot::Corner::upper_left);
}

}  // namespace collective_kick_detail

/// Draws the two panels of \p curves and writes the figure to \p path.
inline void save_collective_kick_figure(const CollectiveKickCurves& curves,
                                        const std::string& path) {
  plot::Figure figure(1, 2, {.width = 1500, .height = 620});
  figure.title("The collective term (eq 16): one kick, explicit and exact");
  figure.stamp(plot::Stamp{.scheme = "Selhammar (1997) collective term", .extra = "N_n = 64"});
  collective_kick_detail::draw_kick(figure.panel(0), curves);
  collective_kick_detail::draw_bound(figure.panel(1), curves);
  figure.save_png(path);
}

}  // namespace app
