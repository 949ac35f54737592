/// \file
/// \brief Axes drawing: data layers and furniture through the GL canvas, then the text.
#include "plot/axes.hpp"

#include "plot/context.hpp"
#include "plot/metrics.hpp"
#include "plot/stroke.hpp"
#include "plot/text.hpp"

#include <algorithm>
#include <cmath>

namespace plot {

using detail::Canvas;
using detail::Font;
using detail::HAlign;
using detail::Metrics;
using detail::PanelTransform;
using detail::StrokeGeometry;
using detail::VAlign;

/// The data -> pixel map of one panel, flattened for tight loops over many points.
struct detail::PanelTransform {
    bool log_x, log_y;
    double ax, bx, ay, by;  // pixel = a + b * u, u = value or log10(value)

    PanelTransform(const Rect& frame, double x_lo, double x_hi, double y_lo, double y_hi, bool lx,
                   bool ly)
        : log_x(lx), log_y(ly) {
        const double ux0 = lx ? std::log10(x_lo) : x_lo, ux1 = lx ? std::log10(x_hi) : x_hi;
        const double uy0 = ly ? std::log10(y_lo) : y_lo, uy1 = ly ? std::log10(y_hi) : y_hi;
        bx = frame.width() / (ux1 - ux0);
        ax = frame.x0 - bx * ux0;
        by = -frame.height() / (uy1 - uy0);
        ay = frame.y1 - by * uy0;
    }
    /// Whether (x, y) can be shown: finite, and positive on a log axis.
    bool valid(double x, double y) const {
        return std::isfinite(x) && std::isfinite(y) && (!log_x || x > 0) && (!log_y || y > 0);
    }
    Point operator()(double x, double y) const {
        return {ax + bx * (log_x ? std::log10(x) : x), ay + by * (log_y ? std::log10(y) : y)};
    }
};

namespace {

/// Snaps a line position so that a line of width \p w is crisp: odd widths on pixel centres,
/// even widths on pixel edges.
double snap(double p, double w) {
    return static_cast<int>(std::lround(w)) % 2 == 1 ? std::floor(p) + 0.5 : std::round(p);
}

void push(std::vector<float>& v, const Point& p) {
    v.push_back(static_cast<float>(p.x));
    v.push_back(static_cast<float>(p.y));
}

/// Outline width of open markers of diameter \p size.
double outline_width(double size) { return std::max(1.0, 0.13 * size); }

}  // namespace

// ---- Entry --------------------------------------------------------------------------------------
void Axes::draw(Canvas& canvas) const {
    if (hidden_) return;
    // Data, clipped to the frame, in the order given (images always beneath).
    const PanelTransform to_px(r_.frame, r_.x_lo, r_.x_hi, r_.y_lo, r_.y_hi, xscale_ == Scale::log,
                               yscale_ == Scale::log);
    canvas.clip(r_.frame);
    draw_images(canvas);
    for (const Series& s : series_) {
        switch (s.kind) {
            case Kind::scatter:
                draw_scatter(canvas, to_px, s);
                break;
            case Kind::color_scatter:
                draw_color_scatter(canvas, to_px, s);
                break;
            case Kind::line:
                draw_line(canvas, to_px, s);
                break;
            case Kind::hline:
            case Kind::vline:
                draw_reference(canvas, to_px, s);
                break;
        }
    }
    canvas.unclip();
    // Furniture on top.
    draw_frame(canvas);
    draw_colorbar(canvas);
    draw_legend(canvas);
}

// ---- Images -------------------------------------------------------------------------------------
void Axes::draw_images(Canvas& canvas) const {
    for (const Layer& layer : layers_) {
        const ImageOptions& o = layer.options;
        const ColorRange range =
            resolve_color_range(o.map, o.zmin, o.zmax, o.log, o.colorbar_label, layer.values);
        // NaN (and, on a log scale, non-positive) cells stay transparent.
        std::vector<std::uint8_t> rgba(layer.values.size() * 4, 0);
        for (std::size_t i = 0; i < layer.values.size(); ++i) {
            const double v = layer.values[i];
            if (!std::isfinite(v) || (o.log && v <= 0)) continue;
            const auto c = to_rgb8(range.at(v));
            std::copy(c.begin(), c.end(), rgba.begin() + static_cast<std::ptrdiff_t>(4 * i));
            rgba[4 * i + 3] = 255;
        }
        const Point low = to_pixel(layer.extent.x0, layer.extent.y0);
        const Point high = to_pixel(layer.extent.x1, layer.extent.y1);
        canvas.texture(rgba, layer.nx, layer.ny, {low.x, high.y, high.x, low.y});
    }
}

// ---- Series -------------------------------------------------------------------------------------
void Axes::draw_stroke(Canvas& canvas, std::span<const Point> points, const LineOptions& style,
                       const Color& color) const {
    StrokeGeometry geometry;
    detail::stroke_polyline(points, style.width, style.style, r_.frame, geometry);
    canvas.triangles(geometry.triangles, color);
    canvas.markers(geometry.dots, geometry.dot_size, Marker::circle, 0.0, color);
}

/// All points in one draw call: positions as floats, the points that cannot be shown left out.
void Axes::draw_scatter(Canvas& canvas, const PanelTransform& to_px, const Series& s) const {
    std::vector<float> xy;
    xy.reserve(2 * s.x.size());
    for (std::size_t i = 0; i < s.x.size(); ++i)
        if (to_px.valid(s.x[i], s.y[i])) push(xy, to_px(s.x[i], s.y[i]));
    const ScatterOptions& o = s.scatter;
    canvas.markers(xy, o.size, o.marker, o.filled ? 0.0 : outline_width(o.size), s.color, o.alpha);
}

/// The same with a colour per point from the colour scale.
void Axes::draw_color_scatter(Canvas& canvas, const PanelTransform& to_px, const Series& s) const {
    const ColorScatterOptions& o = s.color_scatter;
    const ColorRange range =
        resolve_color_range(o.map, o.zmin, o.zmax, o.log, o.colorbar_label, s.values);
    std::vector<float> xy;
    std::vector<std::uint8_t> rgba;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
        const double v = s.values[i];
        if (!to_px.valid(s.x[i], s.y[i]) || !std::isfinite(v) || (o.log && v <= 0)) continue;
        push(xy, to_px(s.x[i], s.y[i]));
        const auto c = to_rgb8(range.at(v));
        rgba.insert(rgba.end(), {c[0], c[1], c[2], 255});
    }
    canvas.markers(xy, o.size, o.marker, 0.0, black, 1.0, rgba);
}

