/// \file
/// \brief One panel of a figure: axes with ticks and labels, and what is drawn in them.
///
/// A panel is made by plot::Figure::panel(); its calls chain:
/// \code
/// plot::Axes& ax = fig.panel(0, 0);
/// ax.xlabel("x [length]").ylabel("\\rho").xlim(-0.5, 0.5);
/// ax.scatter(x, rho, {.label = "SPH", .color = plot::black, .size = 2.0});
/// ax.line(x_exact, rho_exact,
///         {.label = "exact", .color = plot::red, .style = plot::Dash::dashed});
/// ax.legend(plot::Corner::upper_right);
/// \endcode
///
/// \par Data that is not finite
/// NaN and ±infinity in scatter, line and image data are \e skipped and counted, never drawn:
/// skipped_points() reports how many (values ≤ 0 on a logarithmic axis are skipped and
/// counted too, at render time).  A line is broken at a skipped point.  A series that is empty,
/// whose x and y differ in length, or whose every point is skipped is refused with plot::Error.
#pragma once

#include "plot/color.hpp"
#include "plot/markup.hpp"
#include "plot/style.hpp"
#include "plot/ticks.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace plot {

namespace detail {
class Canvas;
class Font;
struct PanelTransform;
}  // namespace detail
struct Image;

/// How points of a scatter series look.  Sizes are pixels of the final image.
struct ScatterOptions {
    std::string label{};           ///< legend text (markup); empty: not in the legend
    std::optional<Color> color{};  ///< default: the panel's next cycle colour
    double size = 3.0;             ///< marker diameter in pixels
    Marker marker = Marker::circle;
    bool filled = true;  ///< false: outlined shapes
    double alpha = 1.0;  ///< opacity in (0, 1]
};

/// How a line series looks.
struct LineOptions {
    std::string label{};  ///< legend text (markup); empty: not in the legend
    std::optional<Color>
        color{};  ///< default: the panel's next cycle colour (grey for hline/vline)
    Dash style = Dash::solid;
    double width = 1.5;            ///< line width in pixels
    Marker marker = Marker::none;  ///< a marker at every data point, if not none
    double marker_size = 8.0;      ///< marker diameter in pixels
    bool marker_filled = true;
};

/// How values become colours: a map, its range, linear or logarithmic, and the colour bar.
/// A panel shows one colour bar, that of the last image or coloured scatter asking for one.
struct ImageOptions {
    Colormap map = Colormap::viridis;
    std::optional<double> zmin{};  ///< default: the smallest finite (positive, if log) value
    std::optional<double> zmax{};  ///< default: the largest finite value
    bool log = false;              ///< map log10 of the value
    std::string colorbar_label{};  ///< markup, beside the colour bar
    bool colorbar = true;          ///< draw a colour bar at the right of the panel
};

/// A scatter whose points are coloured by a third quantity.
struct ColorScatterOptions {
    Colormap map = Colormap::viridis;
    std::optional<double> zmin{};
    std::optional<double> zmax{};
    bool log = false;
    std::string colorbar_label{};
    bool colorbar = true;
    double size = 3.0;
    Marker marker = Marker::circle;
    std::string label{};  ///< legend text; the legend shows the map's middle colour
};

/// The data rectangle an image covers: x0..x1 along x, y0..y1 along y.
struct Extent {
    double x0 = 0.0;
    double x1 = 1.0;
    double y0 = 0.0;
    double y1 = 1.0;
};

/// Horizontal alignment of text placed at a data point.
enum class Align { left, center, right };

/// Text placed at data coordinates.
struct TextOptions {
    Color color = black;
    double size = 1.0;          ///< relative to the figure's font size
    Align align = Align::left;  ///< which end of the text sits at x; vertically centred on y
};

