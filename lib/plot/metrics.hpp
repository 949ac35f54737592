/// \file
/// \brief Sizes of the figure furniture, all proportional to the font size (internal).
#pragma once

#include <algorithm>

namespace plot::detail {

/// Lengths in final pixels derived from the base font size F, so that a figure scales as a
/// whole when F changes.
struct Metrics {
    double font;  ///< F, pixels

    double tick_label_size() const { return font; }
    double axis_label_size() const { return 1.05 * font; }
    double title_size() const { return 1.1 * font; }
    double letter_size() const { return 1.05 * font; }
    double legend_size() const { return 0.92 * font; }
    double stamp_size() const { return 0.75 * font; }

    double frame_width() const { return std::max(1.0, font / 16.0); }
    double major_tick() const { return 0.5 * font; }
    double minor_tick() const { return 0.28 * font; }
    double tick_label_pad() const { return 0.45 * font; }
    double axis_label_pad() const { return 0.55 * font; }
    double outer_pad() const { return 0.6 * font; }
    double colorbar_gap() const { return 0.9 * font; }
    double colorbar_width() const { return 1.0 * font; }
    double legend_inset() const { return major_tick() + 0.35 * font; }  // clear of the ticks
    double legend_pad() const { return 0.5 * font; }
    double legend_row() const { return 1.45 * legend_size(); }
    double legend_sample() const { return 2.4 * font; }
};

}  // namespace plot::detail
