#pragma once
/// \file
/// \brief The static tests of second derivatives (chapter 7): the four methods behind one
/// name, a frozen particle set with its densities, the error of a method against the analytic
/// answer, and the tables the chapter prints.
///
/// A static test freezes a particle set, gives every particle a velocity from an analytic
/// field, applies one of the operators of lib/sph/derivatives to it, and compares the result
/// with the analytic second derivative, whose amplitude is \f$ 4\pi^2 \f$ for every field here.
/// The pieces:
///  - Method and Operator name what is computed; apply() dispatches to the library's
///    functions; name(), color() and method_style() give each method the same look in every
///    table and figure;
///  - StaticSet holds a particle set, its neighbour list and its densities, summed with or
///    without the self term;
///  - measure() reduces one answer to its Errors (rms and largest error, fitted amplitude,
///    scatter about the fit), and MethodResult keeps them with the answer and its run time;
///  - table(), cost_row() and the print functions run every method on one set and print the
///    rows the chapter's output shows; NoiseStudy, DisorderStudy and CostStudy are the records
///    of the chapter's sweeps.
///
/// \code
/// const app::second_derivatives::StaticSet<3> s("settled", particles, true);
/// const auto rows = app::second_derivatives::table(s, velocity, Operator::curl_curl, "settled");
/// \endcode
///
/// The file is header-only and belongs to this chapter: every line of it is shown here.

#include "app/particle_measures.hpp"
#include "app/stopwatch.hpp"
#include "plot/figure.hpp"
#include "sph/derivatives/brookshaw_1985.hpp"
#include "sph/derivatives/flebbe_1994.hpp"
#include "sph/derivatives/watkins_1996_two_pass.hpp"
#include "sph/error.hpp"
#include "sph/setups/watkins_static.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace app::second_derivatives {

using sph::Vec;
namespace dv = sph::derivatives;

/// \f$ 2\pi \f$, the wavenumber of every field of the static tests.
constexpr double two_pi = 2 * std::numbers::pi;
/// \f$ 4\pi^2 \f$, the amplitude of every second derivative of the static tests: errors are
/// quoted in units of it.
constexpr double k2 = two_pi * two_pi;

/// The four methods, in the order of every table and figure.
enum class Method { watkins, own_volume, flebbe, brookshaw };
/// Every method, in table order.
constexpr std::array<Method, 4> all_methods = {Method::watkins, Method::own_volume, Method::flebbe,
                                               Method::brookshaw};
/// The three methods of the paper's figures.
constexpr std::array<Method, 3> paper_methods = {Method::watkins, Method::flebbe,
                                                 Method::brookshaw};

/// The name of method \p m in tables and legends.
inline const char* name(Method m) {
  switch (m) {
    case Method::watkins:
      return "Watkins";
    case Method::own_volume:
      return "own volume";
    case Method::flebbe:
      return "Flebbe";
    case Method::brookshaw:
      return "Brookshaw";
  }
  return "?";
}

/// The colour of method \p m in every figure.
inline plot::Color color(Method m) {
  switch (m) {
    case Method::watkins:
      return plot::blue;
    case Method::own_volume:
      return plot::cyan;
    case Method::flebbe:
      return plot::green;
    case Method::brookshaw:
      return plot::red;
  }
  return plot::black;
}

/// The line of method \p m in the summary figures: its colour, and a marker and dash of its
/// own, so that curves that coincide stay visible.
inline plot::LineOptions method_style(Method m) {
  plot::LineOptions o{.label = name(m), .color = color(m), .width = 2, .marker_size = 7};
  switch (m) {
    case Method::watkins:
      o.marker = plot::Marker::circle;
      break;
    case Method::own_volume:
      o.marker = plot::Marker::square;
      o.marker_filled = false;
      o.style = plot::Dash::dashed;
      break;
    case Method::flebbe:
      o.marker = plot::Marker::triangle;
      o.style = plot::Dash::dotted;
      break;
    case Method::brookshaw:
      o.marker = plot::Marker::diamond;
      break;
  }
  return o;
}

