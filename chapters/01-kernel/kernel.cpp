/// \page ch01 Chapter 1: The smoothing kernel
///
/// \section ch01_intro What this chapter is about
///
/// Smoothed particle hydrodynamics replaces a fluid by particles and every field by a sum over
/// them.  The sum comes from an exact identity, \f$ A(\mathbf r) = \int A(\mathbf r')\,
/// \delta(\mathbf r - \mathbf r')\, dV' \f$, with the delta function replaced by a narrow, smooth
/// bump \f$ W \f$ of width \f$ h \f$, the **smoothing kernel**:
/// \f[ \langle A \rangle(\mathbf r) = \int A(\mathbf r')\, W(\mathbf r - \mathbf r', h)\, dV'
///     \;\approx\; \sum_j \frac{m_j}{\rho_j}\, A_j\, W(\mathbf r - \mathbf r_j, h). \f]
/// The second step treats each particle as a parcel of volume \f$ m_j/\rho_j \f$; it is
/// Watkins et al. (1996) eq A1.  Put \f$ A = \rho \f$ and the volumes cancel: the density is
/// a plain sum of kernels, \f$ \rho_i = \sum_j m_j W_{ij} \f$ (Selhammar 1997 eq 5, and the
/// subject of chapter 2).  Everything SPH does -- densities, pressure forces, viscosities --
/// is built from W and its gradient, so we begin by looking at the kernel closely.
///
/// A kernel must
///  1. integrate to one, \f$ \int W\, dV = 1 \f$, so that a constant field is reproduced;
///  2. be symmetric, \f$ W(\mathbf r) = W(-\mathbf r) \f$, so that \f$ \nabla W \f$ is odd and
///     pair forces can be made equal and opposite;
///  3. tend to the delta function as \f$ h \to 0 \f$, so that the smoothing error vanishes;
///  4. be smooth, because its derivatives appear in the equations of motion;
///  5. vanish beyond a few h -- **compact support** -- so that each sum runs over a few dozen
///     neighbours instead of all N particles.  A Gaussian satisfies 1-4 but reaches everywhere;
///     cut off at \f$ 3h \f$ it is no longer normalised or smooth.
///
/// \section ch01_m4 The M4 cubic spline
///
/// Both papers of this course use the M4 kernel of Monaghan & Lattanzio (1985)
/// (\ref papers_selhammar_eq3 "Selhammar eq 3", \ref papers_watkins_eqA2 "Watkins eqs A2-A3"
/// in our reading notes).  With \f$ q = r/h \f$ it is
/// \f[ W(r, h) = \frac{\sigma_D}{h^D}\, w(q), \qquad
///     w(q) = \begin{cases} 1 - \frac32 q^2 + \frac34 q^3, & 0 \le q < 1,
///                          \\ \frac14 (2 - q)^3, & 1 \le q < 2, \\ 0, & q \ge 2. \end{cases} \f]
/// Its support is \f$ 2h \f$: the h of the papers is *half* the radius of the kernel, which
/// matters when we read their neighbour numbers in chapter 2.  The shape is the cubic
/// B-spline: four unit top-hats convolved with each other.  Start from the top-hat
/// \f$ B_1(q) = 1 \f$ on \f$ |q| < \frac12 \f$; convolving it with itself gives the triangle
/// \f$ B_2 \f$ on \f$ |q| < 1 \f$, once more the piecewise quadratic \f$ B_3 \f$ on
/// \f$ |q| < \frac32 \f$, and once more the piecewise cubic \f$ B_4 \f$ on \f$ |q| < 2 \f$,
/// which is \f$ \frac23 w(q) \f$.  Every convolution with a top-hat integrates once, so it
/// makes the result one derivative smoother and keeps its integral at one.  That origin
/// explains the kernel's virtues.  It is a piecewise cubic whose value, slope and curvature
/// are continuous (C², point 4); it is positive and has unit integral in 1D by construction;
/// and in 1D its Fourier transform is the product of the four top-hats' transforms,
/// \f[ \hat W(k) = \left(\frac{\sin(kh/2)}{kh/2}\right)^4 \qquad (D = 1), \f]
/// which we shall meet again in chapter 2, where it decides how accurately a lattice of
/// particles represents a uniform density.  It is also the lowest-order spline that is C² --
/// cheap to evaluate, with support just wide enough (about 60 neighbours in 3D) to give
/// smooth sums.
///
/// The normalisation \f$ \sigma_D \f$ follows from point 1.  In D dimensions the volume element
/// of a spherical shell is \f$ S_D r^{D-1} dr \f$ with \f$ S_D = 2, 2\pi, 4\pi \f$, so
/// \f[ 1 = \int W\, dV = \sigma_D\, S_D \int_0^2 w(q)\, q^{D-1}\, dq
///     \quad\Longrightarrow\quad \sigma_D = \frac{1}{S_D\, I_D}, \qquad
///     I_D = \int_0^2 w(q)\, q^{D-1}\, dq = \frac34,\ \frac{7}{20},\ \frac14 . \f]
/// Hence \f$ \sigma_1 = 2/3 \f$, \f$ \sigma_2 = 10/(7\pi) \f$, \f$ \sigma_3 = 1/\pi \f$.
/// Watkins writes the same kernel as \f$ \eta_d (\frac23 - u^2 + \frac12 u^3) \f$ with
/// \f$ \eta_d = 1/h,\ 15/(7\pi h^2),\ 3/(2\pi h^3) \f$ (eq A3): the factor \f$ \frac23 \f$ moved
/// into the normalisation.  The program computes the \f$ I_D \f$ by quadrature and checks that
/// the library's table (`lib/sph/kernel.hpp`), Selhammar's eq 3 and Watkins' eq A3 all agree.
///
/// For comparison we carry the Wendland (1995) C2 kernel, scaled to the same support
/// \f$ 2h \f$.  It is as smooth as the M4 (twice differentiable) and -- the property that
/// matters -- its Fourier
/// transform is positive in every dimension, which protects it from the *pairing instability*
/// that afflicts the M4 at large neighbour numbers (Dehnen & Aly 2012).  We shall see the
/// M4's negative Fourier lobe in 3D below.
///
/// \section ch01_program The program
///
/// Nothing in this chapter is physics yet: no particles, no time steps.  But the later chapters
/// evaluate this kernel billions of times, and a kernel that is slightly wrong does not announce
/// itself.  A normalisation off by a rational factor makes every density off by that factor and
/// every figure still smooth; a gradient with the wrong sign in one piece makes particles attract
/// where they should repel, and the first symptom may be a clumpy glass three chapters later.  So
/// the program checks every property this section has claimed, by numbers against exact values,
/// and draws the kernel.  It has six steps, each a function below under its own heading, and
/// `main` at the end calls them in order:
///  1. integrals of the kernel over the radius by Simpson's rule (a tool);
///  2. the Fourier transform of a radial kernel (a tool);
///  3. the kernel's derivative against a finite difference of its value (a tool);
///  4. the normalisation table: \f$ \sigma_D \f$ three ways, \f$ \int W\,dV \f$, the derivative's
///     error and the second moment, in 1D, 2D and 3D for both kernels, each checked;
///  5. the transform measured: the M4 as the cubic B-spline in 1D, its negative lobe in 3D;
///  6. the figure.
///
/// The output is deterministic: it does not depend on the machine or the number of threads.

