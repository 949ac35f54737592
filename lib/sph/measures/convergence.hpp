#pragma once
/// \file
/// \brief Error against run time: run a scene at a series of resolutions, time each run, measure
/// its errors against the reference, and fit the order of convergence.
///
/// This is the facility every scene with a reference solution shares, so that each chapter can
/// answer "which method buys the most accuracy per CPU second?".  A *method* is
/// one variant of a scene (e.g. "alpha=1, beta=2" against "alpha=0.5, beta=1"); each run of it
/// is a RunRecord with the particle number N, the particle spacing \f$ \Delta x \f$, the
/// wall-clock seconds and one or more errors (e.g. \f$ L_1(\rho) \f$, \f$ L_1(v) \f$).
///
/// **Order of convergence.**  We fit \f$ E = C\,\Delta x^{p} \f$ by least squares on
/// \f$ \ln E \f$ against \f$ \ln \Delta x \f$, and report p: the order with respect to
/// resolution, independent of the dimension.  (In D dimensions \f$ \Delta x \propto N^{-1/D} \f$,
/// so the same data give \f$ E \propto N^{-p/D} \f$.)  A second fit, \f$ E \propto t^{s} \f$
/// against the wall-clock time t, gives the *cost slope* s: the steeper (more negative), the
/// more accuracy each extra second buys.  For SPH shock tubes expect p ≈ 1 at best: shocks are
/// captured over a few h, so the L1 error is first order however smooth the rest of the flow.
///
/// Plotting lives elsewhere (lib/app/error_figure.hpp): lib/sph has no plot dependency.

#include "sph/error.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace sph {

/// What one run measured, before timing is added: the spacing and the errors.
struct Measurement {
  double resolution = 0;  ///< particle spacing Δx
  std::vector<std::pair<std::string, double>>
      errors;  ///< (quantity, error), e.g. ("L1(rho)", 1e-3)
};

/// One run of one method at one resolution.
struct RunRecord {
  std::string method;     ///< e.g. "alpha=1, beta=2"
  int particles = 0;      ///< N
  double resolution = 0;  ///< Δx
  double seconds = 0;     ///< wall-clock time of the run
  std::vector<std::pair<std::string, double>> errors;

  /// The error of one quantity; sph::Error if this run did not measure it.
  double error(const std::string& quantity) const {
    for (const auto& [name, value] : errors) {
      if (name == quantity) return value;
    }
    throw Error("run '" + method + "' N = " + std::to_string(particles) + " has no error '" +
                quantity + "'");
  }
  bool has(const std::string& quantity) const {
    for (const auto& e : errors) {
      if (e.first == quantity) return true;
    }
    return false;
  }
};

/// The points of one method and one quantity, coarse to fine: what a figure draws.
struct ErrorCurve {
  std::vector<int> particles;
  std::vector<double> resolution;
  std::vector<double> seconds;
  std::vector<double> error;
};

/// A least-squares power law y = C x^exponent, fitted in log-log.
struct PowerLaw {
  double exponent = 0;
  double prefactor = 0;
  int points = 0;
};

/// Fit y = C x^p to positive data by least squares on ln y against ln x.  Needs two distinct x.
inline PowerLaw fit_power_law(const std::vector<double>& x, const std::vector<double>& y) {
  require(x.size() == y.size(), "power-law fit: " + std::to_string(x.size()) + " x for " +
                                    std::to_string(y.size()) + " y");
  // Means of the logarithms.
  double mean_x = 0, mean_y = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    require(x[k] > 0 && y[k] > 0 && std::isfinite(x[k]) && std::isfinite(y[k]),
            "power-law fit: point " + std::to_string(k) + " (" + std::to_string(x[k]) + ", " +
                std::to_string(y[k]) + ") is not positive and finite");
    mean_x += std::log(x[k]);
    mean_y += std::log(y[k]);
  }
  const double n = static_cast<double>(x.size());
  mean_x /= n;
  mean_y /= n;
  // Slope = covariance / variance of ln x.
  double covariance = 0, variance = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double dx = std::log(x[k]) - mean_x;
    covariance += dx * (std::log(y[k]) - mean_y);
    variance += dx * dx;
  }
  require(x.size() >= 2 && variance > 0, "power-law fit: needs at least two distinct x values");
  const double slope = covariance / variance;
  return {slope, std::exp(mean_y - slope * mean_x), static_cast<int>(x.size())};
}

/// first, first*factor, first*factor^2, ... (count values, rounded to integers).
inline std::vector<int> geometric_series(int first, double factor, int count) {
  require(first > 0 && factor > 1 && count > 0,
          "geometric series: need first > 0, factor > 1, count > 0");
  std::vector<int> values;
  double value = first;
  for (int k = 0; k < count; ++k, value *= factor)
    values.push_back(static_cast<int>(std::lround(value)));
  return values;
}

/// The mean spacing of N particles filling a D-dimensional volume: (volume/N)^(1/D).
inline double mean_spacing(int particles, int dimension, double volume = 1.0) {
  require(particles > 0 && dimension >= 1 && volume > 0, "mean spacing: bad arguments");
  return std::pow(volume / particles, 1.0 / dimension);
}

