// The validators of option values (options.hpp).
#include "app/options.hpp"

#include <omp.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

namespace app {

std::string show(double number, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", std::clamp(digits, 1, 17), number);
  return text;
}

double particle_bytes(int dimension, double particles) {
  // An estimate, rounded up: a particle's fields are some 20 numbers (170 bytes in 3D), and its
  // neighbour list, which dominates, some 60 pairs of 8 bytes in 3D, 30 in 2D and 4 to 8 in 1D,
  // kept from both sides; a run keeps a few copies of the particles besides.
  const double per_particle = dimension == 1 ? 200.0 : dimension == 2 ? 500.0 : 1000.0;
  return per_particle * particles;
}

std::string show_bytes(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int unit = 0;
  while (bytes >= 1000 && unit < 6) {
    bytes /= 1000;
    ++unit;
  }
  return show(bytes, 3) + " " + units[unit];
}

namespace {

/// The value as the message quotes it: as typed, unless that is long ("1000...0" with 300
/// digits), then as %g prints it.
std::string quoted(const std::string& input, double value) {
  return input.size() <= 16 ? input : app::show(value);
}

/// A validator that reads the value as a number and applies \p accept; \p problem is the
/// message when it fails ("must be greater than 1").
CLI::Validator numeric(std::function<bool(double)> accept, const std::string& problem,
                       const std::string& description) {
  return CLI::Validator(
      [accept = std::move(accept), problem](std::string& input) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(input, value)) {
          return "expected a number, got '" + input + "'";
        }
        if (!std::isfinite(value)) {
          return "must be a finite number, got " + input;
        }
        return accept(value) ? std::string() : problem + ", got " + quoted(input, value);
      },
      description);
}

}  // namespace

CLI::Validator finite() {
  return numeric([](double) { return true; }, "must be a finite number", "");
}
CLI::Validator whole_number() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        // (read as a number first: a conversion to an integer would clamp 1e300's digits)
        double number = 0.0;
        if (!CLI::detail::lexical_cast(input, number)) {
          return "expected a whole number, got '" + input + "'";
        }
        if (!std::isfinite(number) || number != std::floor(number)) {
          return "must be a whole number, got " + quoted(input, number);
        }
        if (std::abs(number) > 1e18) return "is far too large, got " + quoted(input, number);
        // In digits, for the range checks that follow and the conversion: 2e9 is 2000000000.
        input = std::to_string(static_cast<long long>(number));
        return {};
      },
      "");
}
CLI::Validator positive() {
  return numeric([](double x) { return x > 0.0; }, "must be positive", "> 0");
}
CLI::Validator non_negative() {
  return numeric([](double x) { return x >= 0.0; }, "must not be negative", ">= 0");
}
CLI::Validator greater_than(double bound) {
  return numeric([bound](double x) { return x > bound; }, "must be greater than " + show(bound),
                 "> " + show(bound));
}
CLI::Validator at_least(double bound) {
  return numeric([bound](double x) { return x >= bound; }, "must be at least " + show(bound),
                 ">= " + show(bound));
}
CLI::Validator less_than(double bound) {
  return numeric([bound](double x) { return x < bound; }, "must be less than " + show(bound),
                 "< " + show(bound));
}
CLI::Validator at_most(double bound) {
  return numeric([bound](double x) { return x <= bound; }, "must be at most " + show(bound),
                 "<= " + show(bound));
}
CLI::Validator between(double low, double high) {
  const std::string range = "[" + show(low) + ", " + show(high) + "]";
  return numeric([low, high](double x) { return low <= x && x <= high; }, "must lie in " + range,
                 "in " + range);
}
CLI::Validator count_between(double low, double high, std::function<double(double)> bytes) {
  const std::string range = "[" + show(low) + ", " + show(high) + "]";
  return CLI::Validator(
      [low, high, range, bytes = std::move(bytes)](std::string& input) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(input, value)) {
          return "expected a number, got '" + input + "'";
        }
        if (!std::isfinite(value)) return "must be a finite number, got " + input;
        if (value < low) return "must lie in " + range + ", got " + quoted(input, value);
        if (value > high) {
          return app::show(value) + " would need about " + show_bytes(bytes(value)) +
                 " of memory; at most " + show(high);
        }
        return {};
      },
      "in " + range);
}

int max_threads() { return std::max(64, 8 * omp_get_num_procs()); }

}  // namespace app
