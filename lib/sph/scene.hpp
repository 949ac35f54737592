#pragma once
/// \file
/// \brief A scene: the parts of the physics named at compile time, with their defaults.
///
/// A scene is a type that names its parts; it derives from Scene<D> and replaces what differs
/// from the defaults:
///
///     template <int D>
///     struct Sod : sph::Scene<D> {
///       using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983>;
///     };
///     sph::Simulation<Sod<1>> sim(particles, box, sph::IdealGas(1.4),
///                                 sph::MonaghanGingold1983{1, 2});
///
/// | part | default | what it decides |
/// |:--|:--|:--|
/// | `D` | (the template argument) | the dimension: a 1D scene compiles one-component vectors |
/// | `Kernel` | `sph::Kernel<D>` (M4) | W and its gradient in every pass |
/// | `Eos` | `sph::IdealGas` | P and c from rho and u; whether u is evolved at all |
/// | `Terms` | `sph::Terms<>` (none) | the terms of the equations of motion (terms.hpp); none means no hydrodynamics: no neighbour search, no density |
/// | `Gravity` | `sph::NoGravity` | self-gravity (gravity/) |
/// | `External` | `sph::NoExternalPotential` | an external potential: a point mass, a uniform field (potential/) |
/// | `Boundaries` | `sph::NoBoundaries` | fixed boundary particles, constraints (boundaries/) |
/// | `Integrator` | `sph::Leapfrog<D>` | the time integrator (integration/) |
///
/// The step (simulation.hpp) runs exactly the passes these parts need and allocates only the
/// fields they use; what a scene does not name, it does not contain.

#include "sph/boundaries/none.hpp"
#include "sph/eos.hpp"
#include "sph/gravity/none.hpp"
#include "sph/integration/integrators.hpp"
#include "sph/kernel.hpp"
#include "sph/potential/none.hpp"
#include "sph/terms.hpp"

namespace sph {

/// The defaults of every slot of a scene in Dim dimensions (M4 kernel, ideal gas, no terms,
/// no gravity, no external potential, no boundaries, leapfrog): a scene derives from it and
/// names what differs.
template <int Dim>
requires SupportedDimension<Dim>
struct Scene {
  static constexpr int D = Dim;
  using Kernel = sph::Kernel<Dim>;
  using Eos = IdealGas;
  using Terms = sph::Terms<>;
  using Gravity = NoGravity;
  using External = NoExternalPotential;
  using Boundaries = NoBoundaries;
  using Integrator = Leapfrog<Dim>;
};

}  // namespace sph
