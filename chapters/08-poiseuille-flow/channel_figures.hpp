#pragma once
/// \file
/// \brief The figures of chapter 8: Watkins' Fig 4 with the start-up, the walls compared, the
/// histories of the error and of the rows' alternation.
///
/// Each takes the records of `channel_run.hpp` and draws them against the reference of
/// sph::PoiseuilleFlow; each is stamped with the scheme, kernel, particle and neighbour numbers.

#include "app/chapter.hpp"
#include "app/text.hpp"
#include "channel_run.hpp"
#include "plot/figure.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace app::poiseuille {

/// The stamp of every figure: Watkins' term on the lattice, with the gas and step of \p c.
inline plot::Stamp stamp(const RunChoices& c, long long particles, double seconds,
                         const std::string& extra) {
  return plot::Stamp{.scheme = "Watkins' two-pass viscosity, constant h, predictor-corrector",
                     .kernel = "M4",
                     .neighbours = c.channel.neighbours,
                     .particles = particles,
                     .run_time = seconds,
                     .extra = app::format("c = %g, dt = %.3g; ", c.sound_speed, c.dt()) + extra};
}

/// The reference curve of \p flow at time t (t < 0: the steady profile, eq 15) over |y| <= a.
inline void reference_curve(const sph::PoiseuilleFlow& flow, double t, std::vector<double>& y,
                            std::vector<double>& v) {
  const double a = flow.half_width();
  y.clear();
  v.clear();
  for (int k = 0; k <= 200; ++k) {
    y.push_back(-a + 2 * a * k / 200.0);
    v.push_back(t < 0 ? flow.steady(y.back()) : flow.from_rest(y.back(), t, 1e-8));
  }
}

/// Watkins' Fig 4 and the way there: (a) v_x against y at the end, every particle, with eq 15;
/// (b) the profiles on the way, against the start-up series at the same times.
inline void fig4(const app::Chapter& chapter, const RunChoices& c, const ChannelRun& run) {
  const sph::PoiseuilleFlow flow = c.flow();
  plot::Figure figure(1, 2, {.width = 1500, .height = 650});
  figure.title("Poiseuille flow between plates at y = \\pm" +
               app::format("%g", c.channel.half_width) + " (Watkins et al. Fig 4)");
  figure.stamp(stamp(c, static_cast<long long>(run.last.size()), run.seconds,
                     app::format("t_\\nu = %.3f", flow.settling_time())));
  std::vector<double> y, v;
  plot::Axes& a = figure.panel(0, 0);
  const Profile& last = run.profiles.back();
  a.title(app::format("the steady state, t = %.2f", last.t));
  a.xlabel("y  [box lengths]").ylabel("v_x  [box lengths / time]");
  a.scatter(last.y, last.vx, {.label = "particles", .color = plot::black, .size = 4});
  reference_curve(flow, -1, y, v);
  a.line(y, v, {.label = "eq 15: g(a^2 - y^2)/2\\mu_s", .color = plot::red, .width = 2});
  a.xlim(-0.5, 0.5).ylim(0, 1.15 * flow.axis_speed());
  a.vline(-c.channel.half_width, {.style = plot::Dash::dashed});
  a.vline(c.channel.half_width, {.label = "plates", .style = plot::Dash::dashed});
  a.legend(plot::Corner::lower_right);
  plot::Axes& b = figure.panel(0, 1);
  b.title("from rest: particles against the start-up series");
  b.xlabel("y  [box lengths]").ylabel("v_x  [box lengths / time]");
  for (std::size_t k = 0; k + 1 < run.profiles.size(); ++k) {
    const Profile& p = run.profiles[k];
    const plot::Color colour = plot::cycle_color(k);
    b.scatter(p.y, p.vx, {.color = colour, .size = 3.5});
    reference_curve(flow, p.t, y, v);
    b.line(y, v, {.label = app::format("t = %.3g", p.t), .color = colour, .width = 1.5});
  }
  b.xlim(-0.5, 0.5).ylim(0, 1.15 * flow.axis_speed());
  b.legend(plot::Corner::upper_right);
  figure.save_png(chapter.figure_path("fig4_poiseuille.png").string());
}

