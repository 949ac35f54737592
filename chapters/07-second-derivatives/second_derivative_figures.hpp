#pragma once
/// \file
/// \brief The figures of the static tests of second derivatives (chapter 7): the paper's
/// four-panel form, the compressive field, and the three summary figures (errors against the
/// noise, against the disorder, and against the resolution and run time).
///
/// Every figure takes the records of `second_derivative_tests.hpp` (shown before Step 1) and
/// draws each method in its own colour, marker and dash (app::second_derivatives::method_style), so
/// that the same method looks the same in all of them.  Each is stamped with the scheme (constant
/// h, gather density), the kernel and the particle and neighbour numbers, and saved through
/// app::Chapter::figure_path.
///
/// Header-only: a chapter that includes it links sph_plot.

#include "app/chapter.hpp"
#include "second_derivative_tests.hpp"
#include "app/text.hpp"
#include "plot/figure.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace app::second_derivatives {

/// A figure in the paper's form: (a) a quantity \p panel_a at the particles against y,
/// (b)-(d) the x-component of the second derivative from the first three \p results (Watkins,
/// Flebbe and Brookshaw), particles as dots and the analytic curve as a line.  \p extra is added
/// to the stamp.
template <int D>
void four_panel_figure(const app::Chapter& chapter, const std::string& file,
                       const std::string& title, const StaticSet<D>& s,
                       const std::vector<double>& panel_a, const std::string& panel_a_label,
                       const std::vector<MethodResult<D>>& results, Operator op,
                       const std::string& extra) {
  plot::Figure figure(2, 2, {.width = 1500, .height = 1200});
  figure.title(title);
  figure.stamp(plot::Stamp{.scheme = "constant h, gather density" +
                                     std::string(s.self_term ? "" : " without the self term"),
                           .kernel = "M4",
                           .neighbours = s.neighbours,
                           .particles = static_cast<long long>(s.p.size()),
                           .extra = extra + "; rms |error| over all components"});
  const int axis = op == Operator::curl_curl ? 1 : 0;
  const std::string along = axis == 1 ? "y" : "x";
  const std::vector<double> y = s.coordinate(axis);
  std::vector<double> ye(401), exact(401);
  for (int k = 0; k <= 400; ++k) {
    ye[k] = k / 400.0;
    exact[k] = op == Operator::curl_curl ? k2 * std::sin(two_pi * ye[k]) : 0.0;
  }
  plot::Axes& a = figure.panel(0, 0);
  a.xlabel(along + "  [box lengths]").ylabel(panel_a_label + "  [code units]").xlim(0, 1);
  a.title(panel_a_label + " at the particles");
  a.scatter(y, panel_a, {.color = plot::black, .size = 2.0});
  /// Panels (b)-(d) then share one y range, so that each method's scatter is judged at the
  /// others' scale.  Each draws one method's x-component at the particles against the analytic
  /// curve; its title carries the rms of the whole error vector, y and z components included.
  // the common y range of panels (b)-(d): the analytic range with a margin, widened to the
  // results' 0.5 and 99.5 percentiles (a few outliers must not squash the curve)
  double lo = -1.3 * k2, hi = 1.3 * k2;
  for (const auto& r : results) {
    std::vector<double> sorted = r.x_component;
    std::sort(sorted.begin(), sorted.end());
    lo = std::min(lo, sorted[sorted.size() / 200]);
    hi = std::max(hi, sorted[sorted.size() - 1 - sorted.size() / 200]);
  }
  hi += 0.25 * (hi - lo);  // (room above the data for the legends of the upper right)
  const std::string quantity = "(\\nabla\\times\\nabla\\times v)_x";
  for (std::size_t k = 0; k < results.size() && k < 3; ++k) {
    const MethodResult<D>& r = results[k];
    plot::Axes& ax = figure.panel(static_cast<int>((k + 1) / 2), static_cast<int>((k + 1) % 2));
    ax.xlabel(along + "  [box lengths]").ylabel(quantity + "  [code units]").xlim(0, 1);
    ax.ylim(lo, hi);
    ax.title(std::string(name(r.method)) + ": rms |error| " + app::format("%.3f", r.errors.rms) +
             " \\times 4\\pi^2");
    ax.scatter(y, r.x_component, {.label = "particles", .color = color(r.method), .size = 2.0});
    ax.line(ye, exact,
            {.label = op == Operator::curl_curl ? "analytic 4\\pi^2 sin 2\\pi y" : "analytic 0",
             .color = plot::black,
             .width = 2});
    ax.legend(plot::Corner::upper_right);
  }
  figure.save_png(chapter.figure_path(file).string());
}

