// Rendering: image size, where markers, lines and log ticks land, determinism, speed, and the
// demonstration figure.
#include "plot/demo_figure.hpp"
#include "plot/figure.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

namespace {

using Rgb = std::array<std::uint8_t, 3>;

const std::string output_dir = SPH_TEST_OUTPUT_DIR;

std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool near(const Rgb& a, const Rgb& b, int tolerance = 2) {
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(a[c]) - int(b[c])) > tolerance) return false;
    return true;
}

/// The centroid of all pixels within \p rect of exactly \p colour.
plot::Point centroid_of(const plot::Image& image, const Rgb& colour, const plot::Rect& rect) {
    double sx = 0, sy = 0, n = 0;
    for (int y = int(rect.y0); y < int(rect.y1); ++y)
        for (int x = int(rect.x0); x < int(rect.x1); ++x)
            if (image.at(x, y) == colour) {
                sx += x + 0.5;
                sy += y + 0.5;
                n += 1;
            }
    return {n > 0 ? sx / n : -1, n > 0 ? sy / n : -1};
}

const Rgb white{255, 255, 255};

}  // namespace

TEST_CASE("render: the image has the requested size", "[plot][render]") {
    plot::Figure fig(2, 3, {.width = 900, .height = 500});
    for (int i = 0; i < 6; ++i)
        fig.panel(i).line(std::vector<double>{0, 1}, std::vector<double>{0, double(i)});
    const plot::Image image = fig.render();
    CHECK(image.width == 900);
    CHECK(image.height == 500);
    CHECK(image.rgb.size() == 900u * 500u * 3u);
    // Default size: 800 × 600 a panel.
    plot::Figure defaults(1, 2);
    CHECK(defaults.width() == 1600);
    CHECK(defaults.height() == 600);
}

TEST_CASE("render: a marker lands on its data coordinates", "[plot][render]") {
    plot::Figure fig(1, 1, {.width = 400, .height = 300, .panel_letters = false});
    plot::Axes& ax = fig.panel(0, 0);
    ax.xlim(0, 10).ylim(0, 10);
    const std::vector<double> x{2.5}, y{7.5};
    ax.scatter(x, y, {.color = plot::red, .size = 12.0});
    const plot::Image image = fig.render();

    // to_pixel is the linear map onto the frame.
    const plot::Rect f = ax.frame();
    const plot::Point p = ax.to_pixel(2.5, 7.5);
    CHECK(p.x == Approx(f.x0 + 0.25 * f.width()));
    CHECK(p.y == Approx(f.y1 - 0.75 * f.height()));

    // The marker is there: solid red at its centre, its centroid on the point, white beyond.
    const Rgb red = plot::to_rgb8(plot::red);
    CHECK(image.at(int(p.x), int(p.y)) == red);
    CHECK(image.at(int(p.x + 4), int(p.y)) == red);
    CHECK(image.at(int(p.x), int(p.y - 4)) == red);
    CHECK(image.at(int(p.x + 9), int(p.y)) == white);
    CHECK(image.at(int(p.x), int(p.y + 9)) == white);
    const plot::Point c = centroid_of(image, red, {p.x - 10, p.y - 10, p.x + 10, p.y + 10});
    CHECK(c.x == Approx(p.x).margin(0.5));
    CHECK(c.y == Approx(p.y).margin(0.5));
}

