#pragma once
/// \file
/// \brief TimestepLimit: which criterion set a time step, and where (simulation.hpp).

#include <cstddef>
#include <string>

namespace sph {

/// Which criterion set the last time step, and where.
struct TimestepLimit {
  /// "Courant (eq 7)", "signal velocity", "acceleration", "cooling", a term's or a potential's
  /// name, "output time", "fixed step"; with individual time steps also "neighbour's step
  /// (limiter)"
  std::string criterion;
  std::size_t particle = 0;
  double dt = 0;
};

}  // namespace sph
