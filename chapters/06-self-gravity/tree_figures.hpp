#pragma once
/// \file
/// \brief The two figures of a gravity tree measured against direct summation: its force error
/// against the opening angle and against its cost (app::save_tree_accuracy_figure), and the
/// cost of one evaluation against the number of particles (app::save_tree_cost_figure).
///
/// The first is the figure a reader needs to choose the opening angle \f$ \theta \f$: the 99th
/// percentile and the largest relative force error, for monopoles (red) and quadrupoles (blue),
/// against \f$ \theta \f$ (left) and against the time of one evaluation relative to direct
/// summation (right), with the two accuracy targets as dotted lines; on the right also the relative
/// criterion (green, quadrupoles, one point for each \f$ \alpha \f$).  The second draws the wall
/// times of both methods on log-log axes with \f$ N^2 \f$ and \f$ N\log N \f$ guides through their
/// middle points.
///
/// Header-only: the program that includes it links sph_plot.

#include "plot/figure.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace app {

/// The force error of a tree at one opening angle and multipole order, against direct
/// summation on the same particles: the quantiles of the relative error
/// \f$ |\mathbf a_\mathrm{tree} - \mathbf a_\mathrm{direct}|/|\mathbf a_\mathrm{direct}| \f$
/// over the particles, and what the evaluation cost.
struct TreeAccuracy {
  double theta = 0;        ///< the opening angle
  double alpha = 0;        ///< alpha of the relative criterion (0: the geometric one, at theta)
  bool quadrupole = true;  ///< false: monopoles only
  double p50 = 0, p90 = 0, p99 = 0, max = 0;  ///< median, 90th, 99th percentile, maximum
  double potential = 0;                       ///< relative error of the potential energy
  double relative_time = 0;                   ///< the tree's wall time over direct summation's
  double interactions = 0;                    ///< particle and node interactions, per particle
  double net_force = 0;                       ///< \f$ |\sum m\mathbf a| / \sum m|\mathbf a| \f$
};

namespace tree_accuracy_detail {

/// A 99th percentile (filled circles) and a maximum (open squares) against measured times:
/// markers only, since the times are noisy.
inline void scatter_errors(plot::Axes& ax, const std::vector<double>& x,
                           const std::vector<double>& p99, const std::vector<double>& max,
                           const std::string& name, plot::Color color) {
  ax.scatter(x, p99, {.label = name + ", 99th percentile", .color = color, .size = 9});
  ax.scatter(x, max,
             {.label = name + ", maximum",
              .color = color,
              .size = 9,
              .marker = plot::Marker::square,
              .filled = false});
}

/// One multipole order's 99th percentile and maximum error, against the opening angle
/// (\p against_theta, lines) or against the relative time (markers: measured times are noisy).
inline void draw_order(plot::Axes& ax, const std::vector<TreeAccuracy>& rows, bool quadrupole,
                       bool against_theta) {
  std::vector<double> x, p99, max;
  for (const TreeAccuracy& r : rows) {
    if (r.quadrupole != quadrupole || r.alpha > 0) continue;
    x.push_back(against_theta ? r.theta : r.relative_time);
    p99.push_back(r.p99);
    max.push_back(r.max);
  }
  const plot::Color color = quadrupole ? plot::blue : plot::red;
  const std::string name = quadrupole ? "quadrupole" : "monopole";
  if (against_theta) {
    ax.line(x, p99,
            {.label = name + ", 99th percentile",
             .color = color,
             .width = 2,
             .marker = plot::Marker::circle,
             .marker_size = 7});
    ax.line(x, max,
            {.label = name + ", maximum",
             .color = color,
             .style = plot::Dash::dashed,
             .width = 1.5,
             .marker = plot::Marker::square,
             .marker_size = 6,
             .marker_filled = false});
  } else {
    scatter_errors(ax, x, p99, max, name, color);
  }
}

/// The relative criterion's 99th percentile and maximum error against the relative time.
inline void draw_relative(plot::Axes& ax, const std::vector<TreeAccuracy>& rows) {
  std::vector<double> x, p99, max;
  for (const TreeAccuracy& r : rows) {
    if (!(r.alpha > 0)) continue;
    x.push_back(r.relative_time);
    p99.push_back(r.p99);
    max.push_back(r.max);
  }
  if (!x.empty()) scatter_errors(ax, x, p99, max, "relative criterion", plot::green);
}

}  // namespace tree_accuracy_detail

