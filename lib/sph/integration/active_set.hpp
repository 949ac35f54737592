#pragma once
/// \file
/// \brief The particles an evaluation updates: all of them, or those whose time step ends now.
///
/// With one time step for all particles every evaluation updates every particle.  With
/// individual time steps (individual_leapfrog.hpp) only the particles whose step ends at this
/// moment need new accelerations; the others keep theirs.  The passes that cost most -- the
/// force loop, its per-particle terms, gravity, an external potential -- then run over an
/// ActiveSet: an index list, or nothing, which means every particle.  A scene with one step
/// for all never makes a list, and its loops read `i = k` as before.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sph {

/// All particles (the default), or the ones listed, in increasing order.
struct ActiveSet {
  const std::vector<std::uint32_t>* list = nullptr;

  bool all() const { return list == nullptr; }
  /// How many particles are active among \p n.
  std::size_t size(std::size_t n) const { return list ? list->size() : n; }
  /// The k-th active particle.
  std::size_t operator[](std::size_t k) const { return list ? (*list)[k] : k; }
};

}  // namespace sph
