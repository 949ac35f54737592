#pragma once
/// \file
/// \brief Settled distributions: particles relaxed to uniform density in a periodic box.
///
/// Watkins et al. (1996, §3) test their derivatives on "5000 particles … distributed with random
/// positions in a box of unit side, and then settled to a uniform density distribution"; the
/// settled set has \f$ \bar\rho = 0.999 \f$, \f$ \sigma_\rho = 0.004 \f$.  The paper does not
/// say how it settled them.  We move the particles down the gradient of an energy that is
/// smallest when the density is uniform.
///
/// **A polytropic energy.**  Give every particle the pressure
/// \f$ P \propto \rho^\gamma \f$.  The SPH pressure force in the Hernquist & Katz form,
/// \f[ \mathbf a_i = -\sum_j m_j \left(\frac{P_i}{\rho_i^2} + \frac{P_j}{\rho_j^2}\right)
///     \nabla_i W(r_{ij}, \bar h_{ij}), \f]
/// is (for a fixed common h and equal masses) exactly \f$ -\nabla_i E / m_i \f$ for the energy
/// \f$ E = \sum_i m_i u(\rho_i) \f$ with \f$ du/d\rho = P/\rho^2 \f$.  Since
/// \f$ m_i \approx \rho_i\,\Delta V_i \f$, E approximates \f$ \int \rho\, u(\rho)\, dV \f$, a
/// convex functional of \f$ \rho \f$ for any \f$ \gamma > 0 \f$ (\f$ \rho\ln\rho \f$ for the
/// isothermal \f$ \gamma = 1 \f$, \f$ \rho^2 \f$ for \f$ \gamma = 2 \f$): at fixed total mass it is
/// smallest when the density is uniform.
///
/// Larger \f$ \gamma \f$ makes the pressure stiffer against over-densities and gives a smaller
/// final scatter (chapter 2 compares \f$ \gamma = 1, 2, 3 \f$).
///
/// **Why not descend on the scatter itself?**  It is tempting to take
/// \f$ F = \sum_i (\rho_i - \bar\rho)^2 \f$ as the functional.  We tried: the scatter falls to
/// \f$ 10^{-5} \f$, but the particles cheat -- they pair up (nearest distances of 0.004
/// \f$ \Delta x \f$) and the mean density rises by 8 %: a set of coincident pairs on a glass is as
/// uniform as the glass.  A pressure pushes particles apart at every density above the mean, so it
/// cannot be fooled that way.
///
/// **The motion.**  Overdamped, with momentum: each iteration
/// \f[ \mathbf u_i \leftarrow \mu\,\mathbf u_i + \epsilon\, h_i^2\, \mathbf a_i, \qquad
///     \mathbf x_i \leftarrow \mathbf x_i + \mathbf u_i , \f]
/// where the factor \f$ h_i^2 \f$ makes the step dimensionless (\f$ h^2 \mathbf a \sim h\,
/// \delta\rho/\rho \f$), \f$ \epsilon \f$ is the step and \f$ \mu \f$ a memory ("heavy ball")
/// that lets long, slowly decaying density waves relax in fewer iterations than plain descent.
/// No particle moves more than `max_move` h in one iteration, which tames the first, violent
/// iterations of a random start.  With a fixed h the neighbour list is built for a slightly
/// larger radius and reused until some particle has moved far enough to matter (a Verlet skin,
/// see relax_detail::RelaxNeighbours): late iterations move particles by \f$ 10^{-3} h \f$, and
/// most of them then cost a density and a force pass but no search.
///
/// **When to stop.**  We measure the density scatter \f$ \sigma_\rho/\bar\rho \f$ every iteration
/// and stop when it has not improved by a relative `min_improvement` in `patience` iterations:
/// the distribution has settled into a glass whose remaining scatter no longer falls at a useful
/// rate.  Descent on E is not descent on the scatter: near the end the scatter can creep up again
/// while E still falls, so we return the positions with the smallest scatter seen.  The result is
/// deterministic for a given start (the neighbour list and all sums are independent of the
/// thread count).

#include "sph/box.hpp"
#include "sph/density.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace sph {

/// The mean and the relative standard deviation of a set of densities.
struct DensityScatter {
  double mean = 0;      ///< \f$ \bar\rho \f$
  double sigma = 0;     ///< \f$ \sigma_\rho \f$ (population standard deviation)
  double relative = 0;  ///< \f$ \sigma_\rho / \bar\rho \f$
};

/// Mean and standard deviation of the densities (Watkins' \f$ \bar\rho \f$ and
/// \f$ \sigma_\rho \f$).
inline DensityScatter density_scatter(const std::vector<double>& density) {
  require(!density.empty(), "density scatter: no densities");
  double sum = 0;
  for (double rho : density) sum += rho;
  const double mean = sum / static_cast<double>(density.size());
  double square = 0;
  for (double rho : density) square += (rho - mean) * (rho - mean);
  const double sigma = std::sqrt(square / static_cast<double>(density.size()));
  return {mean, sigma, sigma / mean};
}

