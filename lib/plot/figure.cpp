/// \file
/// \brief Figure layout and the render pipeline: measure, align, draw with GL, set the text.
#include "plot/figure.hpp"

#include "plot/context.hpp"
#include "plot/error.hpp"
#include "plot/metrics.hpp"
#include "plot/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#ifndef SPH_DEJAVU_FONT
#define SPH_DEJAVU_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#endif

namespace plot {

using detail::Font;
using detail::HAlign;
using detail::Metrics;
using detail::VAlign;

namespace {

void require(bool ok, const std::string& message) {
    if (!ok) throw Error(message);
}

std::string panel_letter(std::size_t index) {
    std::string letter = "(";
    if (index < 26)
        letter += static_cast<char>('a' + index);
    else
        letter += std::to_string(index + 1);
    letter += ')';
    return letter;
}

/// The largest supersampling factor up to \p wanted that keeps the GL buffer within OSMesa's
/// side limit and about 400 MB.
int affordable_supersample(int width, int height, int wanted) {
    int s = wanted;
    while (s > 1 && (static_cast<long>(width) * s > detail::max_buffer_side ||
                     static_cast<long>(height) * s > detail::max_buffer_side ||
                     static_cast<double>(width) * height * s * s > 100e6))
        --s;
    return s;
}

/// Three significant digits, but never in exponent form for values a stamp shows (≥ 1000
/// are given whole: "1234 s", not "1.23e+03 s").
std::string trim_number(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, v >= 1000 ? "%.0f" : "%.3g", v);
    return buffer;
}

}  // namespace

std::string default_font() { return SPH_DEJAVU_FONT; }

std::string format_stamp(const Stamp& s) {
    std::vector<std::string> parts;
    if (!s.scheme.empty()) parts.push_back(s.scheme);
    if (!s.kernel.empty()) parts.push_back(s.kernel + " kernel");
    if (s.neighbours >= 0) parts.push_back("N_{ngb} = " + trim_number(s.neighbours));
    if (s.particles >= 0) parts.push_back("N = " + std::to_string(s.particles));
    if (s.run_time >= 0) parts.push_back(trim_number(s.run_time) + " s");
    if (!s.extra.empty()) parts.push_back(s.extra);
    std::string line;
    for (std::size_t i = 0; i < parts.size(); ++i) line += (i ? ", " : "") + parts[i];
    return line;
}

// ---- Construction -------------------------------------------------------------------------------
Figure::Figure(int rows, int cols, const FigureOptions& options)
    : rows_(rows), cols_(cols), options_(options) {
    require(rows >= 1 && rows <= 16 && cols >= 1 && cols <= 16,
            "a figure of " + std::to_string(rows) + "×" + std::to_string(cols) +
                " panels (rows and columns must lie in 1..16)");
    if (options_.width == 0) options_.width = 800 * cols;
    if (options_.height == 0) options_.height = 600 * rows;
    require(options_.width >= 64 && options_.width <= 10000 && options_.height >= 64 &&
                options_.height <= 10000,
            "figure size " + std::to_string(options_.width) + "×" +
                std::to_string(options_.height) + " px is outside 64..10000 px a side");
    require(options_.font_size >= 4 && options_.font_size <= 200,
            "font size " + std::to_string(options_.font_size) + " px is outside 4..200");
    require(options_.supersample >= 1 && options_.supersample <= 4,
            "supersampling " + std::to_string(options_.supersample) + " is outside 1..4");
    if (options_.font.empty()) options_.font = default_font();
    for (int i = 0; i < rows * cols; ++i) {
        const auto index = static_cast<std::size_t>(i);
        panels_.push_back(std::unique_ptr<Axes>(
            new Axes(index, options_.panel_letters ? panel_letter(index) : "")));
    }
}

Figure::~Figure() = default;
Figure::Figure(Figure&&) noexcept = default;
Figure& Figure::operator=(Figure&&) noexcept = default;

Figure& Figure::title(std::string markup) {
    parse_markup(markup);
    title_ = std::move(markup);
    return *this;
}

Figure& Figure::stamp(std::string markup) {
    parse_markup(markup);
    stamp_ = std::move(markup);
    return *this;
}