/// What is differentiated: \f$ \nabla\times\nabla\times\mathbf v \f$ or
/// \f$ \nabla(\nabla\cdot\mathbf v) \f$.
enum class Operator { curl_curl, grad_div };

/// One method's answer for one operator.  Brookshaw has only the Laplacian: its curl curl is
/// \f$ -\nabla^2\mathbf v \f$, its grad div \f$ \nabla^2\mathbf v \f$ -- each right only where the
/// other operator vanishes.
template <int D>
std::vector<Vec<D>> apply(Method m, Operator op, const dv::ParticleSet<D>& set,
                          const std::vector<Vec<D>>& v) {
  const std::span<const Vec<D>> vs(v);
  const bool cc = op == Operator::curl_curl;
  switch (m) {
    case Method::watkins:
      return cc ? dv::curl_curl(set, vs) : dv::grad_div(set, vs);
    case Method::own_volume:
      return cc ? dv::curl_curl(set, vs, dv::Volume::own) : dv::grad_div(set, vs, dv::Volume::own);
    case Method::flebbe:
      return cc ? dv::flebbe::curl_curl(set, vs) : dv::flebbe::grad_div(set, vs);
    case Method::brookshaw:
      return cc ? dv::brookshaw::curl_curl(set, vs) : dv::brookshaw::laplacian(set, vs);
  }
  return {};
}

/// A particle set of the static tests in the periodic unit box, with its neighbour list (one
/// constant h) and its gather densities, summed with or without the self term.
template <int D>
struct StaticSet {
  std::string label;
  sph::Particles<D> p;
  sph::NeighbourSearch<D> search;
  bool self_term = true;
  sph::DensityScatter scatter;  ///< mean and scatter of the densities
  double neighbours = 0;        ///< the mean neighbour number its h gives, n (2h)^D V_D

  /// Searches the neighbours of \p particles and sums their densities.  The neighbour number
  /// the figures' stamps give is the one the particles' (constant) h implies in the unit box,
  /// so that a stamp says what ran, whatever option chose it.
  StaticSet(std::string name, sph::Particles<D> particles, bool with_self_term)
      : label(std::move(name)), p(std::move(particles)), self_term(with_self_term) {
    search.update(p, sph::setups::unit_box<D>(), sph::SmoothingLengthRule::fixed());
    sph::compute_density<D>(p, search.list(), sph::DensityForm::watkins(self_term));
    scatter = sph::density_scatter(p.density);
    const double support = 2 * p.smoothing_length[0];
    const double ball = D == 2 ? std::numbers::pi * support * support
                               : 4.0 / 3.0 * std::numbers::pi * support * support * support;
    neighbours = std::round(10 * static_cast<double>(p.size()) * ball) / 10;
  }
  /// The frozen set the operators read.
  dv::ParticleSet<D> view() const { return {p, search.list(), sph::setups::unit_box<D>()}; }
  /// Coordinate \p a of every particle.
  std::vector<double> coordinate(int a) const {
    std::vector<double> y(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) y[i] = p.position[i][a];
    return y;
  }
};

/// The error of one method on one set: rms and largest \f$ |\mathbf a - \mathbf a_\mathrm{exact}|
/// \f$ over the particles, both over \f$ 4\pi^2 \f$; the fitted amplitude A of the x-component,
/// \f$ a_x \approx A\sin(2\pi\,\cdot) \f$ by least squares, over \f$ 4\pi^2 \f$ (1 is exact: below
/// one the method smooths the peaks); and the rms scatter about that fit.
struct Errors {
  double rms = 0, max = 0, amplitude = 0, scatter = 0;
};

