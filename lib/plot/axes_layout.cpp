/// \file
/// \brief Axes layout: tick choice without overlapping labels, margins, legend and colour bar
/// placement.
#include "plot/axes.hpp"

#include "plot/error.hpp"
#include "plot/metrics.hpp"
#include "plot/text.hpp"

#include <algorithm>
#include <cmath>

namespace plot {

using detail::Font;
using detail::Metrics;
using detail::TextMetrics;

namespace {

/// Position of \p v along an axis of \p length pixels from lo to hi.
double along(Scale scale, double lo, double hi, double v, double length) {
    if (scale == Scale::log)
        return (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) * length;
    return (v - lo) / (hi - lo) * length;
}

/// The widest and the tallest of the labelled ticks' texts.
struct LabelExtent {
    double width = 0, ascent = 0, descent = 0;
};

LabelExtent label_extent(Font& font, const TickSet& ticks, double size) {
    LabelExtent e;
    for (const Tick& t : ticks.ticks) {
        if (t.label.empty()) continue;
        const TextMetrics m = font.measure(t.label, size);
        e.width = std::max(e.width, m.width);
        e.ascent = std::max(e.ascent, m.ascent);
        e.descent = std::max(e.descent, m.descent);
    }
    return e;
}

}  // namespace

// ---- Ticks --------------------------------------------------------------------------------------
/// The densest tick set (at most 8 labels) whose labels keep a clear gap between neighbours.
TickSet Axes::fit_ticks(Font& font, Scale scale, double lo, double hi, double length,
                        bool horizontal) const {
    const Metrics m{r_.font};
    const double gap = horizontal ? 1.2 * m.font : 0.7 * m.font;
    TickSet ticks;
    for (int n = 8; n >= 2; --n) {
        ticks = make_ticks(scale, lo, hi, n);
        struct Placed {
            double position, extent;
        };
        std::vector<Placed> placed;
        for (const Tick& t : ticks.ticks) {
            if (t.label.empty()) continue;
            const TextMetrics tm = font.measure(t.label, m.tick_label_size());
            placed.push_back(
                {along(scale, lo, hi, t.value, length), horizontal ? tm.width : tm.height()});
        }
        std::sort(placed.begin(), placed.end(),
                  [](const Placed& a, const Placed& b) { return a.position < b.position; });
        bool clear = true;
        for (std::size_t i = 1; i < placed.size(); ++i)
            clear = clear && placed[i].position - placed[i - 1].position >=
                                 (placed[i].extent + placed[i - 1].extent) / 2 + gap;
        if (clear) return ticks;
    }
    return ticks;
}

// ---- Colour bar ---------------------------------------------------------------------------------
/// The colour scale shown in the bar: that of the last image or coloured scatter asking for one.
void Axes::resolve_colorbar() {
    r_.colorbar.reset();
    for (const Layer& layer : layers_) {
        const ImageOptions& o = layer.options;
        if (o.colorbar)
            r_.colorbar =
                resolve_color_range(o.map, o.zmin, o.zmax, o.log, o.colorbar_label, layer.values);
    }
    for (const Series& s : series_) {
        const ColorScatterOptions& o = s.color_scatter;
        if (s.kind == Kind::color_scatter && o.colorbar)
            r_.colorbar =
                resolve_color_range(o.map, o.zmin, o.zmax, o.log, o.colorbar_label, s.values);
    }
}

// ---- Margins ------------------------------------------------------------------------------------
/// The space around the frame that labels need, for a frame of about the size of \p frame_guess.
Axes::Margins Axes::measure(Font& font, double font_size, const Rect& cell,
                            const Rect& frame_guess) {
    r_ = Resolved{};
    r_.font = font_size;
    r_.cell = cell;
    const Metrics m{font_size};
    if (hidden_) return {};
    resolve_limits();
    resolve_colorbar();
    if (legend_room_ && legend_ && !ylim_) make_legend_room(font, frame_guess);

    r_.x_ticks = fit_ticks(font, xscale_, r_.x_lo, r_.x_hi, frame_guess.width(), true);
    r_.y_ticks = fit_ticks(font, yscale_, r_.y_lo, r_.y_hi, frame_guess.height(), false);
    const LabelExtent xl = label_extent(font, r_.x_ticks, m.tick_label_size());
    const LabelExtent yl = label_extent(font, r_.y_ticks, m.tick_label_size());
    r_.x_label_ascent = xl.ascent;
    r_.x_label_height = xl.ascent + xl.descent;
    r_.x_label_width = xl.width;
    r_.y_label_width = yl.width;

    Margins margins;
    // Below: tick labels, then the axis label.
    margins.bottom = m.tick_label_pad() + r_.x_label_height + m.outer_pad();
    if (!xlabel_.empty())
        margins.bottom +=
            m.axis_label_pad() + font.measure_line(xlabel_, m.axis_label_size()).height();
    // Left: tick labels, then the axis label reading upwards.
    margins.left = m.tick_label_pad() + r_.y_label_width + m.outer_pad();
    if (!ylabel_.empty())
        margins.left +=
            m.axis_label_pad() + font.measure_line(ylabel_, m.axis_label_size()).height();
    // Above: half the top tick label, the letter or title, the y multiplier.
    margins.top = 0.5 * (yl.ascent + yl.descent);
    if (!letter_.empty())
        margins.top = std::max(margins.top,
                               font.measure_line(letter_, m.letter_size()).ascent + 0.5 * m.font);
    if (!title_.empty())
        margins.top = std::max(margins.top,
                               font.measure_line(title_, m.title_size()).height() + 0.5 * m.font);
    if (!r_.y_ticks.multiplier.empty())
        margins.top = std::max(
            margins.top,
            font.measure(r_.y_ticks.multiplier, m.tick_label_size()).height() + 0.5 * m.font);
    margins.top += m.outer_pad();
    // Right: the overhang of the last tick label, the x multiplier, the colour bar.
    margins.right = 0.5 * xl.width;
    if (!r_.x_ticks.multiplier.empty())
        margins.right = std::max(
            margins.right, 0.5 * xl.width + 0.4 * m.font +
                               font.measure(r_.x_ticks.multiplier, m.tick_label_size()).width);
    if (r_.colorbar) {
        const auto& c = *r_.colorbar;
        r_.c_ticks = fit_ticks(font, c.log ? Scale::log : Scale::linear, c.lo, c.hi,
                               frame_guess.height(), false);
        r_.c_label_width = label_extent(font, r_.c_ticks, m.tick_label_size()).width;
        double bar = m.colorbar_gap() + m.colorbar_width() + m.tick_label_pad() + r_.c_label_width;
        if (!c.label.empty())
            bar += m.axis_label_pad() + font.measure_line(c.label, m.axis_label_size()).height();
        if (!r_.c_ticks.multiplier.empty())
            bar = std::max(bar, m.colorbar_gap() +
                                    font.measure(r_.c_ticks.multiplier, m.tick_label_size()).width);
        margins.right = std::max(margins.right, bar);
    }
    margins.right += m.outer_pad();
    return margins;
}

// ---- Final placement ----------------------------------------------------------------------------
namespace {

/// Moves a frame edge to a pixel centre, so that one-pixel lines on it are crisp.
double to_pixel_centre(double v) { return std::floor(v) + 0.5; }

}  // namespace

void Axes::place(Font& font, const Rect& frame_in) {
    const Metrics m{r_.font};
    if (hidden_) return;
    Rect frame = frame_in;
    // Equal aspect: shrink one side, keep the frame centred.
    if (equal_aspect_) {
        const double dx = axis_u(r_.x_hi, true) - axis_u(r_.x_lo, true);
        const double dy = axis_u(r_.y_hi, false) - axis_u(r_.y_lo, false);
        const double scale = std::min(frame.width() / dx, frame.height() / dy);
        const double cx = (frame.x0 + frame.x1) / 2, cy = (frame.y0 + frame.y1) / 2;
        frame = {cx - scale * dx / 2, cy - scale * dy / 2, cx + scale * dx / 2,
                 cy + scale * dy / 2};
    }
    frame = {to_pixel_centre(frame.x0), to_pixel_centre(frame.y0), to_pixel_centre(frame.x1),
             to_pixel_centre(frame.y1)};
    if (frame.width() < 2 * m.font || frame.height() < 2 * m.font)
        throw Error(name() + ": too small for its labels (the plot area would be " +
                    std::to_string(static_cast<int>(frame.width())) + "×" +
                    std::to_string(static_cast<int>(frame.height())) +
                    " px); make the figure larger or the font smaller");
    r_.frame = frame;

    // Ticks for the final lengths (never denser than those measured, so the margins hold).
    r_.x_ticks = fit_ticks(font, xscale_, r_.x_lo, r_.x_hi, frame.width(), true);
    r_.y_ticks = fit_ticks(font, yscale_, r_.y_lo, r_.y_hi, frame.height(), false);
    if (r_.colorbar) {
        const auto& c = *r_.colorbar;
        r_.c_ticks =
            fit_ticks(font, c.log ? Scale::log : Scale::linear, c.lo, c.hi, frame.height(), false);
        const double x0 = to_pixel_centre(frame.x1 + m.colorbar_gap());
        r_.colorbar_rect = {x0, frame.y0, x0 + std::round(m.colorbar_width()), frame.y1};
    }
    r_.done = true;
    place_legend(font);
}

// ---- Legend -------------------------------------------------------------------------------------
/// How much data a legend box at \p box would hide: points inside, and line segments crossing.
double Axes::legend_crowding(const Rect& box) const {
    double crowding = 0.0;
    for (const Series& s : series_) {
        if (s.kind == Kind::hline || s.kind == Kind::vline) {
            const Point p = to_pixel(s.kind == Kind::vline ? s.x[0] : r_.x_lo,
                                     s.kind == Kind::hline ? s.y[0] : r_.y_lo);
            crowding += s.kind == Kind::hline ? 20.0 * (p.y >= box.y0 && p.y <= box.y1)
                                              : 20.0 * (p.x >= box.x0 && p.x <= box.x1);
            continue;
        }
        const std::size_t n = s.x.size();
        const std::size_t stride = std::max<std::size_t>(1, n / 20000);
        Point previous{};
        bool have_previous = false;
        for (std::size_t i = 0; i < n; i += stride) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) ||
                (xscale_ == Scale::log && s.x[i] <= 0) || (yscale_ == Scale::log && s.y[i] <= 0)) {
                have_previous = false;
                continue;
            }
            const Point p = to_pixel(s.x[i], s.y[i]);
            crowding += static_cast<double>(stride) * box.contains(p);
            // A line crossing the box: sample its segment every few pixels.
            if (s.kind == Kind::line && have_previous) {
                const double len = std::hypot(p.x - previous.x, p.y - previous.y);
                const int samples = static_cast<int>(std::min(200.0, len / 4.0));
                for (int k = 1; k < samples; ++k) {
                    const double t = static_cast<double>(k) / samples;
                    crowding += 5.0 * box.contains({previous.x + t * (p.x - previous.x),
                                                    previous.y + t * (p.y - previous.y)});
                }
            }
            previous = p;
            have_previous = true;
        }
    }
    return crowding;
}

