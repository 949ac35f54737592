/// \file
/// \brief Turning polylines into triangles: widths, round joins, dash patterns (internal).
#pragma once

#include "plot/style.hpp"

#include <span>
#include <vector>

namespace plot::detail {

/// Triangles (x, y pairs, three vertices each) and round dots (x, y pairs, drawn as circle
/// markers of diameter dot_size) that together draw a stroked polyline.
struct StrokeGeometry {
    std::vector<float> triangles;
    std::vector<float> dots;
    double dot_size = 0.0;
};

/// Appends to \p out the geometry of the polyline \p points (final pixels) stroked with
/// \p width pixels in style \p dash.  Parts outside \p keep are dropped (they would be clipped
/// anyway); the dash phase stays continuous across them.  Segments meet with round joins where
/// the line turns by more than a few degrees.
///
/// Dash patterns scale with the width w (pixels): dashed 4w+2 on, 2.5w+1 off; dotted, round dots
/// of 1.3w every 2.5w+1.5; dash-dot, a dash, a gap, a dot, a gap.
void stroke_polyline(std::span<const Point> points, double width, Dash dash, const Rect& keep,
                     StrokeGeometry& out);

}  // namespace plot::detail