/// Draws the tree's error against the opening angle (left) and against its relative cost
/// (right) for the rows of \p rows, measured on \p particles particles, with a grey line at
/// the default opening angle \p default_theta; writes the PNG to \p path.
inline void save_tree_accuracy_figure(const std::string& path,
                                      const std::vector<TreeAccuracy>& rows, int particles,
                                      double default_theta) {
  plot::Figure figure(1, 2, {.width = 1600, .height = 700});
  figure.title("The tree against direct summation: force error, Evrard sphere at t = 0");
  figure.stamp(plot::Stamp{.kernel = "M4",
                           .neighbours = 64,
                           .particles = particles,
                           .extra = "softening = h; relative error |a_{tree} - a_{direct}| / "
                                    "|a_{direct}|; grey line: the default \\theta"});
  for (int panel = 0; panel < 2; ++panel) {
    plot::Axes& ax = figure.panel(panel);
    ax.yscale(plot::Scale::log).ylabel("relative force error");
    if (panel == 0) {
      ax.xlabel("opening angle \\theta").title("error against \\theta");
    } else {
      ax.xscale(plot::Scale::log)
          .xlabel("time of one evaluation / direct summation's")
          .title("error against cost");
    }
    for (bool quadrupole : {false, true})
      tree_accuracy_detail::draw_order(ax, rows, quadrupole, panel == 0);
    if (panel == 1) tree_accuracy_detail::draw_relative(ax, rows);
    ax.hline(3e-3, {.label = "targets: 99th percentile 3\\times10^{-3}, maximum 7\\times10^{-3}",
                    .color = plot::Color{0.45, 0.45, 0.45},
                    .style = plot::Dash::dotted});
    ax.hline(7e-3, {.color = plot::Color{0.45, 0.45, 0.45}, .style = plot::Dash::dotted});
    if (panel == 0) {
      ax.vline(default_theta, {.color = plot::Color{0.6, 0.6, 0.6}});
      ax.legend(plot::Corner::lower_right);
    } else {
      ax.legend(plot::Corner::upper_right);
    }
  }
  figure.save_png(path);
}

namespace tree_cost_detail {

/// Guides through the middle points of the measured times: \f$ \propto N^2 \f$ through direct
/// summation's (\p nd, \p td), \f$ \propto N\log N \f$ through the tree's (\p nt, \p tt).
inline void draw_guides(plot::Axes& ax, const std::vector<double>& nd,
                        const std::vector<double>& td, const std::vector<double>& nt,
                        const std::vector<double>& tt) {
  std::vector<double> guide_n = {nt.front(), nt.back()}, g2(2), gl(2);
  const std::size_t md = nd.size() / 2, mt = nt.size() / 2;
  for (int k = 0; k < 2; ++k) {
    g2[k] = td[md] * std::pow(guide_n[k] / nd[md], 2);
    gl[k] = tt[mt] * guide_n[k] * std::log(guide_n[k]) / (nt[mt] * std::log(nt[mt]));
  }
  std::vector<double> fine_n, fine_l;
  for (double n = guide_n[0]; n <= guide_n[1] * 1.001; n *= 1.2) {
    fine_n.push_back(n);
    fine_l.push_back(tt[mt] * n * std::log(n) / (nt[mt] * std::log(nt[mt])));
  }
  ax.line(
      guide_n, g2,
      {.label = "\\propto N^2", .color = plot::Color{0.5, 0.5, 0.5}, .style = plot::Dash::dashed});
  ax.line(fine_n, fine_l,
          {.label = "\\propto N log N",
           .color = plot::Color{0.5, 0.5, 0.5},
           .style = plot::Dash::dotted});
}

}  // namespace tree_cost_detail

/// Draws the wall time of one evaluation against the number of particles \p counts, for direct
/// summation (\p direct_seconds; a negative entry: not run) and for the tree with quadrupoles
/// at opening angle \p theta (\p tree_seconds), with \f$ N^2 \f$ and \f$ N\log N \f$ guides;
/// writes the PNG to \p path.
inline void save_tree_cost_figure(const std::string& path, const std::vector<int>& counts,
                                  const std::vector<double>& direct_seconds,
                                  const std::vector<double>& tree_seconds, double theta) {
  plot::Figure figure(1, 1, {.width = 1000, .height = 760});
  figure.title("The cost of self-gravity against the number of particles");
  char extra[128];
  std::snprintf(extra, sizeof extra,
                "softening = h; Evrard sphere; tree with quadrupoles at \\theta = %.2g; 2 threads",
                theta);
  figure.stamp(plot::Stamp{.kernel = "M4", .neighbours = 64, .extra = extra});
  plot::Axes& ax = figure.panel(0);
  ax.xscale(plot::Scale::log).yscale(plot::Scale::log);
  ax.xlabel("N  [particles]").ylabel("wall time of one evaluation  [s]");
  /// Direct summation's points stop where it was not run (a negative time); the tree's go on
  /// to the largest N.
  std::vector<double> nd, td, nt, tt;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    if (direct_seconds[k] > 0) {
      nd.push_back(counts[k]);
      td.push_back(direct_seconds[k]);
    }
    nt.push_back(counts[k]);
    tt.push_back(tree_seconds[k]);
  }
  ax.line(nd, td,
          {.label = "direct summation",
           .color = plot::red,
           .width = 2,
           .marker = plot::Marker::circle,
           .marker_size = 8});
  ax.line(nt, tt,
          {.label = "tree",
           .color = plot::blue,
           .width = 2,
           .marker = plot::Marker::square,
           .marker_size = 8});
  tree_cost_detail::draw_guides(ax, nd, td, nt, tt);
  ax.legend(plot::Corner::upper_left);
  figure.save_png(path);
}

}  // namespace app
