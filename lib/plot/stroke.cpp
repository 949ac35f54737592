/// \file
/// \brief Polyline stroking with dash patterns.
#include "plot/stroke.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace plot::detail {
namespace {

/// A dash pattern: alternating on and off lengths, with zero-length "on" elements meaning dots.
struct Pattern {
    std::vector<double> lengths;  ///< on, off, on, off, ...
    double period() const {
        double p = 0.0;
        for (double l : lengths) p += l;
        return p;
    }
};

Pattern make_pattern(Dash dash, double w) {
    const double dash_on = 4.0 * w + 2.0, dash_off = 2.5 * w + 1.0;
    const double dot_step = 2.5 * w + 1.5;
    switch (dash) {
        case Dash::solid:
            return {};
        case Dash::dashed:
            return {{dash_on, dash_off}};
        case Dash::dotted:
            return {{0.0, dot_step}};
        case Dash::dashdot:
            return {{dash_on, dot_step * 0.8, 0.0, dot_step * 0.8}};
    }
    return {};
}

void push(std::vector<float>& v, double x, double y) {
    v.push_back(static_cast<float>(x));
    v.push_back(static_cast<float>(y));
}

/// A quad of half-width \p h from a to b, as two triangles.
void add_quad(StrokeGeometry& out, Point a, Point b, double h) {
    const double dx = b.x - a.x, dy = b.y - a.y, len = std::hypot(dx, dy);
    if (len <= 0.0) return;
    const double nx = -dy / len * h, ny = dx / len * h;
    auto& t = out.triangles;
    push(t, a.x + nx, a.y + ny);
    push(t, b.x + nx, b.y + ny);
    push(t, b.x - nx, b.y - ny);
    push(t, a.x + nx, a.y + ny);
    push(t, b.x - nx, b.y - ny);
    push(t, a.x - nx, a.y - ny);
}

/// A round join: a disc of radius \p h as a triangle fan.
void add_disc(StrokeGeometry& out, Point c, double h) {
    constexpr int sides = 12;
    for (int k = 0; k < sides; ++k) {
        const double a0 = 2 * std::numbers::pi * k / sides,
                     a1 = 2 * std::numbers::pi * (k + 1) / sides;
        push(out.triangles, c.x, c.y);
        push(out.triangles, c.x + h * std::cos(a0), c.y + h * std::sin(a0));
        push(out.triangles, c.x + h * std::cos(a1), c.y + h * std::sin(a1));
    }
}

Point lerp(Point a, Point b, double s) { return {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)}; }

/// The part [s0, s1] ⊂ [0, 1] of segment a -> b inside \p box (Liang-Barsky); false if none.
bool clip_segment(Point a, Point b, const Rect& box, double& s0, double& s1) {
    s0 = 0.0;
    s1 = 1.0;
    const double d[2] = {b.x - a.x, b.y - a.y};
    const double lo[2] = {box.x0 - a.x, box.y0 - a.y}, hi[2] = {box.x1 - a.x, box.y1 - a.y};
    for (int k = 0; k < 2; ++k) {
        if (d[k] == 0.0) {
            if (lo[k] > 0.0 || hi[k] < 0.0) return false;
            continue;
        }
        double t0 = lo[k] / d[k], t1 = hi[k] / d[k];
        if (t0 > t1) std::swap(t0, t1);
        s0 = std::max(s0, t0);
        s1 = std::min(s1, t1);
    }
    return s0 <= s1;
}

/// Whether the line turns at b (from a -> b to b -> c) enough for a gap to show.
bool needs_join(Point a, Point b, Point c) {
    const double ux = b.x - a.x, uy = b.y - a.y, vx = c.x - b.x, vy = c.y - b.y;
    const double lu = std::hypot(ux, uy), lv = std::hypot(vx, vy);
    if (lu == 0.0 || lv == 0.0) return false;
    return (ux * vx + uy * vy) / (lu * lv) < 0.985;  // about 10 degrees
}

/// Emits the "on" parts of the pattern along one segment, from arc length \p phase into the
/// pattern; returns whether the pattern is "on" at the segment's end.
bool dash_segment(StrokeGeometry& out, Point a, Point b, double s0, double s1, double h,
                  const Pattern& pattern, double phase) {
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    const std::vector<double>& lengths = pattern.lengths;
    // The pattern element k and the position in it at the start of the visible part.  A dot
    // (length 0) is hit only when the position is exactly at it.
    double position = std::fmod(phase + s0 * len, pattern.period());
    std::size_t k = 0;
    while (position > lengths[k] || (position == lengths[k] && lengths[k] > 0.0)) {
        position -= lengths[k];
        k = (k + 1) % lengths.size();
    }
    // Walk the elements to the end of the visible part, emitting the "on" ones.
    double t = s0 * len;
    const double end = s1 * len;
    while (t < end) {
        const double remaining = lengths[k] - position;
        if (k % 2 == 0 && lengths[k] == 0.0) {
            const Point dot = lerp(a, b, t / len);
            push(out.dots, dot.x, dot.y);
        } else if (k % 2 == 0) {
            add_quad(out, lerp(a, b, t / len), lerp(a, b, std::min(end, t + remaining) / len), h);
        }
        if (t + remaining > end) break;
        t += remaining;
        position = 0.0;
        k = (k + 1) % lengths.size();
    }
    return k % 2 == 0 && lengths[k] > 0.0;
}

}  // namespace

void stroke_polyline(std::span<const Point> points, double width, Dash dash, const Rect& keep,
                     StrokeGeometry& out) {
    const double h = width / 2.0;
    const Pattern pattern = make_pattern(dash, width);
    if (dash == Dash::dotted || dash == Dash::dashdot) out.dot_size = 1.3 * width;
    const Rect box{keep.x0 - width, keep.y0 - width, keep.x1 + width, keep.y1 + width};

    double phase = 0.0;  // arc length travelled, modulo the pattern period
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        const Point a = points[i], b = points[i + 1];
        const double len = std::hypot(b.x - a.x, b.y - a.y);
        double s0 = 0.0, s1 = 1.0;
        const bool visible = len > 0.0 && clip_segment(a, b, box, s0, s1);
        bool on_at_end = true;
        if (visible && pattern.lengths.empty()) {
            add_quad(out, lerp(a, b, s0), lerp(a, b, s1), h);
        } else if (visible) {
            on_at_end = dash_segment(out, a, b, s0, s1, h, pattern, phase);
        }
        // Round join at b where the stroke continues through a turn.
        if (visible && on_at_end && s1 >= 1.0 && i + 2 < points.size() &&
            needs_join(a, b, points[i + 2]))
            add_disc(out, b, h);
        if (!pattern.lengths.empty()) phase = std::fmod(phase + len, pattern.period());
    }
}

}  // namespace plot::detail
