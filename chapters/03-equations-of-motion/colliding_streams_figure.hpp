#pragma once
/// \file
/// \brief The colliding-streams figure: x-t diagrams of the particle paths that
/// app::run_colliding_streams recorded, one panel per run, and the final densities against the
/// exact solution in a fourth.
///
/// In an x-t diagram the right-moving stream is drawn in blue and the left-moving one in red, so
/// that crossing paths are particles passing through each other.  A run that stopped early ends
/// at a dotted line marked with the time it reached.
///
/// \code
/// app::save_colliding_streams_figure<1>(
///     {&passing, &pileup, &viscous}, {&passing, &viscous}, setup,
///     {.title = "Two cold streams", .smoothing = "N_{ngb} = 5", .t_end = 0.4, .paths = 24},
///     chapter.figure_path("colliding_streams.png").string());
/// \endcode
///
/// Header-only: a chapter that includes it links sph_plot.

#include "app/colliding_streams_run.hpp"
#include "app/text.hpp"
#include "plot/figure.hpp"
#include "sph/setups/colliding_streams.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace app {

/// Draws the recorded paths of \p run into \p axes, x across and t up to \p t_end, the
/// right-moving stream in blue and the left-moving one in red (the first pair labelled); a run
/// that stopped before \p t_end gets a dotted line and a note at the time it reached.
template <int D>
void draw_stream_paths(plot::Axes& axes, const StreamsRun<D>& run, double t_end) {
  for (std::size_t k = 0; k < run.tracked.size(); ++k) {
    const bool right_moving = static_cast<int>(run.tracked[k]) < run.left_count;
    const std::string label = k >= 2 ? "" : (right_moving ? "moving right" : "moving left");
    axes.line(run.paths[k], run.times,
              {.label = label, .color = right_moving ? plot::blue : plot::red, .width = 1.2});
  }
  axes.xlim(-0.6, 0.6).ylim(0.0, t_end).xlabel("x  [code units]").ylabel("t  [code units]");
  axes.title(run.name);
  if (run.t_reached < t_end) {
    axes.hline(run.t_reached, {.color = plot::grey, .style = plot::Dash::dotted, .width = 1.2});
    axes.text(-0.55, run.t_reached + 0.04 * t_end, format("stopped at t = %.3f", run.t_reached),
              {.color = plot::grey, .size = 0.9});
  }
}

/// How the colliding-streams figure is labelled.
struct StreamsFigureOptions {
  std::string title{};      ///< the figure's title (markup)
  std::string smoothing{};  ///< the stamp's note on how h was set in each panel (markup)
  double t_end = 0.4;       ///< the end time of the runs: the top of the x-t diagrams
  int paths = 24;           ///< the paths recorded per stream (StreamsRunOptions::paths)
};

/// Saves the figure to \p path: the x-t diagrams of the first three of \p runs in panels (a)
/// to (c), and in (d) the final density of each of \p densities (the first in black, the
/// others in blue) against the exact solution of \p setup at `options.t_end`.  The stamp gives
/// the particles of one run, the wall time of all of them, the smoothing note and which
/// particles were drawn.
template <int D>
void save_colliding_streams_figure(const std::vector<const StreamsRun<D>*>& runs,
                                   const std::vector<const StreamsRun<D>*>& densities,
                                   const sph::CollidingStreamsSetup& setup,
                                   const StreamsFigureOptions& options, const std::string& path) {
  plot::Figure figure(2, 2, {.width = 1500, .height = 1200});
  figure.title(options.title);
  double seconds = 0;
  for (const auto* run : runs) seconds += run->seconds;
  const int stride = std::max(1, runs[0]->left_count / options.paths);
  figure.stamp(
      plot::Stamp{.scheme = "SPH, Hernquist-Katz",
                  .kernel = "M4",
                  .particles = static_cast<long long>(runs[0]->particles.size()),
                  .run_time = seconds,
                  .extra = options.smoothing + format("; every %dth particle drawn", stride)});
  for (int k = 0; k < 3; ++k) draw_stream_paths(figure.panel(k), *runs[k], options.t_end);
  figure.panel(1).legend(plot::Corner::upper_right);
  /// The density panel draws the particles of each run in `densities` as dots against the
  /// exact profile, sampled finely enough that its two shocks appear as sharp steps.
  // Panel (d): the final densities, and the exact solution.
  plot::Axes& density = figure.panel(3);
  const auto exact = sph::make_colliding_streams<D>(setup).exact;
  std::vector<double> xs, rho;
  for (int k = 0; k <= 2400; ++k) {
    xs.push_back(-0.6 + k / 2000.0);
    rho.push_back(exact.sample(xs.back(), options.t_end).density);
  }
  for (const auto* run : densities) {
    std::vector<double> x;
    for (const auto& r : run->particles.position) x.push_back(r[0]);
    density.scatter(
        x, run->particles.density,
        {.label = run->name, .color = run == densities[0] ? plot::black : plot::blue, .size = 3.5});
  }
  density.line(xs, rho, {.label = "exact", .color = plot::red, .width = 1.6});
  density.xlim(-0.6, 0.6).ylim(0, 5.5).xlabel("x  [code units]").ylabel("\\rho  [code units]");
  density.title(format("density at t = %.2f", options.t_end)).legend(plot::Corner::upper_right);
  figure.save_png(path);
}

}  // namespace app