/// Polylines broken wherever a point cannot be shown, then the markers on the points.
void Axes::draw_line(Canvas& canvas, const PanelTransform& to_px, const Series& s) const {
    std::vector<Point> run;
    std::vector<float> vertices;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!to_px.valid(s.x[i], s.y[i])) {
            draw_stroke(canvas, run, s.line, s.color);
            run.clear();
            continue;
        }
        run.push_back(to_px(s.x[i], s.y[i]));
        push(vertices, run.back());
    }
    draw_stroke(canvas, run, s.line, s.color);
    const LineOptions& o = s.line;
    canvas.markers(vertices, o.marker_size, o.marker,
                   o.marker_filled ? 0.0 : outline_width(o.marker_size), s.color);
}

/// A horizontal or vertical reference line across the frame, on the pixel grid.
void Axes::draw_reference(Canvas& canvas, const PanelTransform& to_px, const Series& s) const {
    const bool h = s.kind == Kind::hline;
    if (!to_px.valid(h ? r_.x_lo : s.x[0], h ? s.y[0] : r_.y_lo)) return;
    const Point a = h ? to_px(r_.x_lo, s.y[0]) : to_px(s.x[0], r_.y_lo);
    const Point b = h ? to_px(r_.x_hi, s.y[0]) : to_px(s.x[0], r_.y_hi);
    const double w = s.line.width;
    const Point line[2] = {{h ? a.x : snap(a.x, w), h ? snap(a.y, w) : a.y},
                           {h ? b.x : snap(b.x, w), h ? snap(b.y, w) : b.y}};
    draw_stroke(canvas, line, s.line, s.color);
}

