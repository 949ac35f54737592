#pragma once
/// \file
/// \brief Self-gravity by direct summation over every pair: exact, and O(N^2).
///
/// Every particle feels every other one through the softened potential of
/// gravity/softening.hpp:
/// \f[ \mathbf a_i = -G\sum_{j\ne i} m_j\,\tfrac12\left[\phi'(r_{ij}, h_i) + \phi'(r_{ij}, h_j)
///     \right]\hat{\mathbf r}_{ij}, \qquad
///     \Phi_i = G\sum_{j} m_j\,\tfrac12\left[\phi(r_{ij}, h_i) + \phi(r_{ij}, h_j)\right], \f]
/// with the softening length equal to the smoothing length, so that gravity and pressure are
/// resolved on the same scale (Bate & Burkert 1997; Price & Monaghan 2007).  The potential
/// energy is \f$ E_\mathrm{pot} = \tfrac12\sum_i m_i\Phi_i \f$; the sum over j includes j = i,
/// the self-potential \f$ -\tfrac75 Gm_i/h_i \f$ of a particle's own smeared-out mass (in
/// \f$ E_\mathrm{pot} \f$: \f$ -\tfrac7{10}Gm_i^2/h_i \f$), as in
/// Price & Monaghan (2007) -- it is what makes the energy of a smeared-out mass distribution
/// right, and it changes as h does.
///
/// **What we leave out.**  Price & Monaghan (2007, eq 16) add a term that makes the softened
/// force the exact gradient of the potential when h changes with density; it needs the
/// grad-h factor \f$ \Omega_i \f$ and the derivative of the potential with respect to h, both
/// of which belong to a smoothing length tied to the density (\f$ \rho h^3 = \text{const}\f$).
/// Our h is set by the neighbour number (chapter 2), not by that constraint, so the term does
/// not apply in its printed form; its effect is an energy error of the order of the softened
/// part of the potential energy, which chapter 6 measures (the energy drift of the Evrard
/// collapse) rather than assumes.
///
/// Each particle's sum runs over all j in index order, on whichever thread: the result is the
/// same to the bit for any number of threads.  This is the reference the tree
/// (gravity/tree.hpp) is measured against, and the module to use below a few thousand
/// particles.

#include "sph/box.hpp"
#include "sph/error.hpp"
#include "sph/gravity/softening.hpp"
#include "sph/integration/active_set.hpp"
#include "sph/particles.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace sph {

/// Checks every gravity module makes before it sums: an open box (no periodic images:
/// Ewald sums are beyond this course) and a positive, finite softening length everywhere.
template <int D>
void require_gravity_input(const Particles<D>& p, const Box<D>& box, const char* module) {
  static_assert(D == 3,
                "self-gravity is three-dimensional here: in 1D and 2D Newton's 1/r^2 force is "
                "not the gravity of the dimension (it would be a constant, or 1/r)");
  for (int a = 0; a < D; ++a) {
    require(!box.periodic[a], std::string(module) +
                                  ": self-gravity needs an open box (a periodic axis would need "
                                  "Ewald sums, which this course does not build)");
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!(p.smoothing_length[i] > 0) || !std::isfinite(p.smoothing_length[i]) ||
        !p.position[i].allFinite()) {
      throw Error(std::string(module) + ": particle " + show(i) +
                  " has no finite position or positive softening length (h = " +
                  show(p.smoothing_length[i]) + ")");
    }
  }
}

/// Self-gravity by direct summation.
struct DirectGravity {
  static constexpr const char* name = "direct summation";
  static constexpr bool active = true;

  double G = 1.0;  ///< gravitational constant
  /// A softening length for every particle; 0 (the default): each particle's smoothing length.
  double fixed_softening = 0.0;

  DirectGravity() = default;
  explicit DirectGravity(double g) : G(g) {
    require(std::isfinite(g) && g > 0,
            "direct gravity: G must be positive and finite (got " + show(g) + ")");
  }

  /// Adds \f$ -\nabla\Phi_i \f$ to the acceleration of every particle of \p active (all by
  /// default) and keeps their \f$ \Phi_i \f$ for the energy.
  template <int D>
  void add_accelerations(Particles<D>& p, const Box<D>& box, ActiveSet active = {}) {
    require_gravity_input(p, box, "direct gravity");
    require(std::isfinite(fixed_softening) && fixed_softening >= 0,
            "direct gravity: the fixed softening length must be finite and >= 0 (got " +
                show(fixed_softening) + ")");
    const std::size_t n = p.size();
    if (active.all() || potential_.size() != n) potential_.assign(n, 0.0);
    // (one array per axis: the inner loop then streams through memory)
    std::vector<double> xs(n), ys(n), zs(n);
    for (std::size_t j = 0; j < n; ++j) {
      xs[j] = p.position[j][0];
      ys[j] = p.position[j][1];
      zs[j] = p.position[j][2];
    }
    const double* m = p.mass.data();
    // 1/h of the softening length (fixed, or each particle's h), once per particle: a pair then
    // costs one division, 1/r (see softening.hpp)
    std::vector<double> inverse_h(n);
    for (std::size_t j = 0; j < n; ++j)
      inverse_h[j] = 1.0 / (fixed_softening > 0 ? fixed_softening : p.smoothing_length[j]);
    const double* inv_h = inverse_h.data();
    const std::size_t count = active.size(n);
#pragma omp parallel for schedule(dynamic, 64) if (count >= 256)
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = active[k];
      double ax = 0, ay = 0, az = 0, phi = 0;
      const double inv_hi = inv_h[i];
      for (std::size_t j = 0; j < n; ++j) {
        const double dx = xs[i] - xs[j], dy = ys[i] - ys[j], dz = zs[i] - zs[j];
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        const gravity::Softened pair = gravity::pair_softened(r, inv_hi, inv_h[j]);
        const double f = m[j] * pair.force_over_r;
        ax -= f * dx;
        ay -= f * dy;
        az -= f * dz;
        phi += m[j] * pair.potential;
      }
      p.acceleration[i] += G * Vec<D>(ax, ay, az);
      potential_[i] = G * phi;
    }
  }

  /// \f$ \tfrac12\sum_i m_i\Phi_i \f$ at the last evaluation (which the integrators make at the
  /// current positions).
  template <int D>
  double potential_energy(const Particles<D>& p, const Box<D>&) const {
    require(potential_.size() == p.size(),
            "direct gravity: no potential yet (the accelerations were never evaluated)");
    double e = 0;
    for (std::size_t i = 0; i < p.size(); ++i) e += 0.5 * p.mass[i] * potential_[i];
    return e;
  }

  /// \f$ \Phi_i \f$ at the last evaluation.
  const std::vector<double>& potential() const { return potential_; }

 private:
  std::vector<double> potential_;
};

}  // namespace sph
