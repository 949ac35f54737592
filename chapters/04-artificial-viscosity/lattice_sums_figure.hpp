#pragma once
/// \file
/// \brief The lattice-sums figure: how far a kernel's density and gradient sums over a uniform
/// 1D lattice depart from one at each \f$ h/\Delta x \f$, beside a shock-tube error measured at
/// the same \f$ h/\Delta x \f$.
///
/// The left panel draws \f$ |\text{sum} - 1| \f$ of both sums on a log scale, so that a sum
/// that is exact shows as a dip to the bottom of the panel (an exact zero, which a log scale
/// cannot show, is drawn at \f$ 10^{-7} \f$); the right panel draws the error on a log scale.
/// Read side by side, they say whether the error follows the sums.  A program fills the curves
/// one \f$ \eta \f$ at a time and then saves the figure, as Step 2 does just below:
///
/// \code
/// app::LatticeSumsCurves curves{.error_label = "Sod 1D"};
/// ... for each eta: curves.eta.push_back(eta); curves.density_sum.push_back(...); ...
/// app::save_lattice_sums_figure(curves, "Lattice sums and the Sod error", stamp, path);
/// \endcode
///
/// The file is header-only; a program that includes it links the plotting library, sph_plot.

#include "plot/figure.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace app {

/// The curves of the lattice-sums figure, one entry per \f$ \eta = h/\Delta x \f$.
struct LatticeSumsCurves {
  std::vector<double> eta{};          ///< \f$ h/\Delta x \f$
  std::vector<double> density_sum{};  ///< \f$ \sum_j \Delta x\, W(x_j, h) \f$: 1 when exact
  std::vector<double>
      gradient_sum{};           ///< \f$ S = \sum_j \Delta x\,(x_i - x_j)\,W' \f$: 1 when exact
  std::vector<double> error{};  ///< the error measured at each \f$ \eta \f$
  std::string error_label{};    ///< the legend of the error curve (markup)
  std::string error_axis = "L_1(\\rho)";  ///< the axis label of the error panel (markup)
};

/// `departures_from_one` gives \f$ |s - 1| \f$ for each sum s, with the values below
/// \f$ 10^{-7} \f$ (an exact sum) raised to \f$ 10^{-7} \f$, where a log scale can draw them.
inline std::vector<double> departures_from_one(const std::vector<double>& sums) {
  std::vector<double> departures;
  for (double s : sums) departures.push_back(std::max(std::abs(s - 1.0), 1e-7));
  return departures;
}

/// `save_lattice_sums_figure` saves the figure to \p path: the departures of the two sums from
/// one against \f$ h/\Delta x \f$ on the left, the error on the right, with the title \p title
/// and the stamp \p stamp.
inline void save_lattice_sums_figure(const LatticeSumsCurves& curves, const std::string& title,
                                     const plot::Stamp& stamp, const std::string& path) {
  plot::Figure fig(1, 2, {.width = 1500, .height = 600});
  fig.title(title);
  fig.stamp(stamp);
  fig.panel(0)
      .xlabel("h/\\Delta x")
      .ylabel("|lattice sum - 1|")
      .yscale(plot::Scale::log)
      .ylim(3e-8, 1.0)  // (room above the sums for the legend: they touch every lower corner)
      .line(curves.eta, departures_from_one(curves.gradient_sum),
            {.label = "gradient sum S",
             .color = plot::blue,
             .marker = plot::Marker::circle,
             .marker_size = 7})
      .line(curves.eta, departures_from_one(curves.density_sum),
            {.label = "density sum",
             .color = plot::orange,
             .style = plot::Dash::dashed,
             .marker = plot::Marker::square,
             .marker_size = 7})
      .legend(plot::Corner::upper_right);
  fig.panel(1)
      .xlabel("h/\\Delta x")
      .ylabel(curves.error_axis)
      .yscale(plot::Scale::log)
      .line(curves.eta, curves.error,
            {.label = curves.error_label,
             .color = plot::black,
             .marker = plot::Marker::circle,
             .marker_size = 7})
      .legend(plot::Corner::lower_right);
  fig.save_png(path);
}

}  // namespace app
