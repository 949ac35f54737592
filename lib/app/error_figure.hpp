#pragma once
/// \file
/// \brief The error-against-run-time figure: an sph::ErrorVsTime drawn with lib/plot.
///
/// One panel per error quantity (\f$ L_1(\rho) \f$, \f$ L_1(v) \f$, ...), log-log, wall-clock
/// time on x and the error on y, one line with markers per method, coarse runs on the left.
/// The legend gives each method's fitted order p (error \f$ \propto \Delta x^p \f$, see
/// sph::ErrorVsTime::order), so the figure answers both questions at once: which method
/// converges faster, and which buys more accuracy per second.  A method lower and further left
/// is better.
///
/// \code
/// sph::ErrorVsTime study("Sod shock tube, t = 0.2");
/// ... study.sweep(...) for each method ...
/// std::cout << study.table();
/// app::ErrorFigureOptions options;
/// options.stamp = plot::format_stamp({.scheme = "Monaghan-Gingold AV", .kernel = "M4"});
/// app::save_error_figure(study, output / "sod_error_vs_time.png", options);
/// \endcode
///
/// A study can be drawn beside numbers it did not measure, another code's quoted measurements:
/// ErrorFigureOptions::quoted adds them as hollow markers joined by a dotted line, with a legend
/// that says they are quoted.
///
/// Header-only: a chapter that includes it links sph_plot.

#include "plot/error.hpp"
#include "plot/figure.hpp"
#include "plot/markup.hpp"
#include "sph/measures/convergence.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace app {

/// Points measured elsewhere and quoted: the wall times and, per quantity of the study
/// ("L1(rho)", ...), the errors at those times.  A quantity it does not name is not drawn.
struct QuotedPoints {
  std::string label;  ///< legend text (plain or markup), e.g. "other code, h = dx (quoted)"
  std::vector<double> seconds;
  std::map<std::string, std::vector<double>> error;  ///< by quantity, one per entry of seconds
  std::optional<plot::Color> color{};                ///< default: black, grey, black, ...
};

/// How the error figure looks.
struct ErrorFigureOptions {
  std::string title{};  ///< default: the study's title
  std::string stamp{};  ///< markup line at the foot (plot::format_stamp() builds the usual one)
  std::vector<std::string> quantities{};  ///< panels to draw; default: every quantity, in order
  int columns = 3;                        ///< panels per row, at most (rows are balanced)
  int width = 0;                          ///< pixels; 0: the figure engine's default per panel
  int height = 0;
  std::vector<QuotedPoints> quoted{};              ///< drawn beside the study's own runs
  std::string time_label = "wall-clock time [s]";  ///< the x axis of every panel
};