#include "app/chapter.hpp"
#include "kernel_figure.hpp"
#include "app/text.hpp"
#include "plot/figure.hpp"
#include "sph/kernel.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace {

using std::numbers::pi;

/// \section ch01_quadrature Step 1: integrals of the kernel by quadrature
///
/// Every check in this chapter is an integral of the kernel over the radius.  The shape is a
/// different cubic on \f$ [0, 1) \f$ and \f$ [1, 2) \f$, so we integrate each piece separately
/// with the composite Simpson rule, which is then exact up to round-off for integrands that
/// are polynomials of degree three and accurate to \f$ O(\delta q^4) \f$ for the higher powers
/// of q that the moments bring in.  `intervals` is the number of Simpson intervals per piece.
///
/// Why split at the knot?  A Simpson panel that straddled \f$ q = 1 \f$ would integrate a
/// function that is one cubic on the left of a point inside it and another on the right; there
/// the rule is no longer exact, and the 1D normalisation, a cubic on each piece, would carry a
/// quadrature error instead of round-off.  With the knot on a panel boundary each piece is a
/// single polynomial, and the error of the rule is that of a smooth integrand,
/// \f$ -\frac{\delta q^4}{180} \left[ f'''(b) - f'''(a) \right] \f$ on each piece
/// \f$ [a, b] \f$: it vanishes for cubics and falls sixteen-fold when the intervals double.  (The
/// Wendland C2 kernel is one polynomial on the whole support; for it the split is harmless.)

