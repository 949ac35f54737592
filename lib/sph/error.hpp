#pragma once
/// \file
/// \brief The one exception type of the physics library.
///
/// A scene that cannot go on (no neighbours, a NaN, an impossible parameter) throws
/// sph::Error with a message that names the particle, the quantity and the limit.  Chapter
/// programs catch it in app::run and exit with a non-zero code; nothing is silently wrong.

#include <stdexcept>
#include <string>

namespace sph {

/// A physics or input error with a message meant for the user.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throw sph::Error(message) unless `condition` holds.
inline void require(bool condition, const std::string& message) {
  if (!condition) throw Error(message);
}

}  // namespace sph
