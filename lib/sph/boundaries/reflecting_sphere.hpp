#pragma once
/// \file
/// \brief A reflecting sphere: the gas held inside a wall that bounces every particle back.
///
/// The interface of a boundary policy is described in boundaries/none.hpp.

#include "sph/boundaries/none.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/particles.hpp"

#include <cmath>
#include <cstddef>
#include <string>

namespace sph {

/// A reflecting sphere: the gas is held inside \f$ |\mathbf x - \mathbf c| \le R \f$ by a wall
/// that returns every particle that crosses it as an elastic bounce (Watkins et al. 1996,
/// sect. 4.4: the rotating cloud collapses inside a reflecting sphere).  A particle found
/// outside after a drift is taken back along its straight path (it drifted with the velocity
/// \f$ \mathbf v \f$ the integrator hands over) to the point \f$ \mathbf p \f$ where it crossed
/// the wall, \f$ s \f$ time units ago; its velocity is mirrored in the wall there,
/// \f$ \mathbf v' = \mathbf v - 2(\mathbf v\cdot\hat{\mathbf n})\hat{\mathbf n} \f$, and it
/// moves on for the time \f$ s \f$: \f$ \mathbf x' = \mathbf p + s\,\mathbf v' \f$.  The kick of
/// the wall is radial, so the speed and the angular momentum about the centre are exactly those
/// before the bounce (\f$ \mathbf x'\times\mathbf v' = \mathbf p\times\mathbf v' =
/// \mathbf p\times\mathbf v = \mathbf x\times\mathbf v \f$ about the centre).  A particle that
/// would still be outside after that had a step far too long for the wall: `constrain` leaves
/// it and returns false, and the step stops with a message naming it.
template <int D>
struct ReflectingSphere {
  static constexpr const char* name = "reflecting sphere";
  static constexpr bool has_constraint = true;

  Vec<D> centre = Vec<D>::Zero();
  double radius = 1.0;

  ReflectingSphere() = default;
  ReflectingSphere(const Vec<D>& c, double r) : centre(c), radius(r) {
    require(c.allFinite(), "reflecting sphere: the centre must be finite");
    require(std::isfinite(r) && r > 0,
            "reflecting sphere: the radius must be positive (got " + show(r) + ")");
  }

  static constexpr bool moves(std::size_t, const Particles<D>&) { return true; }
  /// Every particle must start inside the sphere.
  void validate(const Particles<D>& p) const {
    NoBoundaries{}.validate(p);
    for (std::size_t i = 0; i < p.size(); ++i) {
      if ((p.position[i] - centre).norm() > radius) {
        throw Error("reflecting sphere: particle " + show(i) + " at " +
                    to_string<D>(p.position[i]) + " starts outside the sphere of radius " +
                    show(radius));
      }
    }
  }
  /// Bring a particle that has crossed the wall back inside, with its velocity mirrored at the
  /// point where it crossed (false, and nothing changed, when that is not possible).
  bool constrain(Vec<D>& x, Vec<D>& v) const {
    const Vec<D> d = x - centre;
    const double r2 = d.squaredNorm();
    if (r2 <= radius * radius) return true;
    // The time s since the crossing: the smaller root of |d - s v|^2 = R^2 (the path left the
    // sphere moving outwards, d.v > 0).
    const double dv = d.dot(v), vv = v.squaredNorm();
    const double discriminant = dv * dv - vv * (r2 - radius * radius);
    if (!(dv > 0 && discriminant >= 0)) return false;
    const double s = (dv - std::sqrt(discriminant)) / vv;
    const Vec<D> crossing = d - s * v;
    const Vec<D> n = crossing / crossing.norm();
    const Vec<D> mirrored = v - 2 * v.dot(n) * n;
    const Vec<D> back = crossing + s * mirrored;
    if (!(back.squaredNorm() <= radius * radius * (1 + 1e-12))) return false;
    x = centre + back;
    v = mirrored;
    return true;
  }
  /// What went wrong when constrain() returned false.
  std::string describe_failure(const Vec<D>& x) const {
    return "reflecting sphere: the particle at " + to_string<D>(x) +
           " crossed the wall of radius " + show(radius) +
           " and cannot be brought back along its path (the step is far too long for "
           "the wall)";
  }
};

}  // namespace sph