Axes& Figure::panel(int row, int col) {
    require(row >= 0 && row < rows_ && col >= 0 && col < cols_,
            "no panel (" + std::to_string(row) + ", " + std::to_string(col) + ") in a " +
                std::to_string(rows_) + "×" + std::to_string(cols_) + " figure");
    return *panels_[static_cast<std::size_t>(row * cols_ + col)];
}

Axes& Figure::panel(int index) {
    require(
        index >= 0 && index < rows_ * cols_,
        "no panel " + std::to_string(index) + " in a figure of " + std::to_string(rows_ * cols_));
    return *panels_[static_cast<std::size_t>(index)];
}

// ---- Render -------------------------------------------------------------------------------------
Image Figure::render() {
    const Metrics m{options_.font_size};
    const double W = options_.width, H = options_.height;
    Font font(options_.font);

    // Bands for the title and the stamp; the panels share the rest in a regular grid.
    const double top =
        title_.empty()
            ? 0.0
            : m.outer_pad() + font.measure_line(title_, m.title_size()).height() + 0.2 * m.font;
    const double bottom =
        stamp_.empty() ? 0.0 : font.measure_line(stamp_, m.stamp_size()).height() + m.outer_pad();
    const double cell_w = W / cols_, cell_h = (H - top - bottom) / rows_;
    auto cell = [&](int r, int c) {
        return Rect{c * cell_w, top + r * cell_h, (c + 1) * cell_w, top + (r + 1) * cell_h};
    };
    auto inset = [](const Rect& c, double l, double t, double r, double b) {
        return Rect{c.x0 + l, c.y0 + t, c.x1 - r, c.y1 - b};
    };

    // Measure every panel twice (the second time for a frame of about its final size), then
    // align: one left/right margin per column, one top/bottom margin per row.
    std::vector<double> left(cols_, 0), right(cols_, 0), upper(rows_, 0), lower(rows_, 0);
    for (int r = 0; r < rows_; ++r) {
        for (int c = 0; c < cols_; ++c) {
            Axes& ax = *panels_[static_cast<std::size_t>(r * cols_ + c)];
            const Rect k = cell(r, c);
            auto guess =
                ax.measure(font, m.font, k,
                           inset(k, 0.15 * cell_w, 0.1 * cell_h, 0.05 * cell_w, 0.15 * cell_h));
            guess = ax.measure(font, m.font, k,
                               inset(k, guess.left, guess.top, guess.right, guess.bottom));
            left[c] = std::max(left[c], guess.left);
            right[c] = std::max(right[c], guess.right);
            upper[r] = std::max(upper[r], guess.top);
            lower[r] = std::max(lower[r], guess.bottom);
        }
    }
    for (int r = 0; r < rows_; ++r)
        for (int c = 0; c < cols_; ++c)
            panels_[static_cast<std::size_t>(r * cols_ + c)]->place(
                font, inset(cell(r, c), left[c], upper[r], right[c], lower[r]));

    // GL: data, frames, colour bars, legend boxes.
    detail::Canvas canvas(
        options_.width, options_.height,
        affordable_supersample(options_.width, options_.height, options_.supersample),
        options_.background);
    for (const auto& ax : panels_) ax->draw(canvas);
    Image image = canvas.resolve();

    // Text at the final resolution.
    for (const auto& ax : panels_) ax->draw_text(font, image);
    if (!title_.empty())
        font.draw(image, title_, m.title_size(), W / 2,
                  m.outer_pad() + font.measure_line(title_, m.title_size()).ascent, HAlign::center,
                  VAlign::baseline, black);
    if (!stamp_.empty())
        font.draw(image, stamp_, m.stamp_size(), m.outer_pad(),
                  H - 0.5 * m.outer_pad() - font.measure_line(stamp_, m.stamp_size()).descent,
                  HAlign::left, VAlign::baseline, Color{0.45, 0.45, 0.45});
    return image;
}

void Figure::save_png(const std::string& path) {
    check_writable(path);  // fail before the render, not after it
    write_png(render(), path);
}

}  // namespace plot