/// The Errors of the answer \p a of operator \p op for the shear field
/// \f$ v_x = \sin 2\pi y \f$ (curl curl) or the compressive \f$ v_x = \sin 2\pi x \f$
/// (grad div), whose exact answers are \f$ (\pm 4\pi^2\sin 2\pi\,\cdot, 0, 0) \f$.
template <int D>
Errors measure(const sph::Particles<D>& p, const std::vector<Vec<D>>& a, Operator op) {
  Errors e;
  double ss = 0, sa = 0, s2 = 0;
  const int axis = op == Operator::curl_curl ? 1 : 0;
  const double sign = op == Operator::curl_curl ? 1.0 : -1.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double s = sign * std::sin(two_pi * p.position[i][axis]);
    Vec<D> exact = Vec<D>::Zero();
    exact[0] = k2 * s;
    const double d = (a[i] - exact).norm() / k2;
    ss += d * d;
    e.max = std::max(e.max, d);
    sa += s * a[i][0];
    s2 += s * s;
  }
  const double n = static_cast<double>(p.size());
  e.rms = std::sqrt(ss / n);
  e.amplitude = sa / s2 / k2;
  double scatter = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double s = sign * std::sin(two_pi * p.position[i][axis]);
    const double d = a[i][0] / k2 - e.amplitude * s;
    scatter += d * d;
  }
  e.scatter = std::sqrt(scatter / n);
  return e;
}

/// The rms and largest \f$ |\mathbf a|/4\pi^2 \f$: the error of an answer whose exact value is
/// zero (the amplitude and scatter are left at zero).
template <int D>
Errors errors_against_zero(const std::vector<Vec<D>>& a) {
  Errors e;
  double ss = 0;
  for (const auto& x : a) {
    const double d = x.norm() / k2;
    ss += d * d;
    e.max = std::max(e.max, d);
  }
  e.rms = std::sqrt(ss / static_cast<double>(a.size()));
  return e;
}

/// One method's result on one set: its errors, the x-component at every particle (for the
/// figures), and the wall time of the evaluation.
template <int D>
struct MethodResult {
  Method method{};
  Errors errors;
  std::vector<double> x_component;
  double seconds = 0;
};

/// Applies method \p m to the velocities \p v on \p s, timed, and measures the answer.
template <int D>
MethodResult<D> run_method(Method m, Operator op, const StaticSet<D>& s,
                           const std::vector<Vec<D>>& v) {
  MethodResult<D> r;
  r.method = m;
  const auto set = s.view();
  const app::Stopwatch clock;
  const std::vector<Vec<D>> a = apply(m, op, set, v);
  r.seconds = clock.seconds();
  r.errors = measure(s.p, a, op);
  r.x_component.resize(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) r.x_component[i] = a[i][0];
  return r;
}

/// Prints the heading of a table of MethodResult rows.
inline void print_table_header() {
  std::printf("    %-12s %10s %10s %12s %10s %10s\n", "method", "rms error", "max error",
              "amplitude", "scatter", "time [s]");
}

/// Prints one MethodResult as a row of the table.
template <int D>
void print_row(const MethodResult<D>& r) {
  std::printf("    %-12s %10.4f %10.4f %12.4f %10.4f %10.4f\n", name(r.method), r.errors.rms,
              r.errors.max, r.errors.amplitude, r.errors.scatter, r.seconds);
}

/// Runs every method on \p s with the velocities \p v, printing the table under \p heading,
/// and returns the rows in the order of all_methods.
template <int D>
std::vector<MethodResult<D>> table(const StaticSet<D>& s, const std::vector<Vec<D>>& v, Operator op,
                                   const std::string& heading) {
  std::printf("  %dD, %s:\n", D, heading.c_str());
  print_table_header();
  std::vector<MethodResult<D>> rows;
  for (Method m : all_methods) {
    rows.push_back(run_method(m, op, s, v));
    print_row(rows.back());
  }
  return rows;
}