template <class F>
double integrate_pieces(F f, int intervals) {
  double total = 0;
  for (int piece = 0; piece < 2; ++piece) {
    const double a = piece, dq = 1.0 / intervals;
    double sum = f(a) + f(a + 1.0);  // the kernel is continuous at the knots
    for (int k = 1; k < intervals; ++k) sum += (k % 2 ? 4.0 : 2.0) * f(a + k * dq);
    total += sum * dq / 3.0;
  }
  return total;
}

/// \f$ \int W\,dV \f$ for kernel K at smoothing length h: the normalisation test.  We integrate
/// the dimensional W (not the shape) so that the library's \f$ h^{-D} \f$ is tested too.  With
/// \f$ r = qh \f$ the integral over space becomes one over the two pieces,
/// \f$ \int W\,dV = S_D\, h \int_0^2 W(qh, h)\, (qh)^{D-1}\, dq \f$, with the surface
/// \f$ S_D \f$ of the unit sphere from `app::unit_sphere_surface` (a one-line function that
/// panel (c) of the figure needs too, so it lives in the file kernel_figure.hpp, shown in Step 6).
template <int D, class K>
double kernel_integral(double h, int intervals) {
  return app::unit_sphere_surface(D) * h *
         integrate_pieces([&](double q) { return K::value(q * h, h) * std::pow(q * h, D - 1); },
                          intervals);
}

/// \f$ \int r^2 W\, dV / h^2 \f$: the kernel's second moment in units of \f$ h^2 \f$.
template <int D, class K>
double second_moment(int intervals) {
  return app::unit_sphere_surface(D) * K::sigma *
         integrate_pieces(
             [](double q) { return q * q * K::shape::evaluate(q).w * std::pow(q, D - 1); },
             intervals);
}

/// \section ch01_fourier Step 2: the Fourier transform
///
/// For a radial kernel the Fourier transform is itself radial.  In 1D it is a cosine
/// transform, in 3D the familiar \f$ \sin(kr)/(kr) \f$ transform:
/// \f[ \hat W_{1}(k) = 2\int_0^{2h} W(r) \cos(kr)\, dr, \qquad
///     \hat W_{3}(k) = 4\pi \int_0^{2h} W(r)\, \frac{\sin kr}{kr}\, r^2\, dr . \f]
/// \f$ \hat W(0) = 1 \f$ is the normalisation again; the behaviour at large k says how strongly
/// the kernel suppresses structure smaller than h.  Smoothing a wave \f$ \sin(kx) \f$ multiplies
/// its amplitude by \f$ \hat W(k) \f$ -- the smoothing error of SPH in one number.

template <int D, class K>
double fourier_transform(double kh, int intervals) {
  static_assert(D == 1 || D == 3, "the radial transforms are written for 1D and 3D");
  const double h = 1.0;
  if constexpr (D == 1) {
    return 2.0 * h *
           integrate_pieces([&](double q) { return K::value(q, h) * std::cos(kh * q); }, intervals);
  } else {
    auto sinc = [](double x) { return std::abs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x; };
    return 4.0 * pi *
           integrate_pieces([&](double q) { return K::value(q, h) * sinc(kh * q) * q * q; },
                            intervals);
  }
}

/// \section ch01_gradient Step 3: the gradient against finite differences
///
/// The library returns \f$ dw/dq \f$ and \f$ (dw/dq)/q \f$ from the same call, so that
/// \f$ \nabla_i W = \frac{\sigma_D}{h^{D+2}} \frac{1}{q}\frac{dw}{dq}\, \mathbf r_{ij} \f$ never
/// divides by \f$ r \f$: two particles on top of each other get a zero gradient, not a NaN.
/// We compare \f$ dW/dr \f$ with a centred difference of W at many radii, and report the worst
/// relative error (with an absolute floor of \f$ 10^{-8} \f$ of the kernel's scale, since the
/// derivative passes through zero at the origin and at the support).
///
/// Three choices in it deserve a word.  The step \f$ \delta r = 10^{-6} h \f$ sits near the
/// balance of the two errors of a centred difference: its truncation error,
/// \f$ \frac16 \delta r^2 W''' \f$, grows with \f$ \delta r \f$, while the round-off of
/// subtracting two nearly equal values of W, about \f$ \epsilon W / \delta r \f$ with
/// \f$ \epsilon \approx 10^{-16} \f$, shrinks with it; the two cross near
/// \f$ \delta r \sim \epsilon^{1/3} h \f$, a few millionths of h.  The radii are
/// \f$ r = 2hk/N \f$ for \f$ k = 1, \ldots, N-1 \f$: the origin and the edge of the support are
/// approached but not sampled, and the sample \f$ k = N/2 \f$ falls on the knot \f$ q = 1 \f$,
/// where the difference straddles both pieces -- two pieces whose slopes did not meet would show
/// there.  And \f$ h = 0.7 \f$ rather than 1, so that a wrong power of h in the derivative's
/// normalisation \f$ \sigma_D / h^{D+1} \f$ cannot hide.