/// The figure of the compressive field \f$ v_x = \sin 2\pi x \f$ (velocities \p v) on \p s:
/// (a) \f$ v_x \f$ against x, (b)-(c) the gradient of the divergence by Watkins and Flebbe
/// (rows 0 and 2 of \p rows, in the order of all_methods), and (d) Brookshaw's curl curl
/// \p brookshaw_cc, whose exact value is zero, with its rms error \p brookshaw_rms.
template <int D>
void compression_figure(const app::Chapter& chapter, const StaticSet<D>& s,
                        const std::vector<Vec<D>>& v, const std::vector<MethodResult<D>>& rows,
                        const std::vector<Vec<D>>& brookshaw_cc, double brookshaw_rms) {
  plot::Figure fig(2, 2, {.width = 1500, .height = 1200});
  fig.title("A compressive field v_x = sin 2\\pi x (" + std::to_string(D) +
            "D settled set): Brookshaw's Laplacian is not the curl curl");
  fig.stamp(plot::Stamp{.scheme = "constant h, gather density",
                        .kernel = "M4",
                        .neighbours = s.neighbours,
                        .particles = static_cast<long long>(s.p.size()),
                        .extra = "\\nabla(\\nabla\\cdot v) = (-4\\pi^2 sin 2\\pi x, 0, 0), "
                                 "\\nabla\\times\\nabla\\times v = 0"});
  const std::vector<double> x = s.coordinate(0);
  std::vector<double> xe(401), gd(401), zero(401, 0.0);
  for (int k = 0; k <= 400; ++k) {
    xe[k] = k / 400.0;
    gd[k] = -k2 * std::sin(two_pi * xe[k]);
  }
  std::vector<double> vx(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) vx[i] = v[i][0];
  plot::Axes& a = fig.panel(0, 0);
  a.xlabel("x  [box lengths]").ylabel("v_x  [code units]").xlim(0, 1);
  a.title("v_x at the particles");
  a.scatter(x, vx, {.color = plot::black, .size = 2.0});
  /// Panels (b) and (c) are Watkins' and Flebbe's gradient of the divergence on a fixed range
  /// about the analytic curve.  Panel (d), Brookshaw's Laplacian taken as a curl curl, gets the
  /// same range, so that its error -- all of its value, since the exact curl curl is zero -- is
  /// seen at the scale of the gradient of the divergence in (b) and (c).
  const double lo = -1.3 * k2, hi = 1.3 * k2;
  for (int k = 0; k < 2; ++k) {
    const MethodResult<D>& r = rows[k == 0 ? 0 : 2];  // Watkins, Flebbe
    plot::Axes& ax = fig.panel(k == 0 ? 0 : 1, k == 0 ? 1 : 0);
    ax.xlabel("x  [box lengths]").ylabel("(\\nabla(\\nabla\\cdot v))_x  [code units]");
    ax.xlim(0, 1).ylim(lo, hi);
    ax.title(std::string(name(r.method)) + ": rms error " + app::format("%.3f", r.errors.rms) +
             " \\times 4\\pi^2");
    ax.scatter(x, r.x_component, {.label = "particles", .color = color(r.method), .size = 2.0});
    ax.line(xe, gd, {.label = "analytic -4\\pi^2 sin 2\\pi x", .color = plot::black, .width = 2});
    ax.legend(plot::Corner::upper_left);  // (the curve's trough is there)
  }
  plot::Axes& d = fig.panel(1, 1);
  std::vector<double> bx(brookshaw_cc.size());
  for (std::size_t i = 0; i < bx.size(); ++i) bx[i] = brookshaw_cc[i][0];
  d.xlabel("x  [box lengths]").ylabel("(\\nabla\\times\\nabla\\times v)_x  [code units]");
  d.xlim(0, 1).ylim(lo, hi);
  d.title("Brookshaw, -\\nabla^2 v as the curl curl: rms error " +
          app::format("%.2f", brookshaw_rms) + " \\times 4\\pi^2");
  d.scatter(x, bx, {.label = "particles", .color = color(Method::brookshaw), .size = 2.0});
  d.line(xe, zero, {.label = "analytic 0", .color = plot::black, .width = 2});
  d.legend(plot::Corner::upper_right);
  fig.save_png(chapter.figure_path("compression_" + std::to_string(D) + "d.png").string());
}

