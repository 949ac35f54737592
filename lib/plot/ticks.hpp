/// \file
/// \brief Tick placement and tick labels for linear and logarithmic axes.
#pragma once

#include <string>
#include <vector>

namespace plot {

/// How an axis maps data to position.
enum class Scale {
    linear,  ///< equal data steps are equal distances
    log,     ///< equal factors are equal distances (base 10); data must be > 0
};

/// One tick mark of an axis.
struct Tick {
    double value = 0.0;  ///< in data units
    std::string label;   ///< markup; empty for an unlabelled tick
    bool major = true;   ///< major ticks are longer and carry the labels
};

/// The ticks of one axis, and a common factor shown once at the end of the axis when the
/// labels share an exponent (e.g. "×10^{5}"), empty otherwise.
struct TickSet {
    std::vector<Tick> ticks;
    std::string multiplier;
};

/// Ticks for the interval [lo, hi] (lo < hi, both > 0 for a log scale) with at most
/// \p max_labels labelled ticks (clamped to 2..8).
///
/// Linear: "nice" steps 1, 2, 5 × 10^e, the smallest that gives at most min(max_labels, 7)
/// labels; minor ticks divide a step into 5 (steps 1, 5) or 4 (step 2).  All labels of an
/// axis carry the same number of decimals, as few as the step needs.  When the largest
/// magnitude is ≥ 10^5 or < 10^-3 the labels share an exponent, given in TickSet::multiplier.
///
/// Log: with three or more decades in range, decade ticks labelled 10^{n} (every k-th decade
/// when there are too many) and unlabelled minor ticks at 2..9; with fewer, labels at
/// 1, 2, 5 × 10^n (or at every integer mantissa) so that at least three ticks carry labels,
/// written plainly ("0.02", "500") when all exponents lie in -3..4, else as "2×10^{-5}".
TickSet make_ticks(Scale scale, double lo, double hi, int max_labels);

/// \p value with \p decimals digits after the point, a real minus sign, and no "-0".
std::string format_number(double value, int decimals);

}  // namespace plot
