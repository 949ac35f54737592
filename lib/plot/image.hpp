/// \file
/// \brief An 8-bit RGB image in memory, and writing it as PNG.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace plot {

/// An 8-bit sRGB image, rows top to bottom, pixels left to right, three bytes each.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;  ///< width * height * 3 bytes

    Image() = default;
    /// A \p width × \p height image filled with \p fill.
    Image(int width, int height, std::array<std::uint8_t, 3> fill = {255, 255, 255});

    /// The pixel at column \p x, row \p y (row 0 at the top).
    std::array<std::uint8_t, 3> at(int x, int y) const;
};

/// Writes \p image to \p path as an 8-bit RGB PNG.
///
/// The bytes depend on the pixels only (no time stamp, no text chunks), so equal images give
/// equal files.  The file is first written to a temporary name in the same directory and
/// renamed into place when complete: a failure never leaves a partial PNG at \p path.
/// Throws plot::Error naming the path and the reason (missing directory, permission, disk).
void write_png(const Image& image, const std::string& path);

/// Checks that \p path could be written (its directory exists and is writable) and throws
/// plot::Error naming the problem if not.  Used before an expensive render.
void check_writable(const std::string& path);

}  // namespace plot