/// One panel: a frame with ticks on all four sides, labels, and layers of data.
class Axes {
  public:
    /// \name Labels and limits
    /// \{
    Axes& xlabel(std::string markup);  ///< e.g. "x [length]"; throws on bad markup
    Axes& ylabel(std::string markup);  ///< e.g. "\\rho"
    Axes& title(std::string markup);   ///< a small title centred above the frame
    Axes& letter(std::string markup);  ///< replaces the automatic "(a)"; "" hides it
    Axes& xlim(double lo, double hi);  ///< fixed limits (lo < hi); default: from the data
    Axes& ylim(double lo, double hi);
    Axes& xscale(Scale scale);
    Axes& yscale(Scale scale);
    Axes& equal_aspect(bool on = true);  ///< one data unit is as long on x as on y
    /// Show a legend of the labelled series.  With `make_room`, when the y limits are
    /// automatic and the legend would hide data in every corner it may take, the y axis is
    /// extended upwards until the legend fits above the data (a panel whose curves fill it).
    Axes& legend(Corner corner = Corner::best, bool make_room = false);
    Axes& hide(bool hidden = true);  ///< leave this panel's cell empty (no frame, no letter)
    /// \}

    /// \name Data
    /// Data is copied; NaN and infinities are skipped and counted (see skipped_points()).
    /// \{
    /// Markers at (x[i], y[i]), all in one GL draw call (10^6 points take well under a second).
    Axes& scatter(std::span<const double> x, std::span<const double> y,
                  const ScatterOptions& options = {});
    /// Markers coloured by values[i] through a colour map, with a colour bar by default.
    Axes& scatter(std::span<const double> x, std::span<const double> y,
                  std::span<const double> values, const ColorScatterOptions& options);
    /// A polyline through the points in the order given, broken at skipped points.
    Axes& line(std::span<const double> x, std::span<const double> y,
               const LineOptions& options = {});
    /// A reference level across the panel (grey unless a colour is given); it counts for the
    /// y limits.
    Axes& hline(double y, const LineOptions& options = {});
    /// A vertical reference line; it counts for the x limits.
    Axes& vline(double x, const LineOptions& options = {});
    /// A field on a regular grid: grid(i, j) is the cell i along x, j along y, cell (0, 0) at
    /// the (x0, y0) corner.  NaN cells (and cells ≤ 0 with a log colour scale) stay blank.
    /// Images are drawn beneath all other series.  On a logarithmic axis the cells are spread
    /// evenly between the extent's edges on screen.
    Axes& image(const Eigen::ArrayXXd& grid, const Extent& extent,
                const ImageOptions& options = {});
    /// The same with values[i + nx * j] (x fastest).
    Axes& image(std::span<const double> values, int nx, int ny, const Extent& extent,
                const ImageOptions& options = {});
    /// Text at data point (x, y), drawn over everything; it does not count for the limits.
    Axes& text(double x, double y, std::string markup, const TextOptions& options = {});
    /// \}

    /// Points skipped because they were NaN or infinite, or (after a render) not positive on a
    /// logarithmic axis.
    std::size_t skipped_points() const { return skipped_nonfinite_ + skipped_nonpositive_; }

    /// \name After a render
    /// Where things landed, for tests and for drawing over the image.  Throw plot::Error before
    /// the figure has been rendered.
    /// \{
    /// The plot area in pixels.  Its edges lie on pixel centres; the frame lines are centred
    /// on them.  A data point at the axis limits maps onto the edges.
    Rect frame() const;
    /// The legend's box in pixels (empty when the panel has no legend).
    Rect legend_box() const;
    /// Data -> pixel position in the final image (pixel (i, j) covers [i, i+1) × [j, j+1)).
    Point to_pixel(double x, double y) const;
    std::pair<double, double> xrange() const;  ///< the x limits used
    std::pair<double, double> yrange() const;  ///< the y limits used
    const TickSet& xticks() const;             ///< the ticks drawn on the x axes
    const TickSet& yticks() const;             ///< the ticks drawn on the y axes
                                               /// \}

  private:
    friend class Figure;
    Axes(std::size_t index, std::string letter) : index_(index), letter_(std::move(letter)) {}