/// One labelled history for the log-scale figures below.
struct History {
  std::string label;
  const ChannelRun* run;
  double Sample::*quantity;
  plot::Dash dash = plot::Dash::solid;
};

/// Histories of one or two quantities on a log scale against t, one line per run.
inline void history_figure(const app::Chapter& chapter, const std::string& file,
                           const std::string& title, const std::string& ylabel,
                           const std::vector<History>& lines, const plot::Stamp& s,
                           double ymin = 1e-18) {
  plot::Figure figure(1, 1, {.width = 1100, .height = 700});
  figure.title(title);
  figure.stamp(s);
  plot::Axes& a = figure.panel(0, 0);
  a.letter("");
  a.xlabel("t  [time]").ylabel(ylabel).yscale(plot::Scale::log);
  int k = 0;
  for (const History& h : lines) {
    std::vector<double> t, q;
    for (const Sample& sample : h.run->samples) {
      const double value = sample.*(h.quantity);
      if (!(value > ymin)) continue;
      t.push_back(sample.t);
      q.push_back(value);
    }
    if (t.empty()) continue;
    a.line(t, q,
           {.label = h.label,
            .color = plot::cycle_color(static_cast<std::size_t>(k++)),
            .style = h.dash,
            .width = 2});
  }
  a.legend(plot::Corner::best);
  figure.save_png(chapter.figure_path(file).string());
}

/// Near the walls: v_x less the series at the end of each run, every particle, against the
/// distance from the nearer plate in particle spacings (the last run drawn on top), at two
/// scales.
inline void wall_figure(const app::Chapter& chapter, const RunChoices& c,
                        const std::vector<std::pair<std::string, const ChannelRun*>>& runs) {
  const sph::PoiseuilleFlow flow = c.flow();
  plot::Figure figure(1, 2, {.width = 1500, .height = 650});
  figure.title("The walls' pseudo-velocity and pseudo-curl: error of v_x near the plates");
  figure.stamp(stamp(c, static_cast<long long>(runs.front().second->last.size()), -1,
                     app::format("t = %.2f", runs.front().second->t_end)));
  /// Panel (a) shows every error; panel (b) the same points on a scale about thirty times
  /// finer, where the small errors of Watkins' walls can be seen beside those of walls at
  /// rest.  The last run is drawn on top with larger dots.
  for (int panel = 0; panel < 2; ++panel) {
    plot::Axes& a = figure.panel(0, panel);
    a.title(panel == 0 ? "every particle" : "the same, magnified");
    a.xlabel("distance from the nearer plate  [particle spacings]")
        .ylabel("(v_x - series) / v_{axis}");
    a.hline(0.0);
    std::size_t k = 0;
    for (const auto& [label, run] : runs) {
      std::vector<double> d, e;
      const Profile& p = run->profiles.back();
      for (std::size_t i = 0; i < p.y.size(); ++i) {
        d.push_back((c.channel.half_width - std::abs(p.y[i])) / c.channel.spacing());
        e.push_back((p.vx[i] - flow.from_rest(p.y[i], p.t, 1e-8)) / flow.axis_speed());
      }
      const bool last = k + 1 == runs.size();
      const std::string name = run->stopped.empty()
                                   ? label
                                   : label + app::format(" (stopped, t = %.3f)", run->stopped_at);
      a.scatter(d, e, {.label = name, .color = plot::cycle_color(k++), .size = last ? 6.0 : 3.0});
    }
    a.xlim(0, 12);
    if (panel == 1) a.ylim(-0.05, 0.25);
    a.legend(plot::Corner::upper_right);
  }
  figure.save_png(chapter.figure_path("walls.png").string());
}

}  // namespace app::poiseuille