/// The rms error of every method, in the order of all_methods, for operator \p op applied to
/// the velocities \p v on \p s (no table printed).
template <int D>
std::array<double, 4> rms_errors(const StaticSet<D>& s, const std::vector<Vec<D>>& v, Operator op) {
  std::array<double, 4> row{};
  for (std::size_t k = 0; k < all_methods.size(); ++k)
    row[k] = run_method(all_methods[k], op, s, v).errors.rms;
  return row;
}

/// The three methods of the paper (Watkins, Flebbe, Brookshaw) out of the four.
template <int D>
std::vector<MethodResult<D>> paper_rows(const std::vector<MethodResult<D>>& rows) {
  std::vector<MethodResult<D>> out;
  for (Method m : paper_methods)
    for (const auto& r : rows)
      if (r.method == m) out.push_back(r);
  return out;
}

/// The errors of method \p m among \p rows; throws sph::Error if it has no row.
template <int D>
const Errors& errors_of(const std::vector<MethodResult<D>>& rows, Method m) {
  for (const auto& r : rows)
    if (r.method == m) return r.errors;
  throw sph::Error("no row for method " + std::string(name(m)));
}

/// The rms errors of every method against the amplitude of the noise added to the velocity.
template <int D>
struct NoiseStudy {
  std::vector<MethodResult<D>> rows;  ///< at the chapter's noise amplitude
  std::vector<double> amplitudes;
  std::vector<std::array<double, 4>> rms;     ///< per amplitude, per method: mean over the draws
  std::vector<std::array<double, 4>> spread;  ///< and the largest minus the smallest
  /// The mean rms error at amplitude \p eps of method \p m.
  double at(double eps, Method m) const {
    for (std::size_t a = 0; a < amplitudes.size(); ++a)
      if (amplitudes[a] == eps)
        for (std::size_t k = 0; k < all_methods.size(); ++k)
          if (all_methods[k] == m) return rms[a][k];
    throw sph::Error("noise study: no row for this amplitude");
  }
};

/// The rms error of every method for operator \p op, over several draws \p fields of a noisy
/// velocity on \p s: the mean over the draws, and the largest minus the smallest.
template <int D>
std::pair<std::array<double, 4>, std::array<double, 4>> mean_and_spread(
    const StaticSet<D>& s, const std::vector<std::vector<Vec<D>>>& fields, Operator op) {
  std::array<double, 4> mean{}, lo{}, hi{}, spread{};
  lo.fill(1e300);
  const double draws = static_cast<double>(fields.size());
  for (const auto& v : fields) {
    for (std::size_t k = 0; k < all_methods.size(); ++k) {
      const double e = run_method(all_methods[k], op, s, v).errors.rms;
      mean[k] += e / draws;
      lo[k] = std::min(lo[k], e);
      hi[k] = std::max(hi[k], e);
    }
  }
  for (std::size_t k = 0; k < 4; ++k) spread[k] = hi[k] - lo[k];
  return {mean, spread};
}

/// Prints the table of a NoiseStudy: one row per amplitude, the mean of the draws and half
/// their range per method.
template <int D>
void print_noise_table(const NoiseStudy<D>& study) {
  std::printf(
      "    rms error against the noise amplitude (mean of 3 draws, +- half the range):\n"
      "      %-8s",
      "epsilon");
  for (Method m : all_methods) std::printf(" %16s", name(m));
  std::printf("\n");
  for (std::size_t a = 0; a < study.amplitudes.size(); ++a) {
    std::printf("      %-8g", study.amplitudes[a]);
    for (std::size_t k = 0; k < 4; ++k)
      std::printf(" %8.4f +-%5.4f", study.rms[a][k], 0.5 * study.spread[a][k]);
    std::printf("\n");
  }
}

/// The rms errors of every method against the disorder of the particle set.
template <int D>
struct DisorderStudy {
  std::vector<double> sigma;               ///< sigma_rho / mean per set (self term included)
  std::vector<std::array<double, 4>> rms;  ///< per set, per method
  double paper_sigma = 0;                  ///< the Poisson set as Fig 3 sums it (no self term)
  std::array<double, 4> paper_rms{};
};

