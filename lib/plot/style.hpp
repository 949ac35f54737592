/// \file
/// \brief Small value types shared by the figure engine: pixel geometry, markers, dashes.
#pragma once

namespace plot {

/// A point in pixels of the final image: x to the right, y downwards, (0, 0) the top-left
/// corner of the top-left pixel (so pixel (i, j) covers [i, i+1) × [j, j+1)).
struct Point {
    double x = 0.0;
    double y = 0.0;
};

/// An axis-aligned rectangle in pixels of the final image (x0 < x1, y0 < y1, y downwards).
struct Rect {
    double x0 = 0.0;
    double y0 = 0.0;
    double x1 = 0.0;
    double y1 = 0.0;
    double width() const { return x1 - x0; }
    double height() const { return y1 - y0; }
    bool contains(const Point& p) const { return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1; }
};

/// Marker shapes for scatter plots and for the points of a line.
enum class Marker { none, circle, square, triangle, diamond, plus, cross };

/// Line styles.
enum class Dash { solid, dashed, dotted, dashdot };

/// Where a legend sits inside its panel.
enum class Corner { best, upper_right, upper_left, lower_left, lower_right };

}  // namespace plot
