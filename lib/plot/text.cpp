/// \file
/// \brief FreeType text layout and blending.
#include "plot/text.hpp"

#include "plot/error.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>

namespace plot::detail {

struct Font::Impl {
    FT_Library library = nullptr;
    FT_Face face = nullptr;
    long current_size = -1;
};

// ---- UTF-8 ----------------------------------------------------------------------------------
std::vector<char32_t> decode_utf8(std::string_view text) {
    std::vector<char32_t> out;
    for (std::size_t i = 0; i < text.size();) {
        const auto lead = static_cast<unsigned char>(text[i]);
        int length = lead < 0x80 ? 1 : lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 0;
        if (length == 0 || i + length > text.size()) {
            out.push_back(0xFFFD);
            ++i;
            continue;
        }
        char32_t cp = length == 1 ? lead : lead & (0xFF >> (length + 1));
        for (int k = 1; k < length; ++k)
            cp = (cp << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
        out.push_back(cp);
        i += length;
    }
    return out;
}

namespace {

/// Widths of the Unicode spaces U+2002..U+200A in em, so that markup spacing does not depend
/// on the font having those glyphs.  Zero for anything else.
double space_width_em(char32_t cp) {
    switch (cp) {
        case 0x2002:
            return 0.5;
        case 0x2003:
            return 1.0;
        case 0x2004:
            return 1.0 / 3.0;
        case 0x2005:
            return 0.25;
        case 0x2006:
            return 1.0 / 6.0;
        case 0x2007:
            return 0.636;
        case 0x2008:
            return 0.318;
        case 0x2009:
            return 0.2;
        case 0x200A:
            return 0.1;
        default:
            return 0.0;
    }
}

long to_26_6(double pixels) { return std::lround(pixels * 64.0); }

}  // namespace

// ---- Font -----------------------------------------------------------------------------------
Font::Font(const std::string& path) : impl_(std::make_unique<Impl>()) {
    if (FT_Init_FreeType(&impl_->library) != 0) throw Error("FreeType could not start");
    if (FT_New_Face(impl_->library, path.c_str(), 0, &impl_->face) != 0) {
        FT_Done_FreeType(impl_->library);
        throw Error("cannot load the font '" + path +
                    "' (set SPH_DEJAVU_FONT or FigureOptions::font)");
    }
}

Font::~Font() {
    FT_Done_Face(impl_->face);
    FT_Done_FreeType(impl_->library);
}

void Font::select_size(long size_26_6) {
    if (impl_->current_size == size_26_6) return;
    FT_Set_Char_Size(impl_->face, 0, size_26_6, 72, 72);
    impl_->current_size = size_26_6;
}

const GlyphBitmap& Font::glyph(unsigned glyph_index, long size_26_6) {
    const auto key = std::make_pair(glyph_index, size_26_6);
    if (auto it = cache_.find(key); it != cache_.end()) return it->second;

    // Light hinting snaps heights to the pixel grid but keeps the glyph shapes and widths.
    select_size(size_26_6);
    GlyphBitmap bitmap;
    FT_Face face = impl_->face;
    if (FT_Load_Glyph(face, glyph_index, FT_LOAD_TARGET_LIGHT | FT_LOAD_RENDER) == 0) {
        const FT_Bitmap& b = face->glyph->bitmap;
        bitmap.width = static_cast<int>(b.width);
        bitmap.rows = static_cast<int>(b.rows);
        bitmap.left = face->glyph->bitmap_left;
        bitmap.top = face->glyph->bitmap_top;
        bitmap.advance = face->glyph->linearHoriAdvance / 65536.0;
        bitmap.coverage.resize(static_cast<std::size_t>(bitmap.width) * bitmap.rows);
        for (int r = 0; r < bitmap.rows; ++r)
            std::copy_n(b.buffer + static_cast<std::ptrdiff_t>(r) * b.pitch, bitmap.width,
                        bitmap.coverage.begin() + static_cast<std::ptrdiff_t>(r) * bitmap.width);
    }
    return cache_.emplace(key, std::move(bitmap)).first->second;
}

Font::Layout Font::layout(const std::vector<TextRun>& runs, double size) {
    Layout out;
    FT_Face face = impl_->face;
    double pen = 0.0;  // pixels, unrounded
    bool first_ink = true;
    double ascent = 0.0, descent = 0.0;
    double run_start = 0.0;  // pen position where the previous run started
    for (const TextRun& run : runs) {
        // A stacked script starts where the previous one did; the pen then goes on from
        // whichever of the two ends further right.
        const double resume = run.stacked ? pen : 0.0;
        if (run.stacked) pen = run_start;
        run_start = pen;
        const double run_size = size * run.scale;
        const long size_26_6 = to_26_6(run_size);
        const int baseline = static_cast<int>(std::lround(run.shift * size));
        unsigned previous = 0;
        for (char32_t cp : decode_utf8(run.text)) {
            // Fixed-width spaces: advance only.
            if (const double em = space_width_em(cp); em > 0.0) {
                pen += em * run_size;
                previous = 0;
                continue;
            }
            select_size(size_26_6);
            const unsigned index = FT_Get_Char_Index(face, cp);
            if (previous != 0 && index != 0 && FT_HAS_KERNING(face)) {
                FT_Vector kern;
                if (FT_Get_Kerning(face, previous, index, FT_KERNING_UNFITTED, &kern) == 0)
                    pen += kern.x / 64.0;
            }
            const GlyphBitmap& g = glyph(index, size_26_6);
            const double advance = g.advance;
            const int x = static_cast<int>(std::lround(pen));
            out.glyphs.push_back({&g, x, baseline});
            if (g.width > 0 && g.rows > 0) {
                const int left = x + g.left, right = x + g.left + g.width;
                out.ink_left = first_ink ? left : std::min(out.ink_left, left);
                out.ink_right = first_ink ? right : std::max(out.ink_right, right);
                ascent = first_ink ? baseline + g.top : std::max<double>(ascent, baseline + g.top);
                descent = first_ink ? g.rows - g.top - baseline
                                    : std::max<double>(descent, g.rows - g.top - baseline);
                first_ink = false;
            }
            pen += advance;
            previous = index;
        }
        pen = std::max(pen, resume);
    }
    out.metrics = {pen, std::max(0.0, ascent), std::max(0.0, descent)};
    return out;
}

TextMetrics Font::measure(const std::vector<TextRun>& runs, double size) {
    return layout(runs, size).metrics;
}

TextMetrics Font::measure_line(std::string_view text, double size) {
    TextMetrics m = measure(text, size);
    const TextMetrics line = measure(std::vector<TextRun>{{"Ay", 0.0, 1.0}}, size);
    m.ascent = std::max(m.ascent, line.ascent);
    m.descent = std::max(m.descent, line.descent);
    return m;
}

std::vector<char32_t> Font::missing_glyphs(const std::vector<TextRun>& runs) {
    std::vector<char32_t> missing;
    for (const TextRun& run : runs)
        for (char32_t cp : decode_utf8(run.text))
            if (space_width_em(cp) == 0.0 && FT_Get_Char_Index(impl_->face, cp) == 0)
                missing.push_back(cp);
    return missing;
}

double Font::digit_height(double size) {
    return measure(std::vector<TextRun>{{"0", 0.0, 1.0}}, size).ascent;
}

namespace {

/// Blends one coverage value of \p color into the pixel at (x, y), if inside the image.
void blend(Image& image, int x, int y, unsigned coverage, const std::array<std::uint8_t, 3>& rgb) {
    if (coverage == 0 || x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    std::uint8_t* p = &image.rgb[(static_cast<std::size_t>(y) * image.width + x) * 3];
    for (int c = 0; c < 3; ++c)
        p[c] = static_cast<std::uint8_t>((p[c] * (255 - coverage) + rgb[c] * coverage + 127) / 255);
}

}  // namespace

void Font::draw(Image& image, const std::vector<TextRun>& runs, double size, double x, double y,
                HAlign halign, VAlign valign, const Color& color, bool vertical) {
    const Layout text = layout(runs, size);
    if (text.glyphs.empty()) return;

    // The anchor in the text's own frame: u along the text from the origin, v up from the
    // baseline.
    const double u = halign == HAlign::left     ? 0.0
                     : halign == HAlign::center ? text.metrics.width / 2
                                                : text.metrics.width;
    double v = 0.0;
    switch (valign) {
        case VAlign::top:
            v = text.metrics.ascent;
            break;
        case VAlign::baseline:
            v = 0.0;
            break;
        case VAlign::digits_middle:
            v = digit_height(size) / 2;
            break;
        case VAlign::bottom:
            v = -text.metrics.descent;
            break;
    }
    // The text origin (pen start on the baseline) in image pixels, on the integer grid so that
    // hinted glyphs stay crisp.
    const int ox = static_cast<int>(std::lround(vertical ? x + v : x - u));
    const int oy = static_cast<int>(std::lround(vertical ? y + u : y + v));

    const auto rgb = to_rgb8(color);
    for (const Placed& p : text.glyphs) {
        const GlyphBitmap& g = *p.glyph;
        for (int r = 0; r < g.rows; ++r) {
            for (int c = 0; c < g.width; ++c) {
                const unsigned a = g.coverage[static_cast<std::size_t>(r) * g.width + c];
                // Text-frame pixel: right of the origin by tu, above the baseline by tv.
                const int tu = p.x + g.left + c;
                const int tv = p.baseline + g.top - r;
                if (vertical)
                    blend(image, ox - tv, oy - tu - 1, a, rgb);
                else
                    blend(image, ox + tu, oy - tv, a, rgb);
            }
        }
    }
}

}  // namespace plot::detail