    enum class Kind { scatter, color_scatter, line, hline, vline };
    struct Series {
        Kind kind;
        std::vector<double> x, y, values;
        ScatterOptions scatter;
        LineOptions line;
        ColorScatterOptions color_scatter;
        Color color;
        std::string label;
    };
    struct Layer {
        std::vector<double> values;
        int nx, ny;
        Extent extent;
        ImageOptions options;
    };
    struct Annotation {
        double x, y;
        std::string markup;
        TextOptions options;
    };
    /// A resolved colour scale: map, range, and whether it is logarithmic.
    struct ColorRange {
        Colormap map;
        double lo, hi;
        bool log;
        std::string label;
        Color at(double value) const;
    };
    /// Everything decided at render time.
    struct Resolved {
        bool done = false;
        double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;
        Rect cell, frame;
        TickSet x_ticks, y_ticks, c_ticks;
        std::optional<ColorRange> colorbar;
        Rect colorbar_rect;
        Rect legend_box;
        std::vector<const Series*> legend_entries;
        double font = 16;
        double x_label_ascent = 0, x_label_height = 0, x_label_width = 0, y_label_width = 0,
               c_label_width = 0;
    };
    struct Margins {
        double left = 0, right = 0, top = 0, bottom = 0;
    };

    // axes.cpp: data and limits
    std::string name() const;
    Series& add_series(Kind kind, std::span<const double> x, std::span<const double> y,
                       std::string label, const char* what);
    Color next_color();
    void resolve_limits();
    std::pair<double, double> auto_limits(bool x_axis) const;
    double axis_u(double v, bool x_axis) const;
    void require_rendered() const;
    ColorRange resolve_color_range(Colormap map, std::optional<double> zmin,
                                   std::optional<double> zmax, bool log, const std::string& label,
                                   std::span<const double> values) const;

    // axes_layout.cpp: ticks, margins, legend and colour bar geometry
    Margins measure(detail::Font& font, double font_size, const Rect& cell,
                    const Rect& frame_guess);
    void place(detail::Font& font, const Rect& frame);
    void resolve_colorbar();
    TickSet fit_ticks(detail::Font& font, Scale scale, double lo, double hi, double length,
                      bool horizontal) const;
    void place_legend(detail::Font& font);
    double legend_crowding(const Rect& box) const;
    void make_legend_room(detail::Font& font, const Rect& frame_guess);

    // axes_draw.cpp: GL layers, then text
    void draw(detail::Canvas& canvas) const;
    void draw_images(detail::Canvas& canvas) const;
    void draw_scatter(detail::Canvas& canvas, const detail::PanelTransform& to_px,
                      const Series& s) const;
    void draw_color_scatter(detail::Canvas& canvas, const detail::PanelTransform& to_px,
                            const Series& s) const;
    void draw_line(detail::Canvas& canvas, const detail::PanelTransform& to_px,
                   const Series& s) const;
    void draw_reference(detail::Canvas& canvas, const detail::PanelTransform& to_px,
                        const Series& s) const;
    void draw_stroke(detail::Canvas& canvas, std::span<const Point> points,
                     const LineOptions& style, const Color& color) const;
    void draw_frame(detail::Canvas& canvas) const;
    void draw_legend(detail::Canvas& canvas) const;
    void draw_colorbar(detail::Canvas& canvas) const;
    void draw_text(detail::Font& font, Image& image) const;
    void draw_legend_text(detail::Font& font, Image& image) const;
    void draw_colorbar_text(detail::Font& font, Image& image) const;

    std::size_t index_;
    std::string letter_{};
    std::string xlabel_, ylabel_, title_;
    std::optional<std::pair<double, double>> xlim_, ylim_;
    Scale xscale_ = Scale::linear, yscale_ = Scale::linear;
    bool equal_aspect_ = false;
    bool hidden_ = false;
    std::optional<Corner> legend_{};
    bool legend_room_ = false;
    std::vector<Series> series_;
    std::vector<Layer> layers_;
    std::vector<Annotation> annotations_;
    std::size_t colors_used_ = 0;
    std::size_t skipped_nonfinite_ = 0;
    std::size_t skipped_nonpositive_ = 0;
    Resolved r_;
};

}  // namespace plot