/// Parameters of relax_to_uniform_density.
struct RelaxOptions {
  SmoothingLengthRule rule = SmoothingLengthRule::fixed();  ///< how h is chosen each iteration
  DensityForm form = DensityForm::watkins();  ///< the density sum whose scatter is minimised
  double gamma = 2.0;  ///< the exponent of the relaxing pressure \f$ P \propto \rho^\gamma \f$
  double step =
      0.2;  ///< \f$ \epsilon \f$: displacement per iteration is \f$ \epsilon h^2 \mathbf a \f$
  double momentum = 0.5;  ///< \f$ \mu \f$ in [0, 1): 0 is plain gradient descent
  double max_move = 0.1;  ///< largest displacement per iteration, in units of h
  double skin =
      0.2;  ///< fixed h: neighbour list for radius (1 + skin) 2h, rebuilt after moves of skin h
  int max_iterations = 2000;  ///< give up after this many iterations
  int patience = 20;          ///< stop when no relative improvement of min_improvement in this many
  double min_improvement = 0.01;
};

/// What relax_to_uniform_density did.
struct RelaxReport {
  int iterations = 0;           ///< iterations performed (each: search, density, move)
  DensityScatter initial;       ///< scatter of the starting set
  DensityScatter final;         ///< scatter of the returned (best) set, its p.density
  std::vector<double> history;  ///< \f$ \sigma_\rho/\bar\rho \f$ at every iteration
  bool converged = false;       ///< stopped because the scatter stopped decreasing
  int list_builds = 0;          ///< neighbour searches with the enlarged radius (fixed h)
};

/// The per-particle factor \f$ B_i = P_i/\rho_i^2 \f$ of the relaxing force, with
/// \f$ P = \bar\rho\,(\rho/\bar\rho)^\gamma \f$ (sound speed 1 at the mean density).
inline double relaxing_factor(double gamma, double rho, double mean_rho) {
  return std::pow(rho / mean_rho, gamma) * mean_rho / (rho * rho);
}

/// The steepest slope of a kernel shape, \f$ \min_q dw/dq \f$, and where it is: for the M4,
/// \f$ dw/dq = -1 \f$ at \f$ q = 2/3 \f$.  Found once by a scan of the shape.
template <class Shape>
std::pair<double, double> steepest_slope() {
  static const std::pair<double, double> slope = [] {
    double q_min = 0, slope_min = 0;
    for (int k = 1; k < 20000; ++k) {
      const double q = Shape::support * k / 20000.0;
      const double s = Shape::evaluate(q).dw_dq;
      if (s < slope_min) {
        slope_min = s;
        q_min = q;
      }
    }
    return std::pair{q_min, slope_min};
  }();
  return slope;
}

/// The relaxing acceleration of particle i, the SPH pressure force
/// \f$ \mathbf a_i = -\sum_j m_j (B_i + B_j)\, \nabla_i W(r_{ij}, \bar h_{ij}) \f$ with
/// \f$ B = P/\rho^2 \f$ from relaxing_factor -- except that inside the kernel's steepest point
/// we keep the steepest slope (Thomas & Couchman 1992): the true gradient of a bell-shaped
/// kernel falls to zero as \f$ r \to 0 \f$, so two particles that start close together would
/// barely repel and stay paired.
template <int D, class K>
Vec<D> relaxing_acceleration(const Particles<D>& p, const NeighbourList<D>& list,
                             const std::vector<double>& factor, std::size_t i) {
  const auto [q_steep, slope_steep] = steepest_slope<typename K::shape>();
  Vec<D> a = Vec<D>::Zero();
  for (const Neighbour& n : list.of(i)) {
    const std::size_t j = n.index;
    const Vec<D> r_ij = list.separation(p.position, i, n);
    const double h_bar = 0.5 * (p.smoothing_length[i] + p.smoothing_length[j]);
    const double r = r_ij.norm(), q = r / h_bar;
    if (r == 0.0 || q >= K::support) continue;  // coincident: no direction to push in
    const double slope = q < q_steep ? slope_steep : K::shape::evaluate(q).dw_dq;
    const double g = K::sigma * power<D + 1>(1.0 / h_bar) * slope / r;  // grad W = g r_ij
    a -= p.mass[j] * (factor[i] + factor[j]) * g * r_ij;
  }
  return a;
}

/// Relax the particles towards uniform density in a fully periodic box (see the file comment).
/// On return the positions are settled and wrapped into the box, and p.smoothing_length,
/// p.neighbour_count and p.density belong to them.  Velocities are untouched.
namespace relax_detail {

/// The neighbour list of a relaxation.  With a fixed h it is built for the larger radius
/// \f$ (1 + s)\, 2h \f$ (s = `skin`) and kept while no particle has moved more than \f$ s h \f$
/// since the build: a pair further apart than that radius cannot have come within \f$ 2h \f$
/// (Verlet 1967).  The sums skip the extra pairs for free -- the kernel is zero there.  Between
/// builds the positions are not wrapped into the box, so the periodic images the list stores stay
/// valid.  With any other rule h changes every iteration and the list is rebuilt every time.
template <int D, class K>
class RelaxNeighbours {
 public:
  RelaxNeighbours(const SmoothingLengthRule& rule, double skin) : rule_(rule), skin_(skin) {}