template <int D, class K>
double worst_gradient_error(int samples) {
  const double h = 0.7, dr = 1e-6 * h, floor = 1e-8 * K::value(0, h) / h;
  double worst = 0;
  for (int k = 1; k < samples; ++k) {
    const double r = 2.0 * h * k / samples;
    const double fd = (K::value(r + dr, h) - K::value(r - dr, h)) / (2 * dr);
    worst = std::max(worst, std::abs(K::derivative(r, h) - fd) / (std::abs(fd) + floor));
  }
  return worst;
}

/// \section ch01_table Step 4: the normalisation table
///
/// Steps 1-3 were tools; this step uses them.  One row per kernel and dimension: the shape
/// integral \f$ I_D \f$ by quadrature, the \f$ \sigma_D \f$ it implies, the library's
/// \f$ \sigma_D \f$, the reference value (for the M4 Watkins' eq A3 times \f$ \frac23 \f$,
/// which in 3D is also Selhammar's eq 3; for the Wendland C2 Dehnen & Aly 2012, Table 1, rescaled
/// to support 2h), \f$ \int W\,dV - 1 \f$, the worst relative error of \f$ dW/dr \f$ against
/// finite differences, and the second moment \f$ \langle r^2 \rangle / h^2 \f$.
///
/// Each row is also checked, against a tolerance that says what could go wrong (see "The checks"
/// below for where each number comes from): \f$ \int W\,dV \f$ is one to \f$ 10^{-10} \f$, the
/// three values of \f$ \sigma_D \f$ agree, the derivative agrees with the finite difference, and
/// the M4's shape integrals are the fractions \f$ \frac34, \frac{7}{20}, \frac14 \f$ of the
/// text.
///
/// <b>What to look for.</b>  Three columns of \f$ \sigma_D \f$ that agree to every printed
/// digit: the quadrature, the library and the papers are the same kernel.  A column
/// \f$ \int W\,dV - 1 \f$ of round-off (\f$ 10^{-15} \f$ to \f$ 10^{-12} \f$): the integral was
/// taken of the dimensional \f$ W(r, h) \f$ at \f$ h = 0.37 \f$, so the library's
/// \f$ h^{-D} \f$ is tested as well as its shape.  A gradient error of 1 to
/// \f$ 3\cdot 10^{-7} \f$ in every row, the same for any `--intervals`, because it is the finite
/// difference's error, not the kernel's (the results explain it): \f$ 3.3\cdot 10^{-7} \f$
/// wherever the kernel ends as \f$ (2-q)^3 \f$ (the M4, the C2 in 1D), \f$ 1.25\cdot 10^{-7} \f$
/// for the C2's \f$ (2-q)^4 \f$ ending in 2D and 3D.  And the last column, which is different
/// for the two kernels at the same h: they do not smooth equally.
///
/// The reference values in the table below are typed as the papers print them, not as the
/// simplified fractions of the text, so that each can be compared with its equation by eye:
/// Watkins' \f$ \eta_d \f$ times \f$ \frac23 \f$ for the M4, and for the Wendland C2 Dehnen &
/// Aly's \f$ \sigma = \frac54, \frac7\pi, \frac{21}{2\pi} \f$ for a support H, divided by
/// \f$ 2^D \f$ because our support is \f$ H = 2h \f$ and \f$ H^{-D} = 2^{-D} h^{-D} \f$.  Within a
/// row, the shape integral and the second moment use the dimensionless shape \f$ w(q) \f$ and the
/// table's \f$ \sigma_D \f$; the volume integral uses the dimensional \f$ W(r, h) \f$ that every
/// later chapter calls.  The first two test the table, the third the evaluator.

struct Row {
  std::string kernel;
  int dimension;
  double shape_integral, sigma_from_integral, sigma_library, sigma_reference, volume_integral,
      gradient_error, moment;
};