TEST_CASE("render: lines land on their data coordinates", "[plot][render]") {
    plot::Figure fig(1, 1, {.width = 400, .height = 300, .panel_letters = false});
    plot::Axes& ax = fig.panel(0, 0);
    ax.xlim(0, 10).ylim(0, 10);
    ax.line(std::vector<double>{0, 10}, std::vector<double>{3, 3},
            {.color = plot::blue, .width = 3.0});
    ax.line(std::vector<double>{0, 10}, std::vector<double>{0, 10},
            {.color = plot::green, .width = 3.0});
    ax.vline(7, {.color = plot::red, .width = 3.0});
    const plot::Image image = fig.render();
    const Rgb blue = plot::to_rgb8(plot::blue), green = plot::to_rgb8(plot::green),
              red = plot::to_rgb8(plot::red);

    // Horizontal line y = 3: its centroid in a column is on y = 3.
    const plot::Point h = ax.to_pixel(5, 3);
    CHECK(image.at(int(h.x), int(h.y)) == blue);
    CHECK(image.at(int(h.x), int(h.y) - 4) == white);
    CHECK(image.at(int(h.x), int(h.y) + 4) == white);
    CHECK(centroid_of(image, blue, {h.x, h.y - 6, h.x + 1, h.y + 6}).y == Approx(h.y).margin(0.5));
    // The diagonal passes through (2, 2).
    const plot::Point d = ax.to_pixel(2, 2);
    CHECK(image.at(int(d.x), int(d.y)) == green);
    // The vertical reference line at x = 7.
    const plot::Point v = ax.to_pixel(7, 8);
    CHECK(std::abs(centroid_of(image, red, {v.x - 6, v.y, v.x + 6, v.y + 1}).x - v.x) <= 0.5);
}

TEST_CASE("render: a log axis puts its decade ticks where they belong", "[plot][render]") {
    plot::Figure fig(1, 1, {.width = 600, .height = 400, .panel_letters = false});
    plot::Axes& ax = fig.panel(0, 0);
    ax.xscale(plot::Scale::log).xlim(1e-3, 1e2).ylim(0, 1);
    ax.line(std::vector<double>{1e-3, 1e2}, std::vector<double>{0.5, 0.5});
    const plot::Image image = fig.render();
    const plot::Rect f = ax.frame();

    int decades = 0;
    for (const plot::Tick& t : ax.xticks().ticks) {
        if (!t.major) continue;
        const int k = int(std::lround(std::log10(t.value)));
        CHECK(t.label == "10^{" + std::to_string(k) + "}");
        // Decade k sits at (k + 3) / 5 of the frame width.
        const double expected = f.x0 + (k + 3) / 5.0 * f.width();
        CHECK(ax.to_pixel(t.value, 0.5).x == Approx(expected).margin(1e-9));
        // The tick mark is drawn there, inside the bottom frame line: dark pixels in its column.
        const int y = int(f.y1) - 3;
        const int column = int(std::floor(expected));
        CHECK(image.at(column, y)[0] < 80);
        ++decades;
    }
    CHECK(decades == 6);
    // Between 10^0 and 2×10^0 (at 1.5) there is no tick.
    const double between = ax.to_pixel(1.5, 0.5).x;
    CHECK(image.at(int(between), int(f.y1) - 3) == white);
    // A minor tick at 2 × 10^0, shorter than the major ones.
    const int minor = int(std::floor(ax.to_pixel(2.0, 0.5).x));
    CHECK(image.at(minor, int(f.y1) - 3)[0] < 80);
    CHECK(image.at(minor, int(f.y1) - 6) == white);
}

TEST_CASE("render: NaN points are skipped and counted, lines break at them", "[plot][render]") {
    plot::Figure fig(1, 1, {.width = 400, .height = 300});
    plot::Axes& ax = fig.panel(0, 0);
    const double nan = std::nan("");
    ax.scatter(std::vector<double>{1, 2, nan, 4}, std::vector<double>{1, nan, 3, 4});
    ax.line(std::vector<double>{0, 1, 2, 3, 4}, std::vector<double>{0, 1, nan, 3, 4});
    CHECK(ax.skipped_points() == 3);
    CHECK_NOTHROW(fig.render());
    // Non-positive values on a log axis are skipped and counted at render time.
    plot::Figure logfig(1, 1, {.width = 400, .height = 300});
    plot::Axes& lx = logfig.panel(0, 0);
    lx.yscale(plot::Scale::log)
        .scatter(std::vector<double>{1, 2, 3}, std::vector<double>{-1, 0, 5});
    logfig.render();
    CHECK(lx.skipped_points() == 2);
    CHECK(lx.yrange().first > 0);
}