  /// The list for the current positions (rebuilt if needed; h and counts per the rule).
  const NeighbourList<D>& update(Particles<D>& p, const Box<D>& box) {
    const bool reuse = rule_.mode == SmoothingLengthRule::Mode::fixed && skin_ > 0;
    if (reuse && built_ && !moved_too_far(p)) return search_.list();
    for (auto& x : p.position) x = box.wrap(x);
    if (!reuse) {
      search_.update(p, box, rule_);
      return search_.list();
    }
    const std::vector<double> h = p.smoothing_length;
    for (double& hi : p.smoothing_length) hi *= 1.0 + skin_;
    search_.update(p, box, rule_);
    p.smoothing_length = h;
    reference_ = p.position;
    built_ = true;
    ++builds_;
    return search_.list();
  }
  int builds() const { return builds_; }

 private:
  bool moved_too_far(const Particles<D>& p) const {
    for (std::size_t i = 0; i < p.size(); ++i) {
      if ((p.position[i] - reference_[i]).norm() > skin_ * p.smoothing_length[i]) return true;
    }
    return false;
  }

  SmoothingLengthRule rule_;
  double skin_;
  NeighbourSearch<D, K> search_;
  std::vector<Vec<D>> reference_;  // positions at the last build
  bool built_ = false;
  int builds_ = 0;
};

/// Check the options and the box of a relaxation.
template <int D>
void validate(const Box<D>& box, const RelaxOptions& options) {
  for (int a = 0; a < D; ++a) {
    require(box.periodic[a],
            std::string("relax: the box must be periodic (axis ") + axis_name(a) + " is open)");
  }
  require(options.gamma > 0, "relax: need gamma > 0");
  require(options.step > 0 && options.momentum >= 0 && options.momentum < 1 && options.max_move > 0,
          "relax: need step > 0, momentum in [0, 1) and max_move > 0");
  require(options.skin >= 0, "relax: need skin >= 0");
  require(options.max_iterations >= 0 && options.patience >= 1,
          "relax: need max_iterations >= 0, patience >= 1");
}

}  // namespace relax_detail

template <int D, class K = Kernel<D>>
RelaxReport relax_to_uniform_density(Particles<D>& p, const Box<D>& box,
                                     const RelaxOptions& options = {}) {
  relax_detail::validate(box, options);
  p.validate();
  const std::size_t n = p.size();
  relax_detail::RelaxNeighbours<D, K> neighbours(options.rule, options.skin);
  std::vector<Vec<D>> drift(n, Vec<D>::Zero());
  std::vector<double> factor(n);
  RelaxReport report;
  std::vector<Vec<D>> best_position;  // the positions with the smallest scatter
  double best = 0;                    // the smallest scatter so far
  int improved = 0;  // the last iteration that improved on `best` by min_improvement
  for (int iteration = 0;; ++iteration) {
    // Measure: neighbours, density and its scatter.
    const NeighbourList<D>& list = neighbours.update(p, box);
    compute_density<D, K>(p, list, options.form);
    const DensityScatter scatter = density_scatter(p.density);
    report.history.push_back(scatter.relative);
    if (iteration == 0) report.initial = scatter;
    // Remember the best set; stop when the scatter has stopped decreasing, or at the limit.
    if (iteration == 0 || scatter.relative < best) {
      if (iteration == 0 || scatter.relative < best * (1.0 - options.min_improvement))
        improved = iteration;
      best = scatter.relative;
      report.final = scatter;
      best_position = p.position;
    }
    if (iteration - improved >= options.patience) {
      report.converged = true;
      break;
    }
    if (iteration == options.max_iterations) break;
    // Move: damped step along the relaxing force, limited to max_move h.
    for (std::size_t i = 0; i < n; ++i)
      factor[i] = relaxing_factor(options.gamma, p.density[i], scatter.mean);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) {
      const double h = p.smoothing_length[i];
      drift[i] = options.momentum * drift[i] +
                 options.step * h * h * relaxing_acceleration<D, K>(p, list, factor, i);
      const double length = drift[i].norm(), limit = options.max_move * h;
      if (length > limit) drift[i] *= limit / length;
    }
    for (std::size_t i = 0; i < n; ++i) p.position[i] += drift[i];
    report.iterations = iteration + 1;
  }
  report.list_builds = neighbours.builds();
  // Return the best set, wrapped, with h, counts and density from one final search by the rule
  // (the caller's velocities and energies are untouched).
  p.position = std::move(best_position);
  for (auto& x : p.position) x = box.wrap(x);
  NeighbourSearch<D, K> search;
  search.update(p, box, options.rule);
  compute_density<D, K>(p, search.list(), options.form);
  return report;
}

}  // namespace sph