/// The neighbour numbers the two figures below were run with, for their stamps.
inline std::string neighbour_note(double neighbours_2d, double neighbours_3d) {
  return "2D: " + format("%g", neighbours_2d) + " neighbours, 3D: " + format("%g", neighbours_3d);
}

/// The errors of every method against the velocity noise, 2D (\p n2) and 3D (\p n3) side by
/// side, log-log, with a line of slope one: `noise.png`.
inline void noise_figure(const app::Chapter& chapter, const NoiseStudy<2>& n2,
                         const NoiseStudy<3>& n3, int particles, double neighbours_2d,
                         double neighbours_3d) {
  plot::Figure figure(1, 2, {.width = 1600, .height = 700});
  figure.title("Errors against the velocity noise, settled sets, v_x = sin 2\\pi y");
  figure.stamp(plot::Stamp{.scheme = "constant h, gather density",
                           .kernel = "M4",
                           .particles = particles,
                           .extra = "uniform noise in [-\\epsilon, \\epsilon] on each velocity "
                                    "component, mean of 3 draws; " +
                                    neighbour_note(neighbours_2d, neighbours_3d)});
  auto draw = [&](plot::Axes& ax, const auto& study, const std::string& title) {
    ax.xscale(plot::Scale::log).yscale(plot::Scale::log);
    ax.xlabel("noise amplitude \\epsilon")
        .ylabel("rms error of \\nabla\\times\\nabla\\times v / 4\\pi^2");
    ax.title(title);
    // (Watkins, "own volume" and Flebbe nearly coincide: distinct markers and dashes)
    for (std::size_t k = 0; k < all_methods.size(); ++k) {
      std::vector<double> y;
      for (const auto& row : study.rms) y.push_back(row[k]);
      ax.line(study.amplitudes, y, method_style(all_methods[k]));
    }
    // slope one, a factor three below Watkins' last point: error proportional to the noise
    const double e = study.rms.back()[0] / 3, a = study.amplitudes.back();
    ax.line(std::vector<double>{a / 300, a}, std::vector<double>{e / 300, e},
            {.label = "\\propto \\epsilon", .color = plot::grey, .style = plot::Dash::dotted});
    ax.legend(plot::Corner::upper_left);
  };
  draw(figure.panel(0, 0), n2, "2D");
  draw(figure.panel(0, 1), n3, "3D");
  figure.save_png(chapter.figure_path("noise.png").string());
}

/// The errors of every method against the density scatter of the set, 2D (\p d2) and 3D
/// (\p d3) side by side, with the paper's two sets marked: `disorder.png`.
inline void disorder_figure(const app::Chapter& chapter, const DisorderStudy<2>& d2,
                            const DisorderStudy<3>& d3, int particles, double neighbours_2d,
                            double neighbours_3d) {
  plot::Figure figure(1, 2, {.width = 1600, .height = 700});
  figure.title("Errors against the particles' disorder, v_x = sin 2\\pi y");
  figure.stamp(plot::Stamp{.scheme = "constant h, gather density",
                           .kernel = "M4",
                           .particles = particles,
                           .extra = "glass moved by random offsets up to 2 spacings, then the "
                                    "Poisson set; densities with the self term, except the open "
                                    "markers (Fig 3's set without it); " +
                                    neighbour_note(neighbours_2d, neighbours_3d)});
  /// Each panel draws a curve per method through the disturbed glasses to the Poisson set, and
  /// the Poisson set as Fig 3 sums it, without the self term, as an open marker off the curve.
  /// On the 3D panel two vertical lines mark the density scatter of Watkins' own two sets.
  // (the paper's two sets are 3D: their scatter is marked on the 3D panel only)
  auto draw = [&](plot::Axes& ax, const auto& study, const std::string& title, bool paper_sets) {
    ax.xscale(plot::Scale::log).yscale(plot::Scale::log);
    ax.xlabel("density scatter \\sigma_\\rho / \\rho")
        .ylabel("rms error of \\nabla\\times\\nabla\\times v / 4\\pi^2");
    ax.title(title);
    for (std::size_t k = 0; k < all_methods.size(); ++k) {
      std::vector<double> y;
      for (const auto& row : study.rms) y.push_back(row[k]);
      ax.line(study.sigma, y, method_style(all_methods[k]));
      ax.scatter(std::vector<double>{study.paper_sigma}, std::vector<double>{study.paper_rms[k]},
                 {.label = k == 0 ? "Fig 3's set, no self term (open)" : "",
                  .color = color(all_methods[k]),
                  .size = 12,
                  .marker = method_style(all_methods[k]).marker,
                  .filled = false});
    }
    if (paper_sets) {
      ax.vline(0.004, {.label = "Watkins' settled set, \\sigma_\\rho = 0.004",
                       .color = plot::grey,
                       .style = plot::Dash::dotted});
      ax.vline(0.281, {.label = "Watkins' random set, \\sigma_\\rho = 0.281",
                       .color = plot::grey,
                       .style = plot::Dash::dashed});
    }
    ax.legend(plot::Corner::upper_left);
  };
  draw(figure.panel(0, 0), d2, "2D", false);
  draw(figure.panel(0, 1), d3, "3D", true);
  figure.save_png(chapter.figure_path("disorder.png").string());
}