template <int D, class K>
Row normalisation_row(const std::string& name, double sigma_reference, int intervals) {
  Row row{name, D, 0, 0, 0, sigma_reference, 0, 0, 0};
  row.shape_integral = integrate_pieces(
      [](double q) { return K::shape::evaluate(q).w * std::pow(q, D - 1); }, intervals);
  row.sigma_from_integral = 1.0 / (app::unit_sphere_surface(D) * row.shape_integral);
  row.sigma_library = K::sigma;
  row.volume_integral = kernel_integral<D, K>(0.37, intervals);
  row.gradient_error = worst_gradient_error<D, K>(2000);
  row.moment = second_moment<D, K>(intervals);
  return row;
}

/// The library's kernel is a template over the dimension and the shape, with the M4 as the
/// default shape; six aliases name the kernels of the table.  Then the step itself: it builds the
/// six rows with the papers' normalisations typed in, prints the table, and checks it.

// The kernels of the chapter: the M4 and the Wendland C2 in 1D, 2D and 3D.
using M4_1 = sph::Kernel<1>;
using M4_2 = sph::Kernel<2>;
using M4_3 = sph::Kernel<3>;
using C2_1 = sph::Kernel<1, sph::WendlandC2<1>>;
using C2_2 = sph::Kernel<2, sph::WendlandC2<2>>;
using C2_3 = sph::Kernel<3, sph::WendlandC2<3>>;

void step4_normalisation_table(app::Chapter& chapter, int intervals) {
  // The papers' normalisations: Selhammar eq 3 in 3D, Watkins eq A3 times 2/3 in 1D-3D.
  const std::vector<Row> rows = {
      normalisation_row<1, M4_1>("M4", 2.0 / 3.0 * 1.0, intervals),
      normalisation_row<2, M4_2>("M4", 2.0 / 3.0 * 15.0 / (7.0 * pi), intervals),
      normalisation_row<3, M4_3>("M4", 2.0 / 3.0 * 3.0 / (2.0 * pi), intervals),
      normalisation_row<1, C2_1>("Wendland C2", 5.0 / 8.0, intervals),
      normalisation_row<2, C2_2>("Wendland C2", 7.0 / (4.0 * pi), intervals),
      normalisation_row<3, C2_3>("Wendland C2", 21.0 / (16.0 * pi), intervals),
  };
  std::printf("Normalisation of the kernels, W = sigma_D / h^D w(r/h), support 2h;\n");
  std::printf("I_D = int_0^2 w(q) q^(D-1) dq, S_D = 2, 2 pi, 4 pi\n\n");
  std::printf("%-11s %1s %12s %12s %12s %12s %11s %9s %9s\n", "kernel", "D", "I_D", "1/(S_D I_D)",
              "sigma (lib)", "sigma (ref)", "int W dV-1", "dW/dr err", "<r^2>/h^2");

  /// Each row is printed and then checked four times, as listed above.  A failed check does not
  /// stop the program: `chapter.check` records it with a message that quotes the number it found,
  /// the remaining rows are still printed, and the run ends with the list of failures.
  for (const Row& r : rows) {
    std::printf("%-11s %1d %12.10f %12.10f %12.10f %12.10f %11.2e %9.2e %9.6f\n", r.kernel.c_str(),
                r.dimension, r.shape_integral, r.sigma_from_integral, r.sigma_library,
                r.sigma_reference, r.volume_integral - 1.0, r.gradient_error, r.moment);
    const std::string who = r.kernel + " in " + std::to_string(r.dimension) + "D";
    chapter.check(
        std::abs(r.volume_integral - 1.0) < 1e-10,
        who + ": int W dV = " + app::format("%.15f", r.volume_integral) + ", expected 1 to 1e-10");
    chapter.check(std::abs(r.sigma_library / r.sigma_reference - 1.0) < 1e-14,
                  who + ": library sigma " + app::format("%.15f", r.sigma_library) +
                      " differs from the reference " + app::format("%.15f", r.sigma_reference));
    chapter.check(std::abs(r.sigma_from_integral / r.sigma_library - 1.0) < 1e-10,
                  who + ": sigma from the quadrature " +
                      app::format("%.15f", r.sigma_from_integral) + " differs from the library's");
    chapter.check(r.gradient_error < 1e-6, who + ": dW/dr differs from finite differences by " +
                                               app::format("%.2e", r.gradient_error) +
                                               " (relative), limit 1e-6");
  }
  // The exact shape integrals of the M4 quoted in the text: 3/4, 7/20, 1/4.
  const double exact_integrals[] = {0.75, 0.35, 0.25};
  for (int d = 0; d < 3; ++d) {
    chapter.check(std::abs(rows[d].shape_integral - exact_integrals[d]) < 1e-10,
                  "M4 shape integral I_" + std::to_string(d + 1) + " = " +
                      app::format("%.15f", rows[d].shape_integral) + ", expected " +
                      app::format("%.4f", exact_integrals[d]));
  }

  /// The second moment \f$ \langle r^2 \rangle = \int r^2 W\, dV \f$ sets the leading
  /// smoothing error: expanding \f$ A(\mathbf r') \f$ to second order under the integral,
  /// \f$ \langle A\rangle = A + \frac{\langle r^2\rangle}{2D} \nabla^2 A + O(h^4) \f$.  For the
  /// 1D M4 it is \f$ h^2/3 \f$ -- the variance of four unit top-hats, \f$ 4 \times \frac1{12} \f$
  /// -- so a wave \f$ \sin kx \f$ is smoothed by \f$ 1 - k^2h^2/6 \f$, the leading term of
  /// \f$ \hat W(k) \f$ above.  The error is second order in h: halving h quarters it.
  chapter.check(std::abs(rows[0].moment - 1.0 / 3.0) < 1e-12,
                "1D M4 second moment " + app::format("%.15f", rows[0].moment) + ", expected 1/3");
  double worst_integral = 0;
  for (const Row& r : rows)
    worst_integral = std::max(worst_integral, std::abs(r.volume_integral - 1.0));
  chapter.summary("error", "max |int W dV - 1| = " + app::format("%.1e", worst_integral));
}

