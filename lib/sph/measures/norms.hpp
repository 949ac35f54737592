#pragma once
/// \file
/// \brief Error norms of particle values against a reference solution.
///
/// For particles \f$ i \f$ in a selection \f$ \mathcal S \f$ of size \f$ N \f$, with values
/// \f$ f_i \f$ and a reference \f$ f_\mathrm{ref}(\mathbf x) \f$,
/// \f[ L_1 = \frac1N \sum_{i\in\mathcal S} |f_i - f_\mathrm{ref}(\mathbf x_i)|, \qquad
///     L_2 = \Big(\frac1N \sum_{i\in\mathcal S}
///           (f_i - f_\mathrm{ref}(\mathbf x_i))^2\Big)^{1/2}, \qquad
///     L_\infty = \max_{i\in\mathcal S} |f_i - f_\mathrm{ref}(\mathbf x_i)| . \f]
/// These are particle averages, not volume integrals: for equal-mass particles they weight each
/// region by its mass, which is the usual convention for SPH shock tubes.
///
/// The relative scatter in a region,
/// \f[ \sigma_\mathrm{rel} = \Big(\frac1N \sum_{i\in\mathcal S}
///     \Big(\frac{f_i - f_\mathrm{ref}(\mathbf x_i)}{f_\mathrm{ref}(\mathbf x_i)}\Big)^2
///     \Big)^{1/2}, \f]
/// is the measure behind Watkins et al. (1996) section 4.3: "velocity scatter about the exact
/// solution" in the shocked region of the Monaghan & Gingold tube, ≈ 15 % with artificial
/// viscosity and ≈ 11 % with their Navier-Stokes bulk viscosity.
///
/// A NaN is never a small error: every value (selected or not) must be finite, and so must the
/// reference wherever it is used; otherwise sph::Error names the particle.

#include "sph/dimension.hpp"
#include "sph/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace sph {

/// Which particles enter a norm: an interval on one axis and, optionally, a mask.
struct Selection {
  int axis = 0;                                             ///< axis of the interval
  double lower = -std::numeric_limits<double>::infinity();  ///< closed interval [lower, upper]
  double upper = std::numeric_limits<double>::infinity();
  std::vector<bool> mask;  ///< if not empty: particle i is selected only if mask[i]

  /// Every particle.
  static Selection all() { return {}; }
  /// Particles with lower <= x[axis] <= upper.
  static Selection range(double lower, double upper, int axis = 0) {
    return {axis, lower, upper, {}};
  }
  /// Particles whose mask entry is true.
  static Selection masked(std::vector<bool> mask) {
    Selection s;
    s.mask = std::move(mask);
    return s;
  }

  /// Is particle i at x selected?
  template <int D>
  bool contains(std::size_t i, const Vec<D>& x) const {
    if (!mask.empty() && !mask[i]) return false;
    return x[axis] >= lower && x[axis] <= upper;
  }

  /// "x in [0, 0.5]", "masked", "all particles": for messages.
  std::string describe() const {
    std::string text;
    if (std::isfinite(lower) || std::isfinite(upper)) {
      char buffer[96];
      std::snprintf(buffer, sizeof buffer, "%s in [%g, %g]", axis_name(axis), lower, upper);
      text = buffer;
    }
    if (!mask.empty()) text += text.empty() ? "masked particles" : ", masked";
    return text.empty() ? "all particles" : text;
  }
};

/// The three norms of one quantity, and where the worst error sits.
struct ErrorNorms {
  std::string quantity;  ///< e.g. "density"
  double L1 = 0, L2 = 0, Linf = 0;
  std::size_t count = 0;        ///< particles in the selection
  std::size_t worst_index = 0;  ///< the particle with |f_i - f_ref| = L_inf
  double worst_value = 0;       ///< its value f_i
  double worst_reference = 0;   ///< and its reference value

  /// "density: L1 = 1.2e-03, L2 = 3.4e-03, Linf = 5.6e-02 at particle 17 (0.51 vs 0.45), N = 400"
  std::string summary() const {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer,
                  "%s: L1 = %.3e, L2 = %.3e, Linf = %.3e at particle %zu (%.6g vs %.6g), N = %zu",
                  quantity.c_str(), L1, L2, Linf, worst_index, worst_value, worst_reference, count);
    return buffer;
  }
};

/// Accept `actual` if it is within `relative` of `expected` or within the floor `absolute`
/// (the tolerance policy of the tests: relative error with an absolute floor; NaN always fails).
struct Tolerance {
  double relative = 1e-6;
  double absolute = 0.0;

  bool accepts(double actual, double expected) const {
    if (!std::isfinite(actual) || !std::isfinite(expected)) return false;
    return std::abs(actual - expected) <= std::max(absolute, relative * std::abs(expected));
  }
};