/// The cost study in three panels: (a) error against N at a fixed neighbour number, with the
/// smoothing error's slope \f$ N^{-2/3} \f$; (b) error against the neighbour number; (c) error
/// against the wall time of one evaluation: `error_vs_cost.png`.
inline void cost_figure(const app::Chapter& chapter, const CostStudy& study) {
  plot::Figure figure(1, 3, {.width = 2100, .height = 700});
  figure.title(
      "Error against resolution and run time: curl curl of v_x = sin 2\\pi y, 3D "
      "settled sets");
  figure.stamp(
      plot::Stamp{.scheme = "constant h, gather density",
                  .kernel = "M4",
                  .extra = "times: one evaluation on " + std::to_string(omp_get_max_threads()) +
                           " threads, fastest of 3; (c) the series of (a), N = 1000 at the left"});
  plot::Axes& a = figure.panel(0, 0);
  plot::Axes& b = figure.panel(0, 1);
  plot::Axes& c = figure.panel(0, 2);
  a.xscale(plot::Scale::log).yscale(plot::Scale::log);
  a.xlabel("N").ylabel("rms error / 4\\pi^2").title("against N, 60 neighbours");
  b.xscale(plot::Scale::log).yscale(plot::Scale::log);
  b.xlabel("neighbour number N_{ngb}")
      .ylabel("rms error / 4\\pi^2")
      .title("against N_{ngb}, N = 5000");
  c.xscale(plot::Scale::log).yscale(plot::Scale::log);
  c.xlabel("wall time of one evaluation [s]").ylabel("rms error / 4\\pi^2");
  c.title("against run time, N = 1000 to " + std::to_string(study.by_n.back().particles));
  /// Every method gets one line in each panel, in its own style: the series against N gives
  /// panels (a) and (c), the series against the neighbour number panel (b).  Panel (a) also gets
  /// the slope the smoothing error alone would follow, \f$ N^{-2/3} \f$, through Watkins' first
  /// point: a curve that falls more slowly than the guide has met the glass's noise.
  for (std::size_t k = 0; k < all_methods.size(); ++k) {
    std::vector<double> n, en, g, eg, t, et;
    for (const auto& r : study.by_n) {
      n.push_back(r.particles);
      en.push_back(r.rms[k]);
      t.push_back(r.seconds[k]);
      et.push_back(r.rms[k]);
    }
    for (const auto& r : study.by_neighbours) {
      g.push_back(r.neighbours);
      eg.push_back(r.rms[k]);
    }
    const plot::LineOptions style = method_style(all_methods[k]);
    a.line(n, en, style);
    b.line(g, eg, style);
    c.line(t, et, style);
  }
  // the smoothing error's slope at a fixed neighbour number, N^(-2/3), through Watkins' first
  // point (the method whose error is the smoothing's; the others level off at their noise)
  if (!study.by_n.empty()) {
    const double n0 = study.by_n.front().particles, e0 = study.by_n.front().rms[0];
    const double n1 = study.by_n.back().particles;
    a.line(std::vector<double>{n0, n1}, std::vector<double>{e0, e0 * std::pow(n1 / n0, -2.0 / 3)},
           {.label = "\\propto N^{-2/3}", .color = plot::grey, .style = plot::Dash::dotted});
  }
  a.legend(plot::Corner::lower_left);
  b.legend(plot::Corner::lower_left);  // (Flebbe's 30-neighbour point is at the top left)
  c.legend(plot::Corner::upper_right);
  figure.save_png(chapter.figure_path("error_vs_cost.png").string());
}

}  // namespace app::second_derivatives