TEST_CASE("render: limits come from the data unless given", "[plot][render]") {
    plot::Figure fig(1, 2, {.width = 800, .height = 300});
    plot::Axes& a = fig.panel(0);
    a.scatter(std::vector<double>{0, 10}, std::vector<double>{-1, 1});
    plot::Axes& b = fig.panel(1);
    b.scatter(std::vector<double>{0, 10}, std::vector<double>{-1, 1}).xlim(2, 3);
    fig.render();
    CHECK(a.xrange().first < 0);  // padded by a few per cent
    CHECK(a.xrange().second > 10);
    CHECK(a.xrange().second < 11);
    CHECK(b.xrange() == std::pair{2.0, 3.0});
}

TEST_CASE("render: the same figure gives the same bytes", "[plot][render][determinism]") {
    auto make = [] {
        plot::Figure fig = plot::demo::make_figure(1200, 400);
        return fig;
    };
    plot::Figure first = make();
    const std::string a = output_dir + "/determinism_a.png", b = output_dir + "/determinism_b.png";
    first.save_png(a);
    plot::Figure second = make();
    second.save_png(b);
    const std::string bytes_a = read_bytes(a), bytes_b = read_bytes(b);
    CHECK(bytes_a.size() > 1000);
    CHECK(bytes_a == bytes_b);
    // Rendering the same object again changes nothing either.
    CHECK(first.render().rgb == second.render().rgb);
}

TEST_CASE("render: a million-point scatter stays fast", "[plot][render][speed]") {
    const std::size_t n = 1'000'000;
    plot::demo::Noise noise(42);
    std::vector<double> x(n), y(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double r = std::sqrt(noise.uniform()), phi = 2 * std::numbers::pi * noise.uniform();
        x[i] = r * std::cos(phi) + 0.05 * noise.normal();
        y[i] = r * std::sin(phi) * 0.6 + 0.05 * noise.normal();
    }
    const auto start = std::chrono::steady_clock::now();
    plot::Figure fig(1, 1, {.width = 1600, .height = 1200});
    fig.title("10^{6} particles");
    plot::Axes& ax = fig.panel(0, 0);
    ax.xlabel("x").ylabel("y").equal_aspect();
    ax.scatter(x, y, {.label = "particles", .color = plot::black, .size = 1.5, .alpha = 0.3});
    ax.legend();
    const std::string path = output_dir + "/scatter_1e6.png";
    fig.save_png(path);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("plot: 10^6-point scatter, 1600×1200 px, render + PNG: %.2f s\n", seconds);
    // About 1 s on an idle 2-core machine.  Not a speed test (speed is measured by a benchmark,
    // not by a test on a shared machine): the bound only catches a per-point cost gone quadratic.
    CHECK(seconds < 30.0);
    CHECK(std::filesystem::file_size(path) > 10000);
}

TEST_CASE("render: colour-mapped scatter and the SPLASH red map with a log colour bar",
          "[plot][render]") {
    plot::Figure fig(1, 2, {.width = 1400, .height = 560});
    std::vector<double> x, y, rho;
    plot::demo::Noise noise(7);
    for (int i = 0; i < 20000; ++i) {
        x.push_back(noise.normal());
        y.push_back(noise.normal());
        rho.push_back(std::exp(-(x.back() * x.back() + y.back() * y.back())) * 100 + 0.1);
    }
    plot::Axes& a = fig.panel(0);
    a.xlabel("x").ylabel("y").equal_aspect().xlim(-3, 3).ylim(-3, 3);
    a.scatter(x, y, rho,
              {.map = plot::Colormap::red, .log = true, .colorbar_label = "\\rho", .size = 2.5});
    Eigen::ArrayXXd grid(64, 48);
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 48; ++j)
            grid(i, j) = (i == 10 && j == 10) ? std::nan("") : std::pow(10.0, 0.05 * (i + j) - 2);
    plot::Axes& b = fig.panel(1);
    b.xlabel("x").ylabel("y");
    b.image(grid, {0, 4, 0, 3},
            {.map = plot::Colormap::red,
             .log = true,
             .colorbar_label = "|\\nabla\\times\\nabla\\times v|"});
    fig.save_png(output_dir + "/colour_maps.png");
    CHECK(b.skipped_points() == 1);
    // The image covers its extent: its lowest-left cell has the map's colour for 10^-2.
    const plot::Point p = b.to_pixel(0.02, 0.02);
    const plot::Image image = fig.render();
    CHECK(near(image.at(int(p.x) + 1, int(p.y) - 1),
               plot::to_rgb8(plot::map_color(plot::Colormap::red, 0.0)), 40));
}

