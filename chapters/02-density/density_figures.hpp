#pragma once
/// \file
/// \brief The figures of the static density tests: the density of particle sets against a
/// coordinate (the form of Watkins et al. 1996, Figs 1a and 3a) beside the history of a
/// relaxation; the density bias of lattices against \f$ \eta = h/\Delta x \f$; and the density
/// error of uniform sets against the time of the density step.
///
/// The chapter decides what is compared -- which sets, which lattices, which reference lines --
/// and these functions draw it:
///
/// \code
/// app::save_density_against_y_figure<3>(path, title, stamp,
///     {glass, "settled", 0.98, 1.02, "settled: mean 0.9988"},
///     {random, "random", 0, 2.2, "random: mean 1.004"},
///     {{"P \\propto \\rho^2", report.history}}, {0.004, "paper: \\sigma = 0.004"});
/// \endcode
///
/// Header-only: a chapter that includes it links sph_plot.

#include "app/error_figure.hpp"
#include "plot/figure.hpp"
#include "sph/measures/convergence.hpp"
#include "sph/particles.hpp"

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace app {

/// A horizontal reference line with its legend, e.g. a value quoted from a paper.
struct ReferenceLine {
  double value;       ///< where it is drawn
  std::string label;  ///< legend text (markup)
};

/// One panel of the density-against-y figure: a particle set and how it is labelled.
template <int D>
struct DensityPanel {
  const sph::Particles<D>& particles;  ///< the positions (their y) and densities drawn
  std::string label;                   ///< legend of the particles
  double low;                          ///< the density axis starts here ...
  double high;                         ///< ... and ends here
  std::string title;                   ///< the panel's title (markup)
};

/// One relaxation in the third panel: its legend and \f$ \sigma_\rho/\bar\rho \f$ at every
/// iteration.
struct RelaxationCurve {
  std::string label;                   ///< legend text (markup)
  const std::vector<double>& history;  ///< one value per iteration
};

/// The coordinate \p axis of every particle of \p p.
template <int D>
std::vector<double> coordinate(const sph::Particles<D>& p, int axis) {
  std::vector<double> v;
  for (const auto& x : p.position) v.push_back(x[axis]);
  return v;
}

/// Draws one set's density against y, with the line \f$ \rho = 1 \f$.
template <int D>
void draw_density_against_y(plot::Axes& axes, const DensityPanel<D>& panel) {
  axes.scatter(coordinate(panel.particles, 1), panel.particles.density,
               {.label = panel.label, .color = plot::black, .size = 2.5});
  axes.hline(1.0, {.label = "\\rho = 1", .color = plot::red, .style = plot::Dash::dashed});
  axes.xlabel("y [box lengths]")
      .ylabel("\\rho [mean density]")
      .xlim(0, 1)
      .ylim(panel.low, panel.high)
      .legend(plot::Corner::upper_right);
  axes.title(panel.title);
}

/// Three panels in a row -- the densities of \p left and \p middle against y, and the
/// relative scatter of the \p relaxations against the iteration on a log scale with the
/// reference line \p paper -- written as a PNG to \p path.
template <int D>
void save_density_against_y_figure(const std::string& path, const std::string& title,
                                   const plot::Stamp& stamp, const DensityPanel<D>& left,
                                   const DensityPanel<D>& middle,
                                   const std::vector<RelaxationCurve>& relaxations,
                                   const ReferenceLine& paper) {
  plot::Figure figure(1, 3, {.width = 2100, .height = 650});
  figure.title(title);
  figure.stamp(stamp);
  draw_density_against_y(figure.panel(0), left);
  draw_density_against_y(figure.panel(1), middle);
  // The relaxations, in the colours blue, black, red, ...
  plot::Axes& c = figure.panel(2);
  const plot::Color colours[] = {plot::blue, plot::black, plot::red};
  for (std::size_t k = 0; k < relaxations.size(); ++k) {
    std::vector<double> iteration;
    for (std::size_t i = 0; i < relaxations[k].history.size(); ++i)
      iteration.push_back(static_cast<double>(i));
    c.line(iteration, relaxations[k].history,
           {.label = relaxations[k].label, .color = colours[k % 3], .width = 2.0});
  }
  c.hline(paper.value, {.label = paper.label, .color = plot::grey, .style = plot::Dash::dashed});
  c.xlabel("relaxation iteration")
      .ylabel("\\sigma_\\rho / mean \\rho")
      .yscale(plot::Scale::log)
      .legend(plot::Corner::upper_right);
  c.title("settling the random set");
  figure.save_png(path);
}

/// The density bias of one lattice at every \f$ \eta \f$ of a scan.
struct LatticeBiasCurve {
  std::string label;         ///< legend text, e.g. "3D bcc"
  std::vector<double> bias;  ///< \f$ \rho_{\rm SPH}/\rho_0 - 1 \f$, one per \f$ \eta \f$
};

/// A marked point of the signed panel, with a dotted vertical line through it.
struct MarkedPoint {
  double x;           ///< \f$ \eta \f$
  double y;           ///< the bias there, in per cent
  std::string label;  ///< legend text (markup)
};

/// Two panels against \f$ \eta \f$ (the entries of \p eta): (a) the signed bias of every
/// lattice in per cent with the point \p mark, (b) its magnitude on a log scale with the
/// reference curve \p bound_label, \p bound (in per cent) -- written as a PNG to \p path.
inline void save_lattice_bias_figure(const std::string& path, const std::string& title,
                                     const plot::Stamp& stamp, const std::vector<double>& eta,
                                     const std::vector<LatticeBiasCurve>& lattices,
                                     const MarkedPoint& mark, const std::string& bound_label,
                                     const std::vector<double>& bound) {
  plot::Figure figure(1, 2, {.width = 1700, .height = 700});
  figure.title(title);
  figure.stamp(stamp);
  // Every lattice in both panels: signed on the left, its magnitude on the right.
  const plot::Color colours[] = {plot::black, plot::red, plot::orange, plot::blue, plot::cyan};
  const plot::Dash dashes[] = {plot::Dash::solid, plot::Dash::solid, plot::Dash::dashed,
                               plot::Dash::solid, plot::Dash::dashed};
  for (int panel = 0; panel < 2; ++panel) {
    for (std::size_t c = 0; c < lattices.size(); ++c) {
      std::vector<double> percent;
      for (double b : lattices[c].bias) percent.push_back(panel == 0 ? 100 * b : 100 * std::abs(b));
      figure.panel(panel).line(eta, percent,
                               {.label = panel == 0 ? lattices[c].label : "",
                                .color = colours[c % 5],
                                .style = dashes[c % 5],
                                .width = 2.0});
    }
    figure.panel(panel).xlabel("\\eta = h / \\Delta x  (mean spacing \\Delta x)").xlim(0.9, 2.4);
  }
  /// Panel (a) adds the zero line and the marked point of the text; panel (b), on a log scale,
  /// adds the 1D bound of Step 4.  Its curves share the colours of (a), which is why the loop
  /// above gives a legend only to the first panel.
  // (a): zero, the mark and its vertical.
  plot::Axes& a = figure.panel(0);
  a.hline(0.0, {.color = plot::grey, .style = plot::Dash::dotted, .width = 1.0});
  a.vline(mark.x, {.color = plot::grey, .style = plot::Dash::dotted, .width = 1.0});
  const std::vector<double> mark_x = {mark.x}, mark_y = {mark.y};
  a.scatter(mark_x, mark_y, {.label = mark.label, .color = plot::black, .size = 10.0});
  a.ylabel("\\rho_{SPH}/\\rho_0 - 1  [%]").ylim(-0.8, 0.8).legend(plot::Corner::upper_right);
  // (b): the reference curve.
  plot::Axes& b = figure.panel(1);
  b.line(eta, bound,
         {.label = bound_label, .color = plot::grey, .style = plot::Dash::dotted, .width = 2.0});
  b.ylabel("|\\rho_{SPH}/\\rho_0 - 1|  [%]  (colours as in a)")
      .yscale(plot::Scale::log)
      .ylim(1e-4, 10)
      .legend(plot::Corner::upper_right);
  figure.save_png(path);
}

/// The error-against-time figure of \p study (app::error_figure) with \p title and \p stamp,
/// its first two panels' error axes set to [\p low0, 1e-2] and [\p low1, 1e-2] with the legend
/// in the lower right, under the lines -- written as a PNG to \p path.
inline void save_density_cost_figure(const std::string& path, const sph::ErrorVsTime& study,
                                     const std::string& title, const std::string& stamp,
                                     double low0, double low1) {
  ErrorFigureOptions options;
  options.stamp = stamp;
  options.title = title;
  plot::Figure figure = error_figure(study, options);
  figure.panel(0).ylim(low0, 1e-2).legend(plot::Corner::lower_right);
  figure.panel(1).ylim(low1, 1e-2).legend(plot::Corner::lower_right);
  figure.save_png(path);
}

}  // namespace app