/// \section ch01_fourier_measured Step 5: the transform, measured
///
/// Two numbers from Step 2's transform.  In 1D we compare the computed transform of the M4 with
/// the B-spline formula \f$ (\sin(kh/2)/(kh/2))^4 \f$ at 400 values of kh: if the M4 is the cubic
/// B-spline, the two agree to the quadrature's accuracy.  In 3D we look for the smallest value of
/// each kernel's transform over \f$ 0 < kh \le 20 \f$, which tells whether the kernel is safe
/// from the pairing instability (a negative value means it is not, at large enough neighbour
/// numbers).
///
/// <b>What to look for.</b>  A 1D difference far below the check's \f$ 10^{-9} \f$: round-off
/// (\f$ 10^{-14} \f$) at the default 2000 intervals, a few \f$ 10^{-12} \f$ with `--quick`; a 3D
/// minimum below zero for the M4, near \f$ kh \approx 8 \f$, and a positive one for the
/// Wendland C2.
///
/// The scans are plain grids.  The 1D comparison takes kh in steps of 0.05; at kh = 20 the
/// integrand \f$ W \cos(kh\, q) \f$ oscillates with a period of 0.31 in q, which still leaves
/// about a hundred Simpson intervals per period at the quick setting of 400 per piece, so the
/// quadrature resolves the transform over the whole range.  The 3D search takes steps of 0.01.
/// The M4's 3D transform is negative between its zero at \f$ kh = 2\pi \f$ and kh of about 9
/// (and again, more weakly, beyond \f$ 4\pi \f$), so the grid puts more than two hundred points
/// in the lobe and finds its deepest point to 0.01 in kh.

/// The deepest point of the 3D M4 transform, and the smallest value of the 3D Wendland C2's.
struct Lobe {
  double m4_min = 1, m4_at = 0, c2_min = 1;
};

