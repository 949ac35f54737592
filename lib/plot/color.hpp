/// \file
/// \brief Colours and colour maps.
///
/// Colours are sRGB triples in [0, 1].  Two colour maps are built in: matplotlib's perceptually
/// uniform \e viridis (the published 256-entry table) and SPLASH's default "red" heat map
/// (black -> red -> yellow -> white, IDL's red-temperature table as used by SPLASH's
/// colour scheme 2), plus a plain greyscale.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace plot {

/// An sRGB colour with components in [0, 1].
struct Color {
    double r = 0.0;
    double g = 0.0;
    double b = 0.0;
    friend bool operator==(const Color&, const Color&) = default;
};

/// \name Named colours
/// A small palette that prints well in journals (and stays distinguishable in greyscale where
/// it can).
/// \{
inline constexpr Color black{0.0, 0.0, 0.0};
inline constexpr Color white{1.0, 1.0, 1.0};
inline constexpr Color grey{0.5, 0.5, 0.5};
inline constexpr Color red{0.84, 0.10, 0.11};
inline constexpr Color blue{0.12, 0.30, 0.75};
inline constexpr Color green{0.10, 0.55, 0.20};
inline constexpr Color orange{0.95, 0.55, 0.05};
inline constexpr Color purple{0.50, 0.20, 0.60};
inline constexpr Color cyan{0.05, 0.65, 0.75};
/// \}

/// The colour given to the i-th series of a panel that names no colour of its own:
/// black, red, blue, green, orange, purple, cyan, grey, then round again.
Color cycle_color(std::size_t i);

/// The built-in colour maps.
enum class Colormap {
    viridis,  ///< matplotlib's perceptually uniform map, dark blue -> green -> yellow
    red,      ///< SPLASH's default rendering map: black -> red -> yellow -> white
    grey,     ///< black -> white
};

/// The colour of map \p map at \p t in [0, 1] (t is clamped; NaN gives the map's low end).
/// Viridis is interpolated linearly between its 256 tabulated entries; "red" between its five
/// control points (luminance 0, 0.475, 0.694, 0.745, 1).
Color map_color(Colormap map, double t);

/// The map's name as the user would write it ("viridis", "red", "grey").
std::string_view colormap_name(Colormap map);

/// 8-bit RGB of a colour, rounded to nearest.
std::array<std::uint8_t, 3> to_rgb8(const Color& c);

}  // namespace plot
