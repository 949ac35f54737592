#pragma once
/// \file
/// \brief The velocity a pair sees across a wall: Watkins et al.'s (1996, sect. 4.1.1)
/// pseudo-velocity and pseudo-curl of fixed wall particles, for the viscosity terms.
///
/// Fixed boundary particles (fixed_particles.hpp) have no velocity of their own worth
/// differencing: a fluid particle beside a wall at rest sees a jump from its own speed to zero
/// across one smoothing length, and a viscosity made of velocity differences is wrong there.
/// A Walls policy says what a wall particle j lends the fluid particle i that looks at it.  It
/// differs for each i, so the viscosity terms apply it inside their pair functions, and never
/// store it on j.  A scene without walls names NoWalls, the default, and pays nothing.

#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/fields.hpp"
#include "sph/particles.hpp"

#include <cmath>
#include <cstddef>
#include <limits>

namespace sph {

/// No walls: a neighbour's velocity, curl and divergence are its own.
struct NoWalls {
  static constexpr bool active = false;
};

/// Whether j is a wall particle seen by fluid particle i (what the walls are asked about).
template <int D>
bool sees_wall(std::size_t i, std::size_t j, const ParticleView<D>& in) {
  return in.kind[j] != ParticleKind::fluid && in.kind[i] == ParticleKind::fluid;
}

/// Plane walls at \f$ y = c \pm a \f$ (y the coordinate \p axis), with the flow between them
/// parabolic near the walls, as in Poiseuille flow: \f$ v_x = K(a^2 - y^2) \f$, \f$ v_y = 0 \f$
/// (eq 16, y measured from the centre c).  A fixed particle j seen from a fluid particle i
/// lends it
///  - the velocity of that parabola through i (eq 17):
///    \f$ [v_x]_j = [v_x]_i\,(a^2 - y_j^2)/(a^2 - y_i^2) \f$ for every component along the
///    walls, and 0 across them -- zero at the wall (no slip), and of the other sign beyond it;
///  - the parabola's curl, linear in y (eq 19): \f$ (\nabla\times\mathbf v)_j =
///    (y_j/y_i)(\nabla\times\mathbf v)_i \f$.  (The printed eq 18 gives the curl as
///    \f$ -2Ky \f$; for \f$ v_x = K(a^2-y^2) \f$ it is \f$ \partial_x v_y - \partial_y v_x =
///    +2Ky \f$.  Eq 19 takes a ratio, so the sign does not enter.)
///  - for the divergence, which Watkins et al. do not extrapolate, i's own: the wall adds
///    nothing to the grad-div part (their flow has \f$ \nabla\cdot\mathbf v = 0 \f$).
/// A fluid particle at or beyond a wall (eq 17 divides by \f$ a^2 - y_i^2 \f$), or one on the
/// centre line that sees a wall (eq 19 divides by \f$ y_i \f$), has no pseudo-velocity: the
/// factors are then NaN, and the step's check of the forces stops the run naming the particle
/// and where it is.  (The pair functions run on many threads at once, where an exception
/// cannot be thrown; the check runs after them.)
template <int D>
struct ParabolicWalls {
  static constexpr bool active = true;
  int axis = D - 1;       ///< the coordinate across the walls (y in 2D)
  double centre = 0;      ///< c, the centre line
  double half_width = 1;  ///< a, the distance of each wall from the centre line
  /// Whether the walls lend eq 17's pseudo-velocity (false: a wall particle is seen at rest).
  bool lend_velocity = true;
  /// Whether the walls lend eq 19's pseudo-curl (false: a wall particle's curl is the one its
  /// own gradient pass finds, from the fluid it sees and its own rest or pseudo-velocity).
  bool lend_curl = true;

  ParabolicWalls() = default;
  ParabolicWalls(double c, double a, int across = D - 1) : axis(across), centre(c), half_width(a) {
    require(across >= 0 && across < D, "parabolic walls: the axis must be one of the box's");
    require(std::isfinite(c), "parabolic walls: the centre must be finite");
    require(std::isfinite(a) && a > 0,
            "parabolic walls: the half-width must be positive (got " + show(a) + ")");
  }

  /// y of particle k, from the centre line.
  double y(std::size_t k, const ParticleView<D>& in) const { return in.x.x[axis][k] - centre; }
  /// Eq 17: the factor by which the components of \f$ \mathbf v_i \f$ along the walls are
  /// lent to wall particle j.
  double velocity_factor(std::size_t i, std::size_t j, const ParticleView<D>& in) const {
    const double yi = y(i, in), yj = y(j, in), a2 = half_width * half_width;
    if (!(std::abs(yi) < half_width)) return std::numeric_limits<double>::quiet_NaN();
    return (a2 - yj * yj) / (a2 - yi * yi);
  }
  /// \f$ \mathbf v_i - \mathbf v_j \f$ with j's pseudo-velocity of eq 17 (NaN where the
  /// factor is): \f$ (1 - f)\,v_i \f$ along the walls, \f$ v_i \f$ across them.
  void velocity_difference(std::size_t i, std::size_t j, const ParticleView<D>& in,
                           double (&v_ij)[D]) const {
    const double f = velocity_factor(i, j, in);
    for (int a = 0; a < D; ++a) v_ij[a] = in.v[a][i] * (a == axis ? 1.0 : 1.0 - f);
  }
  /// Eq 19: the factor by which \f$ (\nabla\times\mathbf v)_i \f$ is lent to wall particle j.
  double curl_factor(std::size_t i, std::size_t j, const ParticleView<D>& in) const {
    const double yi = y(i, in);
    return yi != 0 ? y(j, in) / yi : std::numeric_limits<double>::quiet_NaN();
  }
};

}  // namespace sph
