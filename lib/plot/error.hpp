/// \file
/// \brief The one exception type of the figure engine.
#pragma once

#include <stdexcept>
#include <string>

namespace plot {

/// Every failure of the figure engine is reported as a plot::Error: a missing GL context, an
/// unwritable output path, empty or all-NaN data, an absurd figure size, an unknown markup
/// command.  The message names the problem and, where there is one, the offending value.
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& message) : std::runtime_error("plot: " + message) {}
};

}  // namespace plot
