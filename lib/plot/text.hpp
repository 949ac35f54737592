/// \file
/// \brief Text in figures: FreeType glyphs of DejaVu Sans, laid out from markup runs and
/// blended into the final image (internal to the figure engine).
///
/// Text is not drawn by GL: the scene is rendered supersampled and box-filtered first, then
/// the glyph bitmaps are blended at the final resolution, where FreeType's own antialiasing and
/// light hinting make small labels crisp.
#pragma once

#include "plot/color.hpp"
#include "plot/image.hpp"
#include "plot/markup.hpp"

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace plot::detail {

/// Horizontal anchor of a text box.
enum class HAlign { left, center, right };

/// Vertical anchor of a text box: its ink top, its baseline, the middle of its digits (so a
/// label such as "10^{3}" sits centred on its tick by its "10", not by its superscript), or its
/// ink bottom.
enum class VAlign { top, baseline, digits_middle, bottom };

/// The extent of a laid-out text in pixels: the advance width, and the ink above and below
/// the baseline (both >= 0).
struct TextMetrics {
    double width = 0.0;
    double ascent = 0.0;
    double descent = 0.0;
    double height() const { return ascent + descent; }
};

/// A glyph coverage bitmap as FreeType renders it, with its placement relative to the pen.
struct GlyphBitmap {
    int width = 0;
    int rows = 0;
    int left = 0;          ///< pixels from the pen to the bitmap's left edge
    int top = 0;           ///< pixels from the baseline up to the bitmap's top row
    double advance = 0.0;  ///< unhinted advance width in pixels
    std::vector<unsigned char> coverage;
};

/// A face of one TrueType font at any size.  Not thread-safe: one per render.
class Font {
  public:
    /// Opens the font at \p path; throws plot::Error if FreeType cannot load it.
    explicit Font(const std::string& path);
    ~Font();
    Font(const Font&) = delete;
    Font& operator=(const Font&) = delete;

    /// The extent of \p runs set at base size \p size pixels.
    TextMetrics measure(const std::vector<TextRun>& runs, double size);
    /// The extent of the markup \p text set at \p size pixels.
    TextMetrics measure(std::string_view text, double size) {
        return measure(parse_markup(text), size);
    }

    /// Like measure(), but at least as tall as a line of text ("Ay") at that size, so that
    /// labels without ascenders or descenders (e.g. "x") take the same room as any other.
    TextMetrics measure_line(std::string_view text, double size);

    /// The code points of \p runs the font has no glyph for (the fixed-width spaces need none).
    std::vector<char32_t> missing_glyphs(const std::vector<TextRun>& runs);

    /// The height of the digit "0" at \p size pixels.
    double digit_height(double size);

    /// Blends \p runs into \p image with the anchor point of the text box at (x, y).  With
    /// \p vertical the text reads upwards (turned 90° anticlockwise) and the anchors refer to
    /// the text's own frame.
    void draw(Image& image, const std::vector<TextRun>& runs, double size, double x, double y,
              HAlign halign, VAlign valign, const Color& color, bool vertical = false);
    /// Same for markup text.
    void draw(Image& image, std::string_view text, double size, double x, double y, HAlign halign,
              VAlign valign, const Color& color, bool vertical = false) {
        draw(image, parse_markup(text), size, x, y, halign, valign, color, vertical);
    }

  private:
    struct Placed {
        const GlyphBitmap* glyph;
        int x;         ///< pen position (pixels from the text origin)
        int baseline;  ///< baseline offset, pixels upwards
    };
    struct Layout {
        std::vector<Placed> glyphs;
        TextMetrics metrics;
        int ink_left = 0, ink_right = 0;
    };

    Layout layout(const std::vector<TextRun>& runs, double size);
    const GlyphBitmap& glyph(unsigned glyph_index, long size_26_6);
    void select_size(long size_26_6);

    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::map<std::pair<unsigned, long>, GlyphBitmap> cache_;
};

/// Decodes UTF-8 into code points (invalid bytes become U+FFFD).
std::vector<char32_t> decode_utf8(std::string_view text);

}  // namespace plot::detail
