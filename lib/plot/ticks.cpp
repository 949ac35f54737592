/// \file
/// \brief Tick placement: nice linear steps and decade-based log ticks.
#include "plot/ticks.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace plot {
namespace {

constexpr double eps = 1e-9;  // slack in units of a step, against round-off at the ends

// ---- Linear axes ----------------------------------------------------------------------------

/// A linear step m × 10^e.
struct Step {
    int mantissa;
    int exponent;
    double value() const { return mantissa * std::pow(10.0, exponent); }
};

long first_multiple(double lo, double step) { return std::lround(std::ceil(lo / step - eps)); }
long last_multiple(double hi, double step) { return std::lround(std::floor(hi / step + eps)); }

int count_multiples(double lo, double hi, double step) {
    return static_cast<int>(last_multiple(hi, step) - first_multiple(lo, step) + 1);
}

/// The smallest nice step that gives at most \p max_labels labelled ticks.
Step choose_linear_step(double lo, double hi, int max_labels) {
    const int e0 = static_cast<int>(std::floor(std::log10(hi - lo))) - 2;
    for (int e = e0; e < e0 + 5; ++e) {
        for (int m : {1, 2, 5}) {
            const Step step{m, e};
            if (count_multiples(lo, hi, step.value()) <= max_labels) return step;
        }
    }
    return {1, e0 + 5};
}

int minor_divisions(const Step& step) { return step.mantissa == 2 ? 4 : 5; }

TickSet linear_ticks(double lo, double hi, int max_labels) {
    TickSet set;
    const Step step = choose_linear_step(lo, hi, std::min(max_labels, 7));
    const double h = step.value();

    // Labels: as many decimals as the step needs, or a shared exponent for extreme values.
    const double largest = std::max(std::abs(lo), std::abs(hi));
    const int magnitude = static_cast<int>(std::floor(std::log10(largest)));
    const bool shared_exponent = magnitude >= 5 || magnitude <= -4;
    const int shift = shared_exponent ? magnitude : 0;
    const int decimals = std::max(0, shift - step.exponent);
    if (shared_exponent) set.multiplier = "×10^{" + std::to_string(shift) + "}";

    // Major ticks at integer multiples of the step (no accumulated round-off).
    for (long k = first_multiple(lo, h); k <= last_multiple(hi, h); ++k) {
        const double value = static_cast<double>(k) * h;
        set.ticks.push_back({value, format_number(value / std::pow(10.0, shift), decimals), true});
    }
    // Minor ticks between (and beyond) them.
    const double minor = h / minor_divisions(step);
    for (long k = first_multiple(lo, minor); k <= last_multiple(hi, minor); ++k) {
        if (k % minor_divisions(step) != 0) set.ticks.push_back({k * minor, "", false});
    }
    return set;
}

// ---- Logarithmic axes -----------------------------------------------------------------------

std::string decade_label(int exponent) { return "10^{" + std::to_string(exponent) + "}"; }

/// A tick m × 10^d on a log axis.
struct LogValue {
    int mantissa;
    int exponent;
    double value() const { return mantissa * std::pow(10.0, exponent); }
};

/// Every m × 10^d in [lo, hi] with m taken from \p mantissas.
std::vector<LogValue> log_values(double lo, double hi, const std::vector<int>& mantissas) {
    std::vector<LogValue> values;
    const int d0 = static_cast<int>(std::floor(std::log10(lo))) - 1;
    const int d1 = static_cast<int>(std::ceil(std::log10(hi))) + 1;
    for (int d = d0; d <= d1; ++d) {
        for (int m : mantissas) {
            const double v = LogValue{m, d}.value();
            if (v >= lo * (1 - eps) && v <= hi * (1 + eps)) values.push_back({m, d});
        }
    }
    return values;
}

/// Labels on decades only, every \p stride -th decade; minor ticks at 2..9 when not too many.
TickSet decade_ticks(double lo, double hi, int max_labels) {
    TickSet set;
    const std::vector<LogValue> decades = log_values(lo, hi, {1});
    const int n = static_cast<int>(decades.size());
    const int stride = (n + max_labels - 1) / max_labels;
    for (const LogValue& d : decades) {
        const bool labelled = ((d.exponent % stride) + stride) % stride == 0;
        set.ticks.push_back({d.value(), labelled ? decade_label(d.exponent) : "", true});
    }
    if (std::log10(hi / lo) <= 12.0) {
        for (const LogValue& v : log_values(lo, hi, {2, 3, 4, 5, 6, 7, 8, 9}))
            set.ticks.push_back({v.value(), "", false});
    }
    return set;
}

/// The label of m × 10^d in a sub-decade axis.
std::string mantissa_label(const LogValue& v, bool plain) {
    if (plain) return format_number(v.value(), std::max(0, -v.exponent));
    if (v.mantissa == 1) return decade_label(v.exponent);
    return std::to_string(v.mantissa) + "×" + decade_label(v.exponent);
}

/// Labels at chosen mantissas, for axes spanning about two decades or less.  Returns an empty
/// set when no mantissa choice gives at least three labels within \p max_labels that spread
/// over at least half the axis (0.08, 0.09, 0.1 on an axis to 0.17 leave its upper half
/// unlabelled: linear values, 0.08 to 0.16, read better there).
TickSet mantissa_ticks(double lo, double hi, int max_labels) {
    const std::array<std::vector<int>, 2> choices{std::vector<int>{1, 2, 5},
                                                  std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}};
    for (const std::vector<int>& mantissas : choices) {
        const std::vector<LogValue> labelled = log_values(lo, hi, mantissas);
        const int n = static_cast<int>(labelled.size());
        if (n < 3 || n > max_labels) continue;
        const double spread = std::log(labelled.back().value() / labelled.front().value());
        if (spread < 0.5 * std::log(hi / lo)) continue;
        const bool plain = std::all_of(labelled.begin(), labelled.end(), [](const LogValue& v) {
            return v.exponent >= -3 && v.exponent <= 4;
        });
        TickSet set;
        for (const LogValue& v : labelled)
            set.ticks.push_back({v.value(), mantissa_label(v, plain), true});
        for (const LogValue& v : log_values(lo, hi, {1, 2, 3, 4, 5, 6, 7, 8, 9})) {
            const bool taken =
                std::any_of(labelled.begin(), labelled.end(), [&](const LogValue& l) {
                    return l.mantissa == v.mantissa && l.exponent == v.exponent;
                });
            if (!taken) set.ticks.push_back({v.value(), "", false});
        }
        return set;
    }
    return {};
}

TickSet log_ticks(double lo, double hi, int max_labels) {
    const std::size_t decades = log_values(lo, hi, {1}).size();
    if (decades >= 3) return decade_ticks(lo, hi, max_labels);
    TickSet set = mantissa_ticks(lo, hi, max_labels);
    if (!set.ticks.empty()) return set;
    if (decades == 2) return decade_ticks(lo, hi, max_labels);
    // Less than one mantissa step in range: nice linear values, placed logarithmically.
    return linear_ticks(lo, hi, max_labels);
}

}  // namespace

std::string format_number(double value, int decimals) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", std::clamp(decimals, 0, 17), value);
    std::string text = buffer;
    // "-0", "-0.00": the sign of a rounded zero is noise.
    if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
    if (text.front() == '-') text.replace(0, 1, "\u2212");
    return text;
}

TickSet make_ticks(Scale scale, double lo, double hi, int max_labels) {
    max_labels = std::clamp(max_labels, 2, 8);
    return scale == Scale::log ? log_ticks(lo, hi, max_labels) : linear_ticks(lo, hi, max_labels);
}

}  // namespace plot