/// Prints the table of a DisorderStudy whose first sets were made with the random offsets
/// \p offsets (in particle spacings) and whose last is the Poisson set.
template <int D>
void print_disorder_table(const DisorderStudy<D>& study, const std::vector<double>& offsets) {
  std::printf(
      "  %dD: rms error of curl curl / 4 pi^2 against disorder (self term included)\n"
      "    %-10s %-10s",
      D, "offset/dx", "sigma/rho");
  for (Method m : all_methods) std::printf(" %11s", name(m));
  std::printf("\n");
  for (std::size_t k = 0; k < study.sigma.size(); ++k) {
    if (k < offsets.size()) {
      std::printf("    %-10g %-10.4f", offsets[k], study.sigma[k]);
    } else {
      std::printf("    %-10s %-10.4f", "Poisson", study.sigma[k]);
    }
    for (double e : study.rms[k]) std::printf(" %11.4f", e);
    std::printf("\n");
  }
  std::printf("    %-10s %-10.4f", "Fig 3 set", study.paper_sigma);
  for (double e : study.paper_rms) std::printf(" %11.4f", e);
  std::printf("   (Poisson, no self term)\n");
}

/// One set of the cost study: its size, neighbour number, and per method the rms error and
/// the wall time of one evaluation.
struct CostRow {
  int particles = 0;
  double neighbours = 0;
  std::array<double, 4> rms{}, seconds{};
};

/// The cost study: rows against the number of particles, and against the neighbour number.
struct CostStudy {
  std::vector<CostRow> by_n, by_neighbours;
};

/// The CostRow of the curl curl of the shear field \p v on \p s: each method's error, and the
/// fastest of three evaluations (the cost, not the machine's other work).
inline CostRow cost_row(const StaticSet<3>& s, const std::vector<Vec<3>>& v, double neighbours) {
  CostRow row;
  row.particles = static_cast<int>(s.p.size());
  row.neighbours = neighbours;
  for (std::size_t k = 0; k < all_methods.size(); ++k) {
    double best = 1e300;
    for (int rep = 0; rep < 3; ++rep) {
      const auto r = run_method(all_methods[k], Operator::curl_curl, s, v);
      best = std::min(best, r.seconds);
      row.rms[k] = r.errors.rms;
    }
    row.seconds[k] = best;
  }
  return row;
}

/// Prints the heading of the cost table.
inline void print_cost_header() {
  std::printf(
      "  3D settled sets: rms error of curl curl / 4 pi^2 and the time of one evaluation "
      "[s] (fastest of 3)\n    %7s %6s",
      "N", "N_ngb");
  for (Method m : all_methods) std::printf("  %8s %8s", name(m), "time");
  std::printf("\n");
}

/// Prints one CostRow.
inline void print_cost_row(const CostRow& r) {
  std::printf("    %7d %6g", r.particles, r.neighbours);
  for (std::size_t k = 0; k < 4; ++k) std::printf("  %8.4f %8.4f", r.rms[k], r.seconds[k]);
  std::printf("\n");
}

/// The median wall times of two evaluations \p first and \p second, run alternately
/// \p repeats times (odd), so that both see the same state of the machine.
template <class First, class Second>
std::pair<double, double> alternating_medians(First&& first, Second&& second, int repeats = 5) {
  std::vector<double> t1, t2;
  for (int rep = 0; rep < repeats; ++rep) {
    app::Stopwatch c1;
    first();
    t1.push_back(c1.seconds());
    app::Stopwatch c2;
    second();
    t2.push_back(c2.seconds());
  }
  std::sort(t1.begin(), t1.end());
  std::sort(t2.begin(), t2.end());
  return {t1[static_cast<std::size_t>(repeats / 2)], t2[static_cast<std::size_t>(repeats / 2)]};
}

}  // namespace app::second_derivatives
