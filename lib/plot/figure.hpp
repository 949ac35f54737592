/// \file
/// \brief Figures: panels in rows and columns, a title, a stamp line, rendered off-screen with
/// OSMesa and written as PNG.
///
/// \code
/// #include "plot/figure.hpp"
///
/// plot::Figure fig(1, 2, {.width = 1600, .height = 600});
/// fig.title("Sod shock tube, t = 0.2");
/// fig.stamp({.scheme = "SPH, Monaghan-Gingold AV", .kernel = "M4", .neighbours = 5,
///            .particles = 450, .run_time = 0.12});
/// plot::Axes& a = fig.panel(0, 0);                 // labelled (a)
/// a.xlabel("x [length]").ylabel("\\rho");
/// a.scatter(x, rho, {.label = "SPH", .color = plot::black, .size = 2.0});
/// a.line(xe, rhoe, {.label = "exact", .color = plot::red, .style = plot::Dash::dashed});
/// a.legend();
/// fig.save_png("sod.png");                         // throws plot::Error on failure
/// \endcode
///
/// \par Rendering
/// Lines, markers, frames, images and colour bars are drawn by GL into a buffer
/// FigureOptions::supersample times larger than the image, then box-filtered down; the text is
/// set afterwards at the final resolution with FreeType (DejaVu Sans).  The output depends only
/// on the figure's content: rendering it twice gives the same bytes.
#pragma once

#include "plot/axes.hpp"
#include "plot/color.hpp"
#include "plot/image.hpp"

#include <memory>
#include <string>
#include <vector>

namespace plot {

/// Size and look of a figure.
struct FigureOptions {
    int width = 0;              ///< final image width in pixels; 0: 800 per column
    int height = 0;             ///< final image height in pixels; 0: 600 per row
    double font_size = 16.0;    ///< tick-label font size in pixels; everything else scales with it
    int supersample = 3;        ///< GL renders at this multiple (1..4), then box-filters
    bool panel_letters = true;  ///< label the panels (a), (b), … in reading order
    std::string font{};         ///< TrueType font file; empty: DejaVu Sans (SPH_DEJAVU_FONT)
    Color background = white;
};

/// What produced the figure, for the stamp line at its foot.  Empty or negative fields are
/// left out.
struct Stamp {
    std::string scheme{};      ///< e.g. "Monaghan-Gingold AV"
    std::string kernel{};      ///< e.g. "M4"
    double neighbours = -1;    ///< the neighbour number N_{ngb}
    long long particles = -1;  ///< N
    double run_time = -1;      ///< wall-clock seconds
    std::string extra{};       ///< anything else, appended as is (markup)
};

/// The font file used when FigureOptions::font is empty: DejaVu Sans, as configured by the
/// CMake cache variable SPH_DEJAVU_FONT when the library was built.
std::string default_font();

/// The stamp line for \p stamp: "scheme · M4 kernel · N_{ngb} = 5 · N = 450 · 0.12 s".
std::string format_stamp(const Stamp& stamp);

/// A figure of rows × cols panels.
class Figure {
  public:
    /// Throws plot::Error for absurd layouts (rows or columns outside 1..16) or sizes (an image
    /// side outside 64..10000 pixels, a font size outside 4..200, supersampling outside 1..4).
    Figure(int rows = 1, int cols = 1, const FigureOptions& options = {});
    ~Figure();
    Figure(Figure&&) noexcept;
    Figure& operator=(Figure&&) noexcept;

    Figure& title(std::string markup);  ///< centred at the top
    Figure& stamp(std::string markup);  ///< small grey line at the bottom
    Figure& stamp(const Stamp& stamp) { return this->stamp(format_stamp(stamp)); }

    /// The panel in row \p row, column \p col (from the top left); throws if out of range.
    Axes& panel(int row, int col);
    /// The \p index -th panel in reading order.
    Axes& panel(int index);

    int rows() const { return rows_; }
    int cols() const { return cols_; }
    int width() const { return options_.width; }
    int height() const { return options_.height; }

    /// Lays out and draws the figure; afterwards each panel's frame(), to_pixel(), ticks are
    /// available.  Throws plot::Error (no GL context, font missing, bad data, panels too small).
    Image render();
    /// render() and write_png(): a failed render or write leaves no file at \p path.
    void save_png(const std::string& path);

  private:
    int rows_, cols_;
    FigureOptions options_;
    std::string title_, stamp_;
    std::vector<std::unique_ptr<Axes>> panels_;
};

}  // namespace plot
