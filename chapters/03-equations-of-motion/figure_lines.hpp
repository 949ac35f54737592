#pragma once
/// \file
/// \brief Lines added to a figure that is already drawn: the exact profiles of a second
/// Riemann problem in the four panels of a shock-tube figure, and a guide line of a given slope
/// through the last point of an error curve.
///
/// app::shock_tube_figure draws a run against the exact solution of its own tube.  A chapter that
/// has a second prediction for the same run -- the exact solution of another gas -- draws it
/// into the same panels before the figure is saved; a chapter that plots an error against run
/// time marks the slope an expected order of convergence would give:
///
/// \code
/// plot::Figure figure = app::shock_tube_figure(...);
/// app::add_exact_lines(figure, other_gas, 0.2, 2.0, "prediction", plot::blue);
/// figure.save_png(path);
///
/// plot::Figure errors = app::error_figure(study, options);
/// app::add_slope_guide(errors.panel(0), study.curve("AV", "L1(rho)"), -0.5, "\\propto t^{-1/2}");
/// \endcode
///
/// Header-only: a chapter that includes it links sph_plot.

#include "plot/figure.hpp"
#include "sph/measures/convergence.hpp"
#include "sph/reference/riemann.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace app {

/// Draws the exact \f$ \rho \f$, \f$ v_x \f$, P and u of \p solution at time \p t as dashed
/// lines of colour \p color into the first four panels of \p figure, in the order of
/// app::shock_tube_figure, over \f$ -0.5 \le x \le 0.5 \f$ at 4000 points.  The pressure is
/// multiplied by \p pressure_factor, for a run whose reported pressure is a multiple of the
/// solution's (the internal energy is not: it is the same u in both descriptions).
inline void add_exact_lines(plot::Figure& figure, const sph::RiemannSolution& solution, double t,
                            double pressure_factor, const std::string& label, plot::Color color) {
  std::vector<double> x, rho, v, P, u;
  for (int k = 0; k < 4000; ++k) {
    x.push_back(-0.5 + k / 3999.0);
    sph::GasState w = solution.sample(x.back(), t);
    w.pressure *= pressure_factor;
    rho.push_back(w.density);
    v.push_back(w.velocity);
    P.push_back(w.pressure);
    u.push_back(solution.internal_energy(x.back(), t));
  }
  const std::vector<double>* values[] = {&rho, &v, &P, &u};
  for (int k = 0; k < 4; ++k) {
    figure.panel(k).line(
        x, *values[k], {.label = label, .color = color, .style = plot::Dash::dashed, .width = 1.6});
  }
}

/// Draws into \p axes a dotted grey guide line \f$ e \propto t^{\,\rm exponent} \f$ across the
/// time span of \p curve, through its last (finest) point: a curve parallel to it falls at the
/// rate the exponent stands for.
inline void add_slope_guide(plot::Axes& axes, const sph::ErrorCurve& curve, double exponent,
                            const std::string& label) {
  const std::vector<double> t = {curve.seconds.front(), curve.seconds.back()};
  const std::vector<double> e = {curve.error.back() * std::pow(t[1] / t[0], -exponent),
                                 curve.error.back()};
  axes.line(t, e, {.label = label, .color = plot::grey, .style = plot::Dash::dotted, .width = 1.3});
}

}  // namespace app
