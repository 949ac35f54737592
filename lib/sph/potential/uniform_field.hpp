#pragma once
/// \file
/// \brief A uniform field of acceleration \f$ \mathbf g \f$:
/// \f$ \Phi = -\mathbf g\cdot\mathbf x \f$.
///
/// The body force that drives Watkins et al.'s (1996, sect. 4.1) Poiseuille flow, and gravity
/// near a surface.  It sets no time step of its own (the acceleration criterion of the step
/// covers it).

#include "sph/dimension.hpp"
#include "sph/error.hpp"

#include <limits>

namespace sph {

/// A uniform acceleration \f$ \mathbf g \f$ everywhere (no limit on the time step).
template <int D>
struct UniformField {
  static constexpr const char* name = "uniform field";
  static constexpr bool active = true;
  static constexpr const char* timestep_name = "none";

  Vec<D> g = Vec<D>::Zero();  ///< the acceleration

  UniformField() = default;
  explicit UniformField(const Vec<D>& field) : g(field) {
    require(field.allFinite(), "uniform field: the acceleration must be finite");
  }
  Vec<D> acceleration(const Vec<D>&) const { return g; }
  double potential(const Vec<D>& x) const { return -g.dot(x); }
  double timestep(const Vec<D>&, double) const { return std::numeric_limits<double>::infinity(); }
};

}  // namespace sph
