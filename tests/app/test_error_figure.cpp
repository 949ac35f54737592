// The error-against-time figure with quoted points: they are drawn where their times and errors
// put them, in their own colour, and a mismatch between their times and errors is an error.
#include "app/error_figure.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>

namespace {

sph::ErrorVsTime small_study() {
  sph::ErrorVsTime study("test study");
  study.add({"ours", 100, 0.01, 0.1, {{"L1(rho)", 1e-2}, {"L1(v)", 2e-2}}});
  study.add({"ours", 200, 0.005, 0.4, {{"L1(rho)", 5e-3}, {"L1(v)", 1e-2}}});
  return study;
}

// Pixels inside \p rect whose colour is within 40 of c in every channel.
int pixels_in(const plot::Image& image, const plot::Rect& rect, const plot::Color& c) {
  const auto want = plot::to_rgb8(c);
  int count = 0;
  for (int y = static_cast<int>(rect.y0); y <= static_cast<int>(rect.y1); ++y)
    for (int x = static_cast<int>(rect.x0); x <= static_cast<int>(rect.x1); ++x) {
      const auto got = image.at(x, y);
      bool near = true;
      for (int k = 0; k < 3; ++k) near = near && std::abs(int(got[k]) - int(want[k])) <= 40;
      count += near;
    }
  return count;
}

}  // namespace

TEST_CASE("error figure: quoted points are drawn at their times and errors", "[error_figure]") {
  app::ErrorFigureOptions options;
  options.quoted.push_back(
      {"theirs (quoted)", {0.2, 0.8}, {{"L1(rho)", {8e-3, 4e-3}}}, plot::purple});
  options.time_label = "time [s]";
  plot::Figure figure = app::error_figure(small_study(), options);
  const plot::Image image = figure.render();
  // Panel (a) is L1(rho): the quoted marker sits at (0.2, 8e-3); panel (b), L1(v), has none.
  const plot::Point at = figure.panel(0).to_pixel(0.2, 8e-3);
  CHECK(pixels_in(image, {at.x - 8, at.y - 8, at.x + 8, at.y + 8}, plot::purple) > 5);
  CHECK(pixels_in(image, figure.panel(1).frame(), plot::purple) == 0);
}

TEST_CASE("error figure: quoted times and errors must pair up", "[error_figure]") {
  app::ErrorFigureOptions options;
  options.quoted.push_back({"theirs", {0.2, 0.8}, {{"L1(rho)", {8e-3}}}, std::nullopt});
  CHECK_THROWS_WITH(app::error_figure(small_study(), options),
                    Catch::Contains("quoted points 'theirs'") && Catch::Contains("L1(rho)"));
}
