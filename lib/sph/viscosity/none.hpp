#pragma once
/// \file
/// \brief No artificial viscosity: the inviscid equations of Chapter 3.
///
/// The interface every viscosity variant implements (see monaghan_gingold_1983.hpp for the
/// documented version): `active`, `name`, `pair()` returning Pi_ij and mu_ij, and
/// `signal_term()` for the time step.  With `active == false` the force pass compiles the
/// viscosity out entirely.

#include "sph/pair.hpp"

#include <string>

namespace sph {

/// Pi_ij and the mu_ij it came from, for one pair.
struct PairViscosity {
  double pi = 0;  ///< Pi_ij, added to P_i/rho_i^2 + P_j/rho_j^2
  double mu = 0;  ///< |mu_ij| (enters the time step of Selhammar eq 7)
};

struct NoViscosity {
  static constexpr bool active = false;
  static constexpr const char* name = "no viscosity";
  std::string describe() const { return name; }
  template <int D>
  PairViscosity pair(const Pair<D>&, double, double) const { return {}; }
  double signal_term(double, double) const { return 0; }
};

}  // namespace sph