void Axes::place_legend(Font& font) {
    r_.legend_entries.clear();
    if (!legend_) return;
    for (const Series& s : series_)
        if (!s.label.empty()) r_.legend_entries.push_back(&s);
    if (r_.legend_entries.empty()) return;

    const Metrics m{r_.font};
    double text_width = 0.0;
    for (const Series* s : r_.legend_entries)
        text_width = std::max(text_width, font.measure(s->label, m.legend_size()).width);
    const double w = std::round(2 * m.legend_pad() + m.legend_sample() + 0.6 * m.font + text_width);
    const double h = std::round(2 * m.legend_pad() + r_.legend_entries.size() * m.legend_row() -
                                0.3 * m.legend_size());
    const Rect& f = r_.frame;
    const double inset = m.legend_inset();
    auto box_at = [&](Corner c) {
        const bool right = c == Corner::upper_right || c == Corner::lower_right;
        const bool upper = c == Corner::upper_right || c == Corner::upper_left;
        const double x0 = right ? f.x1 - inset - w : f.x0 + inset;
        const double y0 = upper ? f.y0 + inset : f.y1 - inset - h;
        return Rect{std::floor(x0) + 0.5, std::floor(y0) + 0.5, std::floor(x0) + 0.5 + w,
                    std::floor(y0) + 0.5 + h};
    };
    Corner corner = *legend_;
    if (corner == Corner::best) {
        double least = -1.0;
        for (Corner c :
             {Corner::upper_right, Corner::upper_left, Corner::lower_left, Corner::lower_right}) {
            const double crowding = legend_crowding(box_at(c));
            if (least < 0.0 || crowding < least) {
                least = crowding;
                corner = c;
            }
        }
    }
    r_.legend_box = box_at(corner);
}

