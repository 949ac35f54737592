#pragma once
/// \file
/// \brief The potential of a point mass, softened: \f$ \Phi = -GM/\sqrt{r^2 + \epsilon^2} \f$.
///
/// The central star of Watkins et al. (1996) sect. 4.2 (eq 22: the viscous ring orbits a mass
/// \f$ M \f$ at the origin, \f$ G = M = 1 \f$).  The softening \f$ \epsilon \f$ keeps the force
/// finite for a particle that comes close (Plummer softening; zero for an exact Kepler
/// potential).  Its time step limit is a fraction of the local dynamical time:
/// \f[ \delta t \le \varepsilon_\mathrm{C}\,\sqrt{\frac{(r^2 + \epsilon^2)^{3/2}}{GM}}, \f]
/// which is \f$ \varepsilon_\mathrm{C}/2\pi \f$ of a circular orbit's period (about 21 steps a
/// period with the Courant factor 0.3); a scene that needs a more accurate orbit lowers the
/// factor or fixes the step.

#include "sph/dimension.hpp"
#include "sph/error.hpp"

#include <cmath>
#include <string>

namespace sph {

/// A softened point mass at a fixed position: its acceleration, potential energy and
/// orbital time-step limit.
template <int D>
struct PointMass {
  static constexpr const char* name = "point mass";
  static constexpr bool active = true;
  static constexpr const char* timestep_name = "point-mass orbit";

  double G = 1.0;                  ///< gravitational constant
  double mass = 1.0;               ///< M
  Vec<D> centre = Vec<D>::Zero();  ///< where the mass sits
  double softening = 0.0;          ///< epsilon (Plummer)

  PointMass() = default;
  PointMass(double g, double m, const Vec<D>& at = Vec<D>::Zero(), double eps = 0.0)
      : G(g), mass(m), centre(at), softening(eps) {
    require(std::isfinite(g) && g > 0,
            "point mass: G must be positive and finite (got " + show(g) + ")");
    require(std::isfinite(m) && m > 0,
            "point mass: the mass must be positive and finite (got " + show(m) + ")");
    require(at.allFinite(), "point mass: the centre must be finite");
    require(std::isfinite(eps) && eps >= 0, "point mass: the softening must be non-negative");
  }

  /// \f$ -\nabla\Phi = -GM\,(\mathbf x - \mathbf x_0)/(r^2 + \epsilon^2)^{3/2} \f$.
  Vec<D> acceleration(const Vec<D>& x) const {
    const Vec<D> d = x - centre;
    const double s2 = d.squaredNorm() + softening * softening;
    return -G * mass / (s2 * std::sqrt(s2)) * d;
  }
  double potential(const Vec<D>& x) const {
    return -G * mass / std::sqrt((x - centre).squaredNorm() + softening * softening);
  }
  double timestep(const Vec<D>& x, double courant) const {
    const double s2 = (x - centre).squaredNorm() + softening * softening;
    return courant * std::sqrt(s2 * std::sqrt(s2) / (G * mass));
  }
};

}  // namespace sph