Lobe step5_transform_measured(app::Chapter& chapter, int intervals) {
  double worst_fourier = 0;
  for (int k = 1; k <= 400; ++k) {
    const double kh = 0.05 * k;
    const double bspline = std::pow(std::sin(kh / 2) / (kh / 2), 4);
    worst_fourier =
        std::max(worst_fourier, std::abs(fourier_transform<1, M4_1>(kh, intervals) - bspline));
  }

  /// The 3D search keeps not only the M4's minimum but also where it lies: Step 6 writes its note
  /// into the figure at that kh.
  Lobe lobe;
  for (int k = 1; k <= 2000; ++k) {
    const double kh = 0.01 * k;
    const double m4 = fourier_transform<3, M4_3>(kh, intervals),
                 c2 = fourier_transform<3, C2_3>(kh, intervals);
    if (m4 < lobe.m4_min) {
      lobe.m4_min = m4;
      lobe.m4_at = kh;
    }
    lobe.c2_min = std::min(lobe.c2_min, c2);
  }
  std::printf(
      "\nFourier transform of the M4 in 1D against (sin(kh/2)/(kh/2))^4, 0 < kh <= 20:\n"
      "  largest difference %.2e\n",
      worst_fourier);
  std::printf(
      "Smallest value of the 3D transform for 0 < kh <= 20:\n"
      "  M4 %.3e (at kh = %.2f), Wendland C2 %.3e\n",
      lobe.m4_min, lobe.m4_at, lobe.c2_min);
  chapter.check(worst_fourier < 1e-9, "1D M4 transform differs from the B-spline formula by " +
                                          app::format("%.2e", worst_fourier));
  chapter.check(lobe.m4_min < -1e-4, "expected a negative lobe of the 3D M4 transform, minimum " +
                                         app::format("%.3e", lobe.m4_min));
  chapter.check(lobe.c2_min > -1e-9,
                "the 3D Wendland C2 transform went negative: " + app::format("%.3e", lobe.c2_min));
  chapter.summary("m4_3d_fourier_min", app::format("%.4e", lobe.m4_min));
  return lobe;
}

/// \section ch01_figure Step 6: the figure
///
/// Four panels.  (a) \f$ h^D W \f$ against \f$ q = r/h \f$ -- the kernel as a sum sees it, in
/// each dimension; (b) its slope \f$ h^{D+1}\, dW/dr \f$, whose most negative point (at
/// \f$ q = 2/3 \f$ for the M4) is where a neighbour pushes hardest; (c) the *radial weight*
/// \f$ S_D\, q^{D-1}\, h^D W \f$, the share of the kernel's integral at each radius (each curve
/// has unit area) -- in 3D most of the weight sits near \f$ q = 1 \f$, not at the centre;
/// (d) the tail of the Fourier transform, magnified, where the M4 goes negative in 3D and the
/// Wendland C2 does not.
///
/// <b>What to look for.</b>  In (a), that the M4 has the same shape in every dimension and only its
/// height \f$ \sigma_D \f$ changes (0.67, 0.45, 0.32): the same unit integral is spread over more
/// volume, since a shell's volume grows as \f$ q^{D-1} \f$; in (c), that the 3D curves vanish at
/// the centre; in (d), the blue solid curve dipping below the dotted zero line while the blue
/// dashed one stays above it.
///
/// The step samples each kernel at \f$ h = 1 \f$ over \f$ 0 \le q \le 2.2 \f$, a little past the
/// support so that each curve is seen to arrive at zero and stay there, and each transform over
/// \f$ 0 \le kh \le 20 \f$ with the quadrature of Step 2.  The drawing -- the panels, their labels
/// and legends, the magnified range of (d) -- is `app::save_kernel_figure`, in the file
/// kernel_figure.hpp shown after this step's code; what the chapter decides is what is compared:
/// the colour gives the dimension, the dash the kernel, and the note in (d) marks the minimum that
/// Step 5 found.

void step6_figure(const app::Chapter& chapter, int intervals, int samples, const Lobe& lobe) {
  using plot::Dash;
  const std::vector<app::KernelCurves> kernels = {
      app::kernel_curves<1, M4_1>("M4, 1D", plot::black, Dash::solid, samples),
      app::kernel_curves<2, M4_2>("M4, 2D", plot::red, Dash::solid, samples),
      app::kernel_curves<3, M4_3>("M4, 3D", plot::blue, Dash::solid, samples),
      app::kernel_curves<1, C2_1>("C2, 1D", plot::black, Dash::dashed, samples),
      app::kernel_curves<2, C2_2>("C2, 2D", plot::red, Dash::dashed, samples),
      app::kernel_curves<3, C2_3>("C2, 3D", plot::blue, Dash::dashed, samples)};
  const std::vector<app::TransformCurve> transforms = {
      app::transform_curve("M4, 1D = (sin(kh/2)/(kh/2))^4", plot::black, Dash::solid, samples,
                           [&](double kh) { return fourier_transform<1, M4_1>(kh, intervals); }),
      app::transform_curve("M4, 3D", plot::blue, Dash::solid, samples,
                           [&](double kh) { return fourier_transform<3, M4_3>(kh, intervals); }),
      app::transform_curve("C2, 3D", plot::blue, Dash::dashed, samples,
                           [&](double kh) { return fourier_transform<3, C2_3>(kh, intervals); })};
  app::save_kernel_figure(
      chapter.figure_path("kernel.png"),
      "The M4 cubic spline (solid) and the Wendland C2 kernel (dashed), support 2h",
      plot::Stamp{.kernel = "M4 and Wendland C2", .run_time = chapter.seconds()}, kernels,
      transforms,
      {lobe.m4_at + 0.6, lobe.m4_min, "M4 in 3D < 0 near kh = " + app::format("%.1f", lobe.m4_at)});
  std::printf("\nFigure: kernel.png in the output directory\n");
}