/// Room for the legend above the data: on a frame of about the final size, place the legend as
/// it will be placed; if it would hide data even in the least crowded corner, raise the upper y
/// limit so that the data ends an inset below the legend box of an upper corner (in log space
/// on a logarithmic axis).  Called from measure(), before the ticks are chosen, so that the
/// ticks and the margins are those of the extended range.
void Axes::make_legend_room(Font& font, const Rect& frame_guess) {
    r_.frame = frame_guess;
    r_.done = true;  // to_pixel for the trial placement
    place_legend(font);
    const bool crowded = !r_.legend_entries.empty() && legend_crowding(r_.legend_box) > 0.0;
    r_.done = false;
    if (!crowded) return;
    const Metrics m{r_.font};
    // The fraction of the frame's height the legend takes from the top, with an inset below it.
    const double taken = (r_.legend_box.height() + 2.5 * m.legend_inset()) / frame_guess.height();
    if (!(taken > 0.0 && taken < 0.6)) return;  // a legend this tall: leave the data its room
    const double stretch = 1.0 / (1.0 - taken);
    if (yscale_ == Scale::log) {
        r_.y_hi = r_.y_lo * std::pow(r_.y_hi / r_.y_lo, stretch);
    } else {
        r_.y_hi = r_.y_lo + (r_.y_hi - r_.y_lo) * stretch;
    }
}

}  // namespace plot
