#pragma once
/// \file
/// \brief Validators for the values of a chapter's options: each refuses a value with a message
/// that names the option and the problem (`--gamma: must be greater than 1, got 0.5`), and
/// the number formats those messages use.  app::Chapter (chapter.hpp) attaches them to its
/// parameters; they know nothing else of a chapter.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <utility>

namespace app {
/// \name Validators for parameter values
/// Each produces a message such as `--gamma: must be greater than 1, got 0.5`.
/// Use them as `chapter.parameter("--gamma", gamma, "...").check(app::greater_than(1.0))`.
/// @{

/// Accepts any finite number (rejects `nan`, `inf`).  Added to every floating-point parameter.
CLI::Validator finite();
/// Accepts whole numbers (rejects `3.5`), and writes one given as `2e9` in digits, so that it
/// reaches the range checks and the conversion.  Added to every integer parameter.
CLI::Validator whole_number();
/// Accepts numbers > 0.
CLI::Validator positive();
/// Accepts numbers >= 0.
CLI::Validator non_negative();
/// Accepts numbers > \p bound.
CLI::Validator greater_than(double bound);
/// Accepts numbers >= \p bound.
CLI::Validator at_least(double bound);
/// Accepts numbers < \p bound.
CLI::Validator less_than(double bound);
/// Accepts numbers <= \p bound.
CLI::Validator at_most(double bound);
/// Accepts numbers in the closed interval [\p low, \p high].
CLI::Validator between(double low, double high);
/// Accepts counts in [\p low, \p high].  A larger value is refused with the memory it would
/// need, `bytes(value)` bytes (a count of particles, or of particles per unit length in a
/// 3D box): "--particles: 2e+09 would need about 400 GB of memory; at most 200000".
CLI::Validator count_between(double low, double high, std::function<double(double)> bytes);

/// The memory that \p particles simulated particles take in \p dimension dimensions, with their
/// neighbour lists and the copies a run keeps, generously: what count_between quotes for a
/// particle count that is too large.
double particle_bytes(int dimension, double particles);

/// A number as `%g` prints it, with up to \p digits significant digits: 0.2, 1e-06, 2e+09,
/// 3200; never 0.000000 or a long run of digits.
std::string show(double number, int digits = 6);
/// A size in bytes, readably: "512 B", "3.1 MB", "400 GB".
std::string show_bytes(double bytes);

/// The largest `--threads` a chapter accepts: 8 per core of this machine, and at least 64.
int max_threads();

/// Accepts a value of type \p T for which \p predicate is true; otherwise the message is
/// "<option>: <problem>, got <value>".  Example:
/// `.check(app::require<int>([](int n) { return n % 2 == 0; }, "must be even"))`.
template <class T>
CLI::Validator require(std::function<bool(const T&)> predicate, std::string problem) {
  return CLI::Validator(
      [predicate = std::move(predicate), problem](std::string& input) -> std::string {
        T value{};
        if (!CLI::detail::lexical_cast(input, value)) {
          return "cannot read '" + input + "' as a value of this option";
        }
        return predicate(value) ? std::string() : problem + ", got " + input;
      },
      problem);
}
/// @}

}  // namespace app