/// The file kernel_figure.hpp holds the drawing: the curves sampled from each kernel and
/// transform, and the four panels made from them.  It is plotting code, no SPH, but it is the
/// code that makes the figure, so we show it whole.  It also holds `app::unit_sphere_surface`,
/// the \f$ S_D \f$ of Steps 1 and 4.
///
/// \show_file kernel_figure.hpp

}  // namespace

/// \section ch01_checks The checks
///
/// Every check compares a number with its exact value and a stated tolerance.  The
/// tolerances are not arbitrary:
///  - \f$ \int W\,dV = 1 \f$ to \f$ 10^{-10} \f$: Simpson's rule with 400 or more intervals per
///    kernel piece is accurate to about \f$ 10^{-11} \f$ for the worst integrands, those of the
///    2D rows and of the Wendland C2 (the M4's 1D and 3D integrands are integrated exactly), and
///    round-off is \f$ 10^{-14} \f$; a wrong normalisation would be off by
///    a rational factor, not by \f$ 10^{-10} \f$.
///  - the library's \f$ \sigma_D \f$ equals the papers' to \f$ 10^{-14} \f$: both are the same
///    fraction of \f$ \pi \f$ computed in double precision.
///  - \f$ dW/dr \f$ against finite differences to \f$ 10^{-6} \f$ relative: the difference
///    quotient's own truncation error is \f$ 3\cdot 10^{-7} \f$ at its worst (next to the
///    support's edge, see the results), so a tighter bound would test the finite difference,
///    not the kernel.
///  - the 1D transform against \f$ (\sin(kh/2)/(kh/2))^4 \f$ to \f$ 10^{-9} \f$: the two are
///    the same function if and only if the M4 is the cubic B-spline.

/// \section ch01_next What comes next
///
/// Chapter 2 puts particles under the kernel: the density sum \f$ \rho_i = \sum_j m_j W_{ij} \f$,
/// the neighbour search that finds the j within \f$ 2h \f$, and the choice of h.  Two results of
/// this chapter return there.  The Fourier transform decides how well a lattice of particles
/// represents a uniform density: by Poisson summation the lattice's density error is the sum of
/// the transform over its reciprocal lattice vectors, which is why that error vanishes at
/// \f$ h = \Delta x \f$ in 1D, where \f$ (\sin(kh/2)/(kh/2))^4 \f$ has its zeros.  And the radial
/// weight of panel (c) explains why the error in 3D is so sensitive to where the lattice's shells
/// of neighbours fall relative to h.

/// \section ch01_main The main program
///
/// The main program reads its one option, then runs the steps in order: the table (Step 4,
/// which uses the tools of Steps 1 and 3), the transform (Step 5, with the tool of Step 2) and
/// the figure (Step 6).  With `--quick` it uses 400 instead of 2000 Simpson intervals per piece
/// and fewer figure samples (the checks hold either way); `--intervals` sets the quadrature
/// directly, so that a reader can watch the checks fail when the quadrature is too coarse.

int main(int argc, char** argv) {
  return app::run_main([&] {
    app::Chapter chapter("01-kernel", "Chapter 1: The smoothing kernel", argc, argv);
    int intervals = 2000;
    // (the cost grows with the intervals: 20000, the largest allowed, takes some ten seconds)
    chapter.parameter("--intervals", intervals, "Simpson intervals per kernel piece (even)", 400)
        .check(app::between(2, 20000))
        ->check(app::require<int>([](int n) { return n % 2 == 0; }, "must be even"));
    if (int rc = chapter.parse(); rc >= 0) return rc;
    const int samples = chapter.quick() ? 200 : 800;

    step4_normalisation_table(chapter, intervals);
    const Lobe lobe = step5_transform_measured(chapter, intervals);
    step6_figure(chapter, intervals, samples, lobe);
    return chapter.finish();
  });
}