TEST_CASE("render: the demonstration figure", "[plot][render][demo]") {
    plot::Figure fig = plot::demo::make_figure();
    const std::string path = output_dir + "/plot_demo.png";
    fig.save_png(path);
    CHECK(std::filesystem::file_size(path) > 10000);
    CHECK(fig.panel(0).skipped_points() == 0);
    std::printf("plot: demonstration figure written to %s\n", path.c_str());
}

TEST_CASE("stamp: the usual line from its parts", "[plot][stamp]") {
    CHECK(plot::format_stamp({.scheme = "Monaghan-Gingold AV",
                              .kernel = "M4",
                              .neighbours = 5,
                              .particles = 450,
                              .run_time = 0.12}) ==
          "Monaghan-Gingold AV, M4 kernel, N_{ngb} = 5, N = 450, 0.12 s");
    CHECK(plot::format_stamp({.kernel = "M4", .run_time = 1234.4}) == "M4 kernel, 1234 s");
    CHECK(plot::format_stamp({}).empty());
}

TEST_CASE("render: hidden and empty panels", "[plot][render]") {
    plot::Figure fig(2, 2, {.width = 800, .height = 600});
    fig.panel(0).line(std::vector<double>{0, 1}, std::vector<double>{0, 1});
    fig.panel(3).hide();  // panels 1 and 2 stay empty: a frame with default limits
    const plot::Image image = fig.render();
    CHECK(fig.panel(1).xrange() == std::pair{0.0, 1.0});
    // Nothing at all in the hidden cell.
    bool blank = true;
    for (int y = 310; y < 600; ++y)
        for (int x = 410; x < 800; ++x)
            blank = blank && image.at(x, y) == std::array<std::uint8_t, 3>{255, 255, 255};
    CHECK(blank);
}

TEST_CASE("render: a legend asked to make room sits above curves that fill every corner",
          "[plot][render][legend]") {
    // Two diagonals: each corner of the frame holds a curve's end, so no corner is free.
    std::vector<double> x, up, down;
    for (int i = 0; i <= 200; ++i) {
        x.push_back(i / 200.0);
        up.push_back(x.back());
        down.push_back(1.0 - x.back());
    }
    auto hidden_points = [&](bool make_room, double& y_top) {
        plot::Figure fig(1, 1, {.width = 800, .height = 600});
        plot::Axes& ax = fig.panel(0, 0);
        ax.xlabel("x").ylabel("y");
        ax.line(x, up, {.label = "rising curve, labelled at length"});
        ax.line(x, down, {.label = "falling curve"});
        ax.legend(plot::Corner::best, make_room);
        fig.save_png(output_dir + (make_room ? "/legend_room.png" : "/legend_no_room.png"));
        const plot::Rect box = ax.legend_box();
        int hidden = 0;
        for (std::size_t i = 0; i < x.size(); ++i)
            hidden +=
                box.contains(ax.to_pixel(x[i], up[i])) + box.contains(ax.to_pixel(x[i], down[i]));
        y_top = ax.yrange().second;
        return hidden;
    };
    double top_without = 0, top_with = 0;
    const int without = hidden_points(false, top_without);
    const int with = hidden_points(true, top_with);
    std::printf("plot: legend over data points: %d without room, %d with (y limit %.3f -> %.3f)\n",
                without, with, top_without, top_with);
    CHECK(without > 0);             // the case is the one it is meant to be
    CHECK(with == 0);               // the legend hides nothing
    CHECK(top_with > top_without);  // by a taller y axis, not by moving data
}