// ---- Frame and ticks ----------------------------------------------------------------------------
void Axes::draw_frame(Canvas& canvas) const {
    const Metrics m{r_.font};
    const Rect& f = r_.frame;
    const double w = m.frame_width(), h = w / 2;
    // Four sides, overlapping at the corners.
    canvas.rect({f.x0 - h, f.y0 - h, f.x1 + h, f.y0 + h}, black);
    canvas.rect({f.x0 - h, f.y1 - h, f.x1 + h, f.y1 + h}, black);
    canvas.rect({f.x0 - h, f.y0 - h, f.x0 + h, f.y1 + h}, black);
    canvas.rect({f.x1 - h, f.y0 - h, f.x1 + h, f.y1 + h}, black);

    // Inward ticks on all four sides: x ticks on the bottom and top, y ticks left and right.
    for (const Tick& t : r_.x_ticks.ticks) {
        const double x = snap(to_pixel(t.value, r_.y_lo).x, w);
        if (x < f.x0 - 0.5 || x > f.x1 + 0.5) continue;
        const double len = t.major ? m.major_tick() : m.minor_tick();
        canvas.rect({x - h, f.y1 - len, x + h, f.y1}, black);
        canvas.rect({x - h, f.y0, x + h, f.y0 + len}, black);
    }
    for (const Tick& t : r_.y_ticks.ticks) {
        const double y = snap(to_pixel(r_.x_lo, t.value).y, w);
        if (y < f.y0 - 0.5 || y > f.y1 + 0.5) continue;
        const double len = t.major ? m.major_tick() : m.minor_tick();
        canvas.rect({f.x0, y - h, f.x0 + len, y + h}, black);
        canvas.rect({f.x1 - len, y - h, f.x1, y + h}, black);
    }
}

// ---- Colour bar ---------------------------------------------------------------------------------
namespace {

double colorbar_y(const Rect& bar, Scale scale, double lo, double hi, double v) {
    const double t = scale == Scale::log
                         ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                         : (v - lo) / (hi - lo);
    return bar.y1 - t * bar.height();
}

}  // namespace

void Axes::draw_colorbar(Canvas& canvas) const {
    if (!r_.colorbar) return;
    const Metrics m{r_.font};
    const ColorRange& c = *r_.colorbar;
    const Rect& bar = r_.colorbar_rect;
    // The gradient: one texel per map step, bottom to top (uniform in the scale's own space).
    constexpr int steps = 256;
    std::vector<std::uint8_t> rgba;
    for (int i = 0; i < steps; ++i) {
        const auto rgb = to_rgb8(map_color(c.map, (i + 0.5) / steps));
        rgba.insert(rgba.end(), {rgb[0], rgb[1], rgb[2], 255});
    }
    canvas.texture(rgba, 1, steps, bar);

    const double w = m.frame_width(), h = w / 2;
    canvas.rect({bar.x0 - h, bar.y0 - h, bar.x1 + h, bar.y0 + h}, black);
    canvas.rect({bar.x0 - h, bar.y1 - h, bar.x1 + h, bar.y1 + h}, black);
    canvas.rect({bar.x0 - h, bar.y0 - h, bar.x0 + h, bar.y1 + h}, black);
    canvas.rect({bar.x1 - h, bar.y0 - h, bar.x1 + h, bar.y1 + h}, black);
    const Scale scale = c.log ? Scale::log : Scale::linear;
    for (const Tick& t : r_.c_ticks.ticks) {
        const double y = snap(colorbar_y(bar, scale, c.lo, c.hi, t.value), w);
        if (y < bar.y0 - 0.5 || y > bar.y1 + 0.5) continue;
        const double len = (t.major ? 0.45 : 0.25) * bar.width();
        canvas.rect({bar.x0, y - h, bar.x0 + len, y + h}, black);
        canvas.rect({bar.x1 - len, y - h, bar.x1, y + h}, black);
    }
}