namespace convergence_detail {

/// Display width of a UTF-8 string (code points), so "ρ" counts as one column.
inline std::size_t display_width(const std::string& s) {
  std::size_t width = 0;
  for (unsigned char c : s) width += (c & 0xC0) != 0x80;
  return width;
}

/// A method's name for a terminal: the TeX of a figure legend ("\\alpha = 1, \\beta = 2")
/// becomes plain Unicode ("α = 1, β = 2"); other text is unchanged.
inline std::string plain_text(std::string s) {
  static const std::pair<const char*, const char*> symbols[] = {
      {"\\varepsilon", "ε"}, {"\\epsilon", "ε"}, {"\\alpha", "α"}, {"\\beta", "β"},
      {"\\gamma", "γ"},      {"\\Delta", "Δ"},   {"\\delta", "δ"}, {"\\eta", "η"},
      {"\\rho", "ρ"},        {"\\nu", "ν"},      {"\\mu", "μ"},    {"\\sigma", "σ"}};
  for (const auto& [tex, unicode] : symbols) {
    for (std::size_t at = s.find(tex); at != std::string::npos; at = s.find(tex, at))
      s.replace(at, std::char_traits<char>::length(tex), unicode);
  }
  return s;
}

/// printf into a std::string.
template <class... Args>
std::string format(const char* pattern, Args... args) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, args...);
  return buffer;
}

/// Rows of cells printed in aligned columns: the first left-aligned, the rest right-aligned.
inline std::string aligned(const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> width;
  for (const auto& row : rows) {
    width.resize(std::max(width.size(), row.size()), 0);
    for (std::size_t c = 0; c < row.size(); ++c)
      width[c] = std::max(width[c], display_width(row[c]));
  }
  std::string text;
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string padding(width[c] - display_width(row[c]), ' ');
      line += c == 0 ? row[c] + padding : "  " + padding + row[c];
    }
    text += line.substr(0, line.find_last_not_of(' ') + 1) + "\n";
  }
  return text;
}

}  // namespace convergence_detail

/// The runs of several methods at several resolutions, with their errors and timings.
///
/// \code
/// sph::ErrorVsTime study("Sod shock tube, t = 0.2");
/// for (auto [name, alpha, beta] : variants)
///   study.sweep(name, sph::geometric_series(100, 2, 4), [&](int n) {
///     auto result = run_sod(n, alpha, beta);
///     return sph::Measurement{result.dx, {{"L1(rho)", result.l1_rho}, {"L1(v)", result.l1_v}}};
///   }, &std::cout);
/// std::cout << study.table();
/// \endcode
class ErrorVsTime {
 public:
  explicit ErrorVsTime(std::string title) : title_(std::move(title)) {}

  const std::string& title() const { return title_; }
  const std::vector<RunRecord>& records() const { return records_; }

  /// Add a finished run; sph::Error if a number is not positive and finite (a NaN error never
  /// enters the table).
  void add(RunRecord run) {
    const std::string who = "error-vs-time '" + title_ + "': run '" + run.method +
                            "' N = " + std::to_string(run.particles);
    require(!run.method.empty(), who + " has no method name");
    require(run.particles > 0, who + ": particle number must be positive");
    require(std::isfinite(run.resolution) && run.resolution > 0,
            who + ": resolution " + std::to_string(run.resolution) + " (must be positive)");
    require(std::isfinite(run.seconds) && run.seconds >= 0,
            who + ": run time " + std::to_string(run.seconds));
    require(!run.errors.empty(), who + " measured no error");
    for (const auto& [quantity, value] : run.errors) {
      require(std::isfinite(value) && value >= 0, who + ": error " + quantity + " = " +
                                                      std::to_string(value) +
                                                      " (must be finite and >= 0)");
    }
    records_.push_back(std::move(run));
  }

  /// Run `scene(particles)` (returning a Measurement), time it with the steady clock, and add it.
  template <class Scene>
  const RunRecord& run(const std::string& method, int particles, Scene&& scene) {
    const auto start = std::chrono::steady_clock::now();
    Measurement measured = scene(particles);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    add({method, particles, measured.resolution, seconds, std::move(measured.errors)});
    return records_.back();
  }

  /// run() at each particle number in turn; one progress line per run to `log` if given.
  template <class Scene>
  void sweep(const std::string& method, const std::vector<int>& particle_numbers, Scene&& scene,
             std::ostream* log = nullptr) {
    for (int n : particle_numbers) {
      const RunRecord& r = run(method, n, scene);
      if (!log) continue;
      *log << method << ": N = " << n
           << ", dx = " << convergence_detail::format("%.3e", r.resolution) << ", "
           << convergence_detail::format("%.3g", r.seconds) << " s";
      for (const auto& [quantity, value] : r.errors)
        *log << ", " << quantity << " = " << convergence_detail::format("%.3e", value);
      *log << "\n";
    }
  }

  /// The methods, in the order they first appear.
  std::vector<std::string> methods() const {
    return unique([](const RunRecord& r) { return std::vector{r.method}; });
  }

