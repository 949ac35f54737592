#pragma once
/// \file
/// \brief The one exception type of the physics library.
///
/// A scene that cannot go on (no neighbours, a NaN, an impossible parameter) throws
/// sph::Error with a message that names the particle, the quantity and the limit.  Chapter
/// programs catch it in app::run and exit with a non-zero code; nothing is silently wrong.

#include <concepts>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace sph {

/// A physics or input error with a message meant for the user.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A number as a message shows it: integers in full, real numbers with six significant digits
/// (`%g`: 1e-08, 0.163, 2.5e+06 -- never 0.000000 for a small number, never 300 digits for a
/// large one).
template <class T>
requires std::integral<T> std::string show(T value) { return std::to_string(value); }
inline std::string show(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

/// Throw sph::Error(message) unless `condition` holds.
inline void require(bool condition, const std::string& message) {
  if (!condition) throw Error(message);
}

}  // namespace sph