/// The x-component (or any axis) of a vector field, as the values of a norm.
template <int D>
std::vector<double> component(const std::vector<Vec<D>>& field, int axis) {
  require(axis >= 0 && axis < D,
          "component: axis " + show(axis) + " in " + show(D) + " dimensions");
  std::vector<double> values(field.size());
  for (std::size_t i = 0; i < field.size(); ++i) values[i] = field[i][axis];
  return values;
}

namespace norms_detail {

/// Check sizes and that every value is finite; names the first bad particle.
template <int D>
void require_finite_values(const std::string& quantity, const std::vector<Vec<D>>& position,
                           const std::vector<double>& value, const Selection& selection) {
  require(position.size() == value.size(), quantity + ": " + show(value.size()) + " values for " +
                                               show(position.size()) + " positions");
  require(selection.mask.empty() || selection.mask.size() == value.size(),
          quantity + ": selection mask has " + show(selection.mask.size()) + " entries for " +
              show(value.size()) + " particles");
  require(selection.axis >= 0 && selection.axis < D,
          quantity + ": selection axis " + show(selection.axis) + " in " + show(D) + " dimensions");
  for (std::size_t i = 0; i < value.size(); ++i) {
    require(std::isfinite(value[i]), quantity + ": particle " + show(i) + " at " +
                                         to_string<D>(position[i]) + " has value " +
                                         show(value[i]) + " (must be finite)");
  }
}

/// The reference at particle i, checked to be finite.
template <int D, class Reference>
double reference_at(const std::string& quantity, std::size_t i, const Vec<D>& x,
                    Reference& reference) {
  const double r = reference(x);
  require(std::isfinite(r), quantity + ": the reference is " + show(r) + " at particle " + show(i) +
                                " at " + to_string<D>(x));
  return r;
}

/// Error if nothing is selected.
inline void require_selected(const std::string& quantity, std::size_t count,
                             const Selection& selection) {
  require(count > 0, quantity + ": no particles selected (" + selection.describe() + ")");
}

}  // namespace norms_detail

/// L1, L2 and L∞ of `value` against `reference(position)` over the selected particles.
/// `reference` is any callable double(const Vec<D>&).
///
/// \code
/// auto rho = sph::error_norms<1>("density", p.position, p.density,
///     [&](const sph::Vec<1>& x) { return exact.sample(x[0], t).density; },
///     sph::Selection::range(-0.4, 0.4));
/// \endcode
template <int D, class Reference>
ErrorNorms error_norms(const std::string& quantity, const std::vector<Vec<D>>& position,
                       const std::vector<double>& value, Reference&& reference,
                       const Selection& selection = {}) {
  norms_detail::require_finite_values<D>(quantity, position, value, selection);
  ErrorNorms norms;
  norms.quantity = quantity;
  double sum_abs = 0, sum_square = 0;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!selection.contains<D>(i, position[i])) continue;
    // Accumulate |f_i - f_ref| and its square.
    const double ref = norms_detail::reference_at<D>(quantity, i, position[i], reference);
    const double error = std::abs(value[i] - ref);
    sum_abs += error;
    sum_square += error * error;
    ++norms.count;
    // Keep the worst particle.
    if (norms.count == 1 || error > norms.Linf) {
      norms.Linf = error;
      norms.worst_index = i;
      norms.worst_value = value[i];
      norms.worst_reference = ref;
    }
  }
  norms_detail::require_selected(quantity, norms.count, selection);
  norms.L1 = sum_abs / static_cast<double>(norms.count);
  norms.L2 = std::sqrt(sum_square / static_cast<double>(norms.count));
  return norms;
}

/// RMS of the relative deviation (f_i - f_ref)/f_ref over the selected particles.  A zero
/// reference value in the selection is an error (the relative deviation is undefined there).
template <int D, class Reference>
double relative_scatter(const std::string& quantity, const std::vector<Vec<D>>& position,
                        const std::vector<double>& value, Reference&& reference,
                        const Selection& selection) {
  norms_detail::require_finite_values<D>(quantity, position, value, selection);
  double sum_square = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!selection.contains<D>(i, position[i])) continue;
    const double ref = norms_detail::reference_at<D>(quantity, i, position[i], reference);
    require(ref != 0.0, quantity + ": relative scatter undefined, the reference is 0 at particle " +
                            show(i) + " at " + to_string<D>(position[i]));
    const double deviation = (value[i] - ref) / ref;
    sum_square += deviation * deviation;
    ++count;
  }
  norms_detail::require_selected(quantity, count, selection);
  return std::sqrt(sum_square / static_cast<double>(count));
}

/// The relative scatter over the particles with lower <= x[axis] <= upper.
template <int D, class Reference>
double relative_scatter(const std::string& quantity, const std::vector<Vec<D>>& position,
                        const std::vector<double>& value, Reference&& reference, double lower,
                        double upper, int axis = 0) {
  return relative_scatter<D>(quantity, position, value, std::forward<Reference>(reference),
                             Selection::range(lower, upper, axis));
}

}  // namespace sph
