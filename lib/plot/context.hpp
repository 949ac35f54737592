/// \file
/// \brief The off-screen GL canvas: an OSMesa context rendering supersampled, box-filtered
/// down to the final image (internal to the figure engine).
///
/// All coordinates given to the canvas are pixels of the \e final image (x right, y down); the
/// canvas scales them by the supersampling factor itself.  Everything is drawn with two small
/// GLSL programs (flat triangles and point-sprite markers) and a third for textured images.
#pragma once

#include "plot/color.hpp"
#include "plot/image.hpp"
#include "plot/style.hpp"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace plot::detail {

/// Largest supersampled buffer side OSMesa accepts.
inline constexpr int max_buffer_side = 16384;

/// An OSMesa context and its supersampled colour buffer: draws in pixels, reads back the
/// box-filtered image.
class Canvas {
  public:
    /// A \p width × \p height canvas rendered at \p supersample × that resolution.
    /// Throws plot::Error when the buffer is too large or no GL context can be made.
    Canvas(int width, int height, int supersample, const Color& background);
    ~Canvas();
    Canvas(const Canvas&) = delete;
    Canvas& operator=(const Canvas&) = delete;

    /// Restricts drawing to \p rect (final pixels) until unclip().
    void clip(const Rect& rect);
    void unclip();

    /// Filled triangles: \p xy holds x, y pairs, three vertices a triangle.
    void triangles(std::span<const float> xy, const Color& color, double alpha = 1.0);
    /// A filled axis-aligned rectangle.
    void rect(const Rect& r, const Color& color, double alpha = 1.0);
    /// Markers of diameter \p size pixels centred on the \p xy pairs, in one draw call.  With
    /// \p rgba (4 bytes a point) each marker has its own colour; \p outline > 0 draws open
    /// shapes with that line width (pixels); plus and cross are strokes of at least
    /// max(1, 0.15 size) pixels.
    void markers(std::span<const float> xy, double size, Marker shape, double outline,
                 const Color& color, double alpha = 1.0, std::span<const std::uint8_t> rgba = {});
    /// An RGBA8 texture of \p tex_width × \p tex_height texels (row 0 at the bottom) stretched
    /// over \p where, sampled nearest (cells stay sharp).
    void texture(std::span<const std::uint8_t> rgba, int tex_width, int tex_height,
                 const Rect& where);

    /// Finishes rendering and returns the box-filtered final image.
    Image resolve();

    int supersample() const { return supersample_; }

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    int width_, height_, supersample_;
};

}  // namespace plot::detail
