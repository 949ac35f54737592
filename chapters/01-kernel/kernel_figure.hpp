#pragma once
/// \file
/// \brief The kernel figure: a smoothing kernel's value, slope and radial weight against
/// \f$ q = r/h \f$ in three panels, and the tail of its Fourier transform in a fourth.
///
/// Each kernel is sampled once into app::KernelCurves (value, slope and weight at \f$ h = 1 \f$)
/// and each transform into app::TransformCurve; save_kernel_figure() draws them, every kernel
/// with its own colour and dash in all three panels.  Step 6's `step6_figure`, just above, is the
/// one caller: six kernels, three transforms and the note on the M4's lobe.
///
/// Header-only: a chapter that includes it links sph_plot.

#include "plot/figure.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace app {

/// The surface of the unit sphere in \p dimension dimensions: 2, \f$ 2\pi \f$, \f$ 4\pi \f$.
constexpr double unit_sphere_surface(int dimension) {
  return dimension == 1 ? 2.0 : dimension == 2 ? 2.0 * std::numbers::pi : 4.0 * std::numbers::pi;
}

/// One kernel as the figure draws it: its legend, colour and dash, and three curves against q.
struct KernelCurves {
  std::string label;           ///< legend text, e.g. "M4, 3D"
  plot::Color color;           ///< the colour of all its curves
  plot::Dash dash;             ///< the dash of all its curves
  std::vector<double> q;       ///< \f$ q = r/h \f$, from 0 to 2.2
  std::vector<double> value;   ///< \f$ h^D W \f$
  std::vector<double> slope;   ///< \f$ h^{D+1}\, dW/dr \f$
  std::vector<double> weight;  ///< \f$ S_D\, q^{D-1}\, h^D W \f$, of unit area
};

/// The curves of kernel \p K in \p D dimensions at \p samples + 1 values of q in [0, 2.2].
template <int D, class K>
KernelCurves kernel_curves(std::string label, plot::Color color, plot::Dash dash, int samples) {
  KernelCurves c{std::move(label), color, dash, {}, {}, {}, {}};
  for (int k = 0; k <= samples; ++k) {
    const double q = 2.2 * k / samples;
    c.q.push_back(q);
    c.value.push_back(K::value(q, 1.0));
    c.slope.push_back(K::derivative(q, 1.0));
    c.weight.push_back(unit_sphere_surface(D) * std::pow(q, D - 1) * K::value(q, 1.0));
  }
  return c;
}

/// One Fourier transform as the figure draws it, against kh.
struct TransformCurve {
  std::string label;              ///< legend text
  plot::Color color;              ///< line colour
  plot::Dash dash;                ///< line dash
  std::vector<double> kh;         ///< from 0 to 20
  std::vector<double> transform;  ///< \f$ \hat W(k) \f$
};

/// The transform \p transform (a callable double(double kh)) at \p samples + 1 values of kh
/// in [0, 20].
template <class Transform>
TransformCurve transform_curve(std::string label, plot::Color color, plot::Dash dash, int samples,
                               Transform transform) {
  TransformCurve c{std::move(label), color, dash, {}, {}};
  for (int k = 0; k <= samples; ++k) {
    c.kh.push_back(20.0 * k / samples);
    c.transform.push_back(transform(c.kh.back()));
  }
  return c;
}

/// A note written into the transform panel at (\p kh, \p value), in blue.
struct TransformNote {
  double kh;         ///< x of the note's start
  double value;      ///< y of the note
  std::string text;  ///< what it says
};

/// The four panels -- (a) \f$ h^D W \f$, (b) \f$ h^{D+1} dW/dr \f$, (c) the radial weight,
/// (d) the transforms' tail, magnified to \f$ [-0.002, 0.006] \f$ -- with \p title and
/// \p stamp, written as a PNG to \p path.
inline void save_kernel_figure(const std::string& path, const std::string& title,
                               const plot::Stamp& stamp, const std::vector<KernelCurves>& kernels,
                               const std::vector<TransformCurve>& transforms,
                               const TransformNote& note) {
  plot::Figure figure(2, 2, {.width = 1600, .height = 1200});
  figure.title(title);
  figure.stamp(stamp);
  // Panels (a)-(c): every kernel in each.
  for (const KernelCurves& c : kernels) {
    const plot::LineOptions style{
        .label = c.label, .color = c.color, .style = c.dash, .width = 2.0};
    figure.panel(0).line(c.q, c.value, style);
    figure.panel(1).line(c.q, c.slope, style);
    figure.panel(2).line(c.q, c.weight, style);
  }
  figure.panel(0).xlabel("q = r/h").ylabel("h^D W").legend(plot::Corner::upper_right);
  figure.panel(1).xlabel("q = r/h").ylabel("h^{D+1} dW/dr").legend(plot::Corner::lower_right);
  figure.panel(1).hline(0.0, {.color = plot::grey, .style = plot::Dash::dotted, .width = 1.0});
  figure.panel(2)
      .xlabel("q = r/h")
      .ylabel("S_D q^{D-1} h^D W  (unit area)")
      .legend(plot::Corner::upper_right);
  /// The transforms get a panel of their own scale.  The M4's negative lobe in 3D is less than a
  /// thousandth of \f$ \hat W(0) = 1 \f$ deep and would be invisible on a scale that shows the
  /// whole transform, so panel (d) is magnified to the band around zero, with a dotted zero line
  /// for the M4 to cross and the Wendland C2 to stay above.
  // Panel (d): the transforms, the zero line and the note.
  plot::Axes& fourier = figure.panel(3);
  for (const TransformCurve& c : transforms) {
    fourier.line(c.kh, c.transform,
                 {.label = c.label, .color = c.color, .style = c.dash, .width = 2.0});
  }
  fourier.hline(0.0, {.color = plot::grey, .style = plot::Dash::dotted, .width = 1.0});
  fourier.text(note.kh, note.value, note.text, {.color = plot::blue});
  fourier.xlabel("kh")
      .ylabel("Fourier transform of W (tail, magnified)")
      .ylim(-0.002, 0.006)
      .xlim(0, 20);
  fourier.legend(plot::Corner::upper_right);
  figure.save_png(path);
}

}  // namespace app