namespace error_figure_detail {

/// Method names and titles as markup: a text with a backslash is meant as markup
/// ("\\alpha = 1, \\beta = 2") and used as it is if it parses; any other text is plain, so the
/// characters the markup would interpret are escaped ("Watkins_bulk" keeps its underscore).
inline std::string as_markup(const std::string& text) {
  if (text.find('\\') != std::string::npos) {
    try {
      plot::parse_markup(text);
      return text;
    } catch (const plot::Error&) {
    }
  }
  std::string out;
  for (char c : text) {
    if (c == '_' || c == '^' || c == '{' || c == '}' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

/// A quantity name as axis markup: "L1(rho)" -> "L_1(\rho)", "Linf(v)" -> "L_\infty(v)".
/// A name that already contains markup (a backslash, '_' or '^') is used as it is.
inline std::string quantity_markup(const std::string& quantity) {
  if (quantity.find_first_of("\\_^") != std::string::npos) return quantity;
  static const char* const greek[] = {"alpha", "beta", "gamma", "delta", "epsilon", "eta",  "mu",
                                      "nu",    "rho",  "sigma", "tau",   "omega",   "Delta"};
  std::string out;
  std::size_t i = 0;
  while (i < quantity.size()) {
    // Copy anything that is not a letter.
    if (!std::isalpha(static_cast<unsigned char>(quantity[i]))) {
      out += quantity[i++];
      continue;
    }
    // A word, possibly followed by digits: L1, L2, Linf, rho ...
    std::size_t end = i;
    while (end < quantity.size() && std::isalpha(static_cast<unsigned char>(quantity[end]))) ++end;
    const std::string word = quantity.substr(i, end - i);
    std::size_t digits = end;
    while (digits < quantity.size() && std::isdigit(static_cast<unsigned char>(quantity[digits])))
      ++digits;
    if (word == "L" && digits > end) {
      out += "L_" + quantity.substr(end, digits - end);
      i = digits;
      continue;
    }
    if (word == "Linf") {
      out += "L_\\infty";
    } else if (std::find_if(std::begin(greek), std::end(greek),
                            [&](const char* g) { return word == g; }) != std::end(greek)) {
      out += "\\" + word;
    } else {
      out += word;
    }
    i = end;
  }
  return out;
}

/// Markers and dashes that tell the methods apart in greyscale too.
inline plot::Marker marker_of(std::size_t k) {
  static const plot::Marker markers[] = {plot::Marker::circle,   plot::Marker::square,
                                         plot::Marker::triangle, plot::Marker::diamond,
                                         plot::Marker::plus,     plot::Marker::cross};
  return markers[k % 6];
}
inline plot::Dash dash_of(std::size_t k) {
  static const plot::Dash dashes[] = {plot::Dash::solid, plot::Dash::dashed, plot::Dash::dashdot,
                                      plot::Dash::dotted};
  return dashes[k % 4];
}

/// "alpha=1, beta=2 (error \f$ \propto \Delta x^{0.98} \f$)": the order fitted to the errors
/// against the particle spacing, so that the legend says what it is; or the bare name when no
/// order can be fitted.
inline std::string legend_label(const sph::ErrorVsTime& study, const std::string& method,
                                const std::string& quantity) {
  std::string label = as_markup(method);
  try {
    char order[48];
    std::snprintf(order, sizeof order, " (\\propto \\Delta x^{%.2f})",
                  study.order(method, quantity));
    label += order;
  } catch (const sph::Error&) {
  }
  return label;
}

/// Draw one quantity's panel: one line per method through its (time, error) points, then the
/// quoted points that have this quantity.
inline void draw_panel(plot::Axes& axes, const sph::ErrorVsTime& study, const std::string& quantity,
                       const std::vector<QuotedPoints>& quoted = {},
                       const std::string& time_label = "wall-clock time [s]") {
  axes.xscale(plot::Scale::log).yscale(plot::Scale::log);
  axes.xlabel(time_label).ylabel(quantity_markup(quantity));
  const std::vector<std::string> methods = study.methods();
  for (std::size_t k = 0; k < methods.size(); ++k) {
    // Keep the points a log-log plot can show.
    const sph::ErrorCurve curve = study.curve(methods[k], quantity);
    std::vector<double> seconds, error;
    for (std::size_t i = 0; i < curve.error.size(); ++i) {
      if (curve.seconds[i] > 0 && curve.error[i] > 0) {
        seconds.push_back(curve.seconds[i]);
        error.push_back(curve.error[i]);
      }
    }
    if (seconds.empty()) continue;
    axes.line(seconds, error,
              {.label = legend_label(study, methods[k], quantity),
               .style = dash_of(k),
               .width = 1.6,
               .marker = marker_of(k),
               .marker_size = 8.0});
  }
  for (std::size_t k = 0; k < quoted.size(); ++k) {
    const auto it = quoted[k].error.find(quantity);
    if (it == quoted[k].error.end()) continue;
    sph::require(it->second.size() == quoted[k].seconds.size(),
                 "error figure: the quoted points '" + quoted[k].label + "' have " +
                     std::to_string(it->second.size()) + " errors of " + quantity + " for " +
                     std::to_string(quoted[k].seconds.size()) + " times");
    axes.line(quoted[k].seconds, it->second,
              {.label = as_markup(quoted[k].label),
               .color = quoted[k].color.value_or(k % 2 ? plot::grey : plot::black),
               .style = plot::Dash::dotted,
               .width = 1.2,
               .marker = marker_of(methods.size() + k),
               .marker_size = 11.0,
               .marker_filled = false});
  }
  // The corner that covers the fewest points; if every corner holds points, room above them.
  axes.legend(plot::Corner::best, true);
}

}  // namespace error_figure_detail

/// The figure: one log-log panel per error quantity, error against wall-clock time, one line
/// per method.  Throws sph::Error if the study has no runs or a requested quantity is unknown.
inline plot::Figure error_figure(const sph::ErrorVsTime& study,
                                 const ErrorFigureOptions& options = {}) {
  // Which panels, and how they are arranged.
  const std::vector<std::string> known = study.quantities();
  const std::vector<std::string> quantities =
      options.quantities.empty() ? known : options.quantities;
  sph::require(!quantities.empty(), "error figure '" + study.title() + "': the study has no runs");
  for (const std::string& q : quantities) {
    sph::require(std::find(known.begin(), known.end(), q) != known.end(),
                 "error figure '" + study.title() + "': no quantity '" + q + "' was measured");
  }
  // As few rows as `columns` allows, then as few columns as those rows need (4 panels: 2 x 2).
  const int count = static_cast<int>(quantities.size());
  const int rows = (count + std::max(options.columns, 1) - 1) / std::max(options.columns, 1);
  const int cols = (count + rows - 1) / rows;
  // The figure, its title and stamp.
  plot::Figure figure(rows, cols, {.width = options.width, .height = options.height});
  figure.title(
      error_figure_detail::as_markup(options.title.empty() ? study.title() : options.title));
  figure.stamp(options.stamp);
  // One panel per quantity; unused cells of the last row stay empty.
  for (int k = 0; k < count; ++k)
    error_figure_detail::draw_panel(figure.panel(k), study, quantities[k], options.quoted,
                                    options.time_label);
  return figure;
}

/// error_figure() written to a PNG at `path` (plot::Error if it cannot be written).
inline void save_error_figure(const sph::ErrorVsTime& study, const std::string& path,
                              const ErrorFigureOptions& options = {}) {
  plot::Figure figure = error_figure(study, options);
  figure.save_png(path);
}

}  // namespace app