  /// The error quantities, in the order they first appear.
  std::vector<std::string> quantities() const {
    return unique([](const RunRecord& r) {
      std::vector<std::string> names;
      for (const auto& e : r.errors) names.push_back(e.first);
      return names;
    });
  }

  /// The runs of one method, coarse to fine (largest Δx first).
  std::vector<RunRecord> series(const std::string& method) const {
    std::vector<RunRecord> runs;
    for (const RunRecord& r : records_) {
      if (r.method == method) runs.push_back(r);
    }
    std::stable_sort(runs.begin(), runs.end(), [](const RunRecord& a, const RunRecord& b) {
      return a.resolution > b.resolution;
    });
    return runs;
  }

  /// The points of one method and quantity, coarse to fine, for a figure.
  ErrorCurve curve(const std::string& method, const std::string& quantity) const {
    ErrorCurve c;
    for (const RunRecord& r : series(method)) {
      if (!r.has(quantity)) continue;
      c.particles.push_back(r.particles);
      c.resolution.push_back(r.resolution);
      c.seconds.push_back(r.seconds);
      c.error.push_back(r.error(quantity));
    }
    return c;
  }

  /// The order p in error ∝ Δx^p (least-squares slope of ln error against ln Δx).  sph::Error
  /// if the method has fewer than two resolutions with a positive error for the quantity.
  double order(const std::string& method, const std::string& quantity) const {
    const ErrorCurve c = curve(method, quantity);
    return fit(c.resolution, c.error, method, quantity, "resolutions").exponent;
  }

  /// The cost slope s in error ∝ (wall time)^s; negative when more time buys less error.
  double cost_slope(const std::string& method, const std::string& quantity) const {
    const ErrorCurve c = curve(method, quantity);
    return fit(c.seconds, c.error, method, quantity, "run times").exponent;
  }

  /// The runs and the fitted orders as aligned plain text (fixed width: for a terminal and for
  /// a docs page in a code block).
  std::string table() const {
    using convergence_detail::format;
    const std::vector<std::string> names = quantities();
    // The runs: one row each, grouped by method, coarse to fine.
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> heading = {"method", "N", "dx", "wall [s]"};
    heading.insert(heading.end(), names.begin(), names.end());
    rows.push_back(heading);
    for (const std::string& method : methods()) {
      bool first = true;
      for (const RunRecord& r : series(method)) {
        std::vector<std::string> row = {first ? convergence_detail::plain_text(method) : "",
                                        std::to_string(r.particles), format("%.3e", r.resolution),
                                        format("%.3g", r.seconds)};
        for (const std::string& q : names)
          row.push_back(r.has(q) ? format("%.3e", r.error(q)) : "-");
        rows.push_back(row);
        first = false;
      }
    }
    std::string text = title_ + "\n\n" + convergence_detail::aligned(rows);
    // The fits: order p against dx and cost slope s against wall time.
    text += "\norder p, error ~ dx^p (least-squares slope of ln error against ln dx)\n";
    text += fits_table(names,
                       [this](const std::string& m, const std::string& q) { return order(m, q); });
    text += "\ncost slope s, error ~ (wall time)^s (more negative: more accuracy per second)\n";
    text += fits_table(
        names, [this](const std::string& m, const std::string& q) { return cost_slope(m, q); });
    return text;
  }

 private:
  /// The distinct strings `names_of(record)` yields, in order of first appearance.
  template <class NamesOf>
  std::vector<std::string> unique(NamesOf names_of) const {
    std::vector<std::string> result;
    for (const RunRecord& r : records_) {
      for (const std::string& name : names_of(r)) {
        if (std::find(result.begin(), result.end(), name) == result.end()) result.push_back(name);
      }
    }
    return result;
  }

  /// A power-law fit with a message naming the method and quantity when it cannot be made.
  static PowerLaw fit(const std::vector<double>& x, const std::vector<double>& error,
                      const std::string& method, const std::string& quantity, const char* what) {
    std::vector<double> xs, ys;
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (x[k] > 0 && error[k] > 0) {
        xs.push_back(x[k]);
        ys.push_back(error[k]);
      }
    }
    const bool distinct = !xs.empty() && *std::min_element(xs.begin(), xs.end()) <
                                             *std::max_element(xs.begin(), xs.end());
    require(distinct, "cannot fit " + quantity + " of '" + method + "': fewer than two distinct " +
                          what + " with a positive error");
    return fit_power_law(xs, ys);
  }

  /// One row per method, one column per quantity, "n/a" where no fit is possible.
  template <class Fit>
  std::string fits_table(const std::vector<std::string>& names, Fit fit_of) const {
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> heading = {"method"};
    heading.insert(heading.end(), names.begin(), names.end());
    rows.push_back(heading);
    for (const std::string& method : methods()) {
      std::vector<std::string> row = {convergence_detail::plain_text(method)};
      for (const std::string& q : names) {
        try {
          row.push_back(convergence_detail::format("%.2f", fit_of(method, q)));
        } catch (const Error&) {
          row.push_back("n/a");
        }
      }
      rows.push_back(row);
    }
    return convergence_detail::aligned(rows);
  }

  std::string title_;
  std::vector<RunRecord> records_;
};

}  // namespace sph