// ---- Legend -------------------------------------------------------------------------------------
void Axes::draw_legend(Canvas& canvas) const {
    if (r_.legend_entries.empty()) return;
    const Metrics m{r_.font};
    const Rect& box = r_.legend_box;
    const double w = m.frame_width(), h = w / 2;
    const Color edge{0.25, 0.25, 0.25};
    canvas.rect(box, white);
    canvas.rect({box.x0 - h, box.y0 - h, box.x1 + h, box.y0 + h}, edge);
    canvas.rect({box.x0 - h, box.y1 - h, box.x1 + h, box.y1 + h}, edge);
    canvas.rect({box.x0 - h, box.y0 - h, box.x0 + h, box.y1 + h}, edge);
    canvas.rect({box.x1 - h, box.y0 - h, box.x1 + h, box.y1 + h}, edge);

    for (std::size_t k = 0; k < r_.legend_entries.size(); ++k) {
        const Series& s = *r_.legend_entries[k];
        const double y = snap(
            box.y0 + m.legend_pad() + (k + 0.5) * m.legend_row() - 0.15 * m.legend_size(), 1.0);
        const double x0 = box.x0 + m.legend_pad(), x1 = x0 + m.legend_sample();
        const float centre[2] = {static_cast<float>((x0 + x1) / 2), static_cast<float>(y)};
        switch (s.kind) {
            case Kind::scatter: {
                const double size = std::max(s.scatter.size, 0.45 * m.font);
                canvas.markers(centre, size, s.scatter.marker,
                               s.scatter.filled ? 0.0 : outline_width(size), s.color);
                break;
            }
            case Kind::color_scatter: {
                const ColorScatterOptions& o = s.color_scatter;
                canvas.markers(centre, std::max(o.size, 0.45 * m.font), o.marker, 0.0,
                               map_color(o.map, 0.5));
                break;
            }
            case Kind::line:
            case Kind::hline:
            case Kind::vline: {
                const Point sample[2] = {{x0, snap(y, s.line.width)}, {x1, snap(y, s.line.width)}};
                StrokeGeometry geometry;
                detail::stroke_polyline(sample, s.line.width, s.line.style, box, geometry);
                canvas.triangles(geometry.triangles, s.color);
                canvas.markers(geometry.dots, geometry.dot_size, Marker::circle, 0.0, s.color);
                canvas.markers(centre, s.line.marker_size, s.line.marker,
                               s.line.marker_filled ? 0.0 : outline_width(s.line.marker_size),
                               s.color);
                break;
            }
        }
    }
}

// ---- Text ---------------------------------------------------------------------------------------
void Axes::draw_text(Font& font, Image& image) const {
    if (hidden_) return;
    const Metrics m{r_.font};
    const Rect& f = r_.frame;
    const double size = m.tick_label_size();
    const double w = m.frame_width();

    // Tick labels: below the bottom axis on a common baseline, left of the left axis.
    const double x_baseline = f.y1 + m.tick_label_pad() + r_.x_label_ascent;
    for (const Tick& t : r_.x_ticks.ticks) {
        if (t.label.empty()) continue;
        const double x = snap(to_pixel(t.value, r_.y_lo).x, w);
        font.draw(image, t.label, size, x, x_baseline, HAlign::center, VAlign::baseline, black);
    }
    for (const Tick& t : r_.y_ticks.ticks) {
        if (t.label.empty()) continue;
        const double y = snap(to_pixel(r_.x_lo, t.value).y, w);
        font.draw(image, t.label, size, f.x0 - m.tick_label_pad(), y, HAlign::right,
                  VAlign::digits_middle, black);
    }
    // Shared exponents: right of the x axis end, above the y axis top.
    if (!r_.x_ticks.multiplier.empty())
        font.draw(image, r_.x_ticks.multiplier, size, f.x1 + 0.5 * r_.x_label_width + 0.4 * m.font,
                  x_baseline, HAlign::left, VAlign::baseline, black);
    if (!r_.y_ticks.multiplier.empty())
        font.draw(image, r_.y_ticks.multiplier, size, f.x0, f.y0 - 0.4 * m.font, HAlign::left,
                  VAlign::bottom, black);

    // Axis labels.
    const double label_size = m.axis_label_size();
    // Axis labels sit on baselines a full line box away from the tick labels, so that "x" and
    // "\rho" labels of neighbouring panels line up.
    if (!xlabel_.empty()) {
        const double top = f.y1 + m.tick_label_pad() + r_.x_label_height + m.axis_label_pad();
        font.draw(image, xlabel_, label_size, (f.x0 + f.x1) / 2,
                  top + font.measure_line(xlabel_, label_size).ascent, HAlign::center,
                  VAlign::baseline, black);
    }
    if (!ylabel_.empty()) {
        const double right = f.x0 - m.tick_label_pad() - r_.y_label_width - m.axis_label_pad();
        font.draw(image, ylabel_, label_size,
                  right - font.measure_line(ylabel_, label_size).descent, (f.y0 + f.y1) / 2,
                  HAlign::center, VAlign::baseline, black, true);
    }

    // Panel letter at the top-left of the cell, title centred above the frame.
    if (!letter_.empty())
        font.draw(image, letter_, m.letter_size(), r_.cell.x0 + m.outer_pad(), f.y0 - 0.5 * m.font,
                  HAlign::left, VAlign::baseline, black);
    if (!title_.empty())
        font.draw(image, title_, m.title_size(), (f.x0 + f.x1) / 2, f.y0 - 0.5 * m.font,
                  HAlign::center, VAlign::bottom, black);

    // Annotations at data points.
    for (const Annotation& a : annotations_) {
        const Point p = to_pixel(a.x, a.y);
        const HAlign align = a.options.align == Align::left     ? HAlign::left
                             : a.options.align == Align::center ? HAlign::center
                                                                : HAlign::right;
        font.draw(image, a.markup, a.options.size * m.font, p.x, p.y, align, VAlign::digits_middle,
                  a.options.color);
    }
    draw_legend_text(font, image);
    draw_colorbar_text(font, image);
}

void Axes::draw_legend_text(Font& font, Image& image) const {
    const Metrics m{r_.font};
    const Rect& box = r_.legend_box;
    for (std::size_t k = 0; k < r_.legend_entries.size(); ++k) {
        const double y = snap(
            box.y0 + m.legend_pad() + (k + 0.5) * m.legend_row() - 0.15 * m.legend_size(), 1.0);
        const double x = box.x0 + m.legend_pad() + m.legend_sample() + 0.6 * m.font;
        font.draw(image, r_.legend_entries[k]->label, m.legend_size(), x, y, HAlign::left,
                  VAlign::digits_middle, black);
    }
}

void Axes::draw_colorbar_text(Font& font, Image& image) const {
    if (!r_.colorbar) return;
    const Metrics m{r_.font};
    const ColorRange& c = *r_.colorbar;
    const Rect& bar = r_.colorbar_rect;
    const Scale scale = c.log ? Scale::log : Scale::linear;
    for (const Tick& t : r_.c_ticks.ticks) {
        if (t.label.empty()) continue;
        const double y = snap(colorbar_y(bar, scale, c.lo, c.hi, t.value), m.frame_width());
        font.draw(image, t.label, m.tick_label_size(), bar.x1 + m.tick_label_pad(), y, HAlign::left,
                  VAlign::digits_middle, black);
    }
    if (!r_.c_ticks.multiplier.empty())
        font.draw(image, r_.c_ticks.multiplier, m.tick_label_size(), bar.x0, bar.y0 - 0.4 * m.font,
                  HAlign::left, VAlign::bottom, black);
    if (!c.label.empty()) {
        const double left = bar.x1 + m.tick_label_pad() + r_.c_label_width + m.axis_label_pad();
        font.draw(image, c.label, m.axis_label_size(),
                  left + font.measure_line(c.label, m.axis_label_size()).ascent,
                  (bar.y0 + bar.y1) / 2, HAlign::center, VAlign::baseline, black, true);
    }
}

}  // namespace plot
