// Failure modes: every one throws plot::Error (a std::runtime_error) with a message that names
// the problem, and a failed save leaves no file behind.
#include "plot/context.hpp"
#include "plot/error.hpp"
#include "plot/figure.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

const std::string output_dir = SPH_TEST_OUTPUT_DIR;
const std::vector<double> some{1, 2, 3};

/// Names in \p dir starting with \p stem (the PNG and any temporary file beside it).
std::vector<std::string> files_like(const std::string& dir, const std::string& stem) {
    std::vector<std::string> found;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().filename().string().rfind(stem, 0) == 0)
            found.push_back(entry.path().string());
    return found;
}

}  // namespace

using Catch::Contains;

TEST_CASE("errors: plot::Error is a std::exception", "[plot][errors]") {
    try {
        plot::Figure fig(0, 1);
        FAIL("no exception");
    } catch (const std::exception& e) {
        CHECK(dynamic_cast<const plot::Error*>(&e) != nullptr);
        CHECK(std::string(e.what()).rfind("plot: ", 0) == 0);
    }
}

TEST_CASE("errors: no GL context for an impossible buffer", "[plot][errors]") {
    // OSMesa buffers are limited to 16384 pixels a side.
    CHECK_THROWS_WITH(plot::detail::Canvas(20000, 100, 1, plot::white),
                      Contains("OSMesa") && Contains("20000"));
    CHECK_NOTHROW(plot::detail::Canvas(100, 100, 2, plot::white));
}

TEST_CASE("errors: absurd figure sizes and layouts", "[plot][errors]") {
    CHECK_THROWS_WITH(plot::Figure(0, 1), Contains("0×1 panels"));
    CHECK_THROWS_WITH(plot::Figure(1, 40), Contains("1..16"));
    CHECK_THROWS_WITH(plot::Figure(1, 1, {.width = 100000, .height = 600}), Contains("100000×600"));
    CHECK_THROWS_WITH(plot::Figure(1, 1, {.width = 10, .height = 600}), Contains("64..10000"));
    CHECK_THROWS_WITH(plot::Figure(1, 1, {.width = 800, .height = 600, .font_size = 0}),
                      Contains("font size"));
    CHECK_THROWS_WITH(plot::Figure(1, 1, {.width = 800, .height = 600, .supersample = 9}),
                      Contains("supersampling"));
    plot::Figure fig(2, 2);
    CHECK_THROWS_WITH(fig.panel(2, 0), Contains("no panel (2, 0)"));
    CHECK_THROWS_WITH(fig.panel(7), Contains("no panel 7"));
    // Panels too small for their labels.
    plot::Figure tiny(8, 8, {.width = 200, .height = 200, .font_size = 20});
    tiny.panel(0).line(some, some);
    CHECK_THROWS_WITH(tiny.render(), Contains("too small"));
}

TEST_CASE("errors: unwritable output paths", "[plot][errors]") {
    plot::Figure fig(1, 1, {.width = 300, .height = 200});
    fig.panel(0).line(some, some);
    CHECK_THROWS_WITH(fig.save_png(""), Contains("empty"));
    CHECK_THROWS_WITH(fig.save_png("/nonexistent/dir/figure.png"),
                      Contains("/nonexistent/dir") && Contains("does not exist"));
    CHECK_THROWS_WITH(fig.save_png(output_dir), Contains("is a directory"));
    // A directory that refuses new files even to root.
    CHECK_THROWS_WITH(fig.save_png("/proc/plot_test.png"), Contains("/proc/plot_test.png"));
    CHECK_FALSE(std::filesystem::exists("/proc/plot_test.png"));
}

TEST_CASE("errors: a failed render leaves no PNG behind", "[plot][errors]") {
    const std::string stem = "failed_render";
    const std::string path = output_dir + "/" + stem + ".png";
    std::filesystem::remove(path);
    plot::Figure fig(1, 1, {.width = 300, .height = 200});
    fig.panel(0).yscale(plot::Scale::log).scatter(some, std::vector<double>{-1, -2, -3});
    CHECK_THROWS_WITH(fig.save_png(path), Contains("no positive y values"));
    CHECK(files_like(output_dir, stem).empty());
    // An old file at the path survives a failed save untouched.
    plot::Figure good(1, 1, {.width = 300, .height = 200});
    good.panel(0).line(some, some);
    good.save_png(path);
    const auto size = std::filesystem::file_size(path);
    CHECK_THROWS(fig.save_png(path));
    CHECK(std::filesystem::file_size(path) == size);
    CHECK(files_like(output_dir, stem).size() == 1);
}

TEST_CASE("errors: empty, mismatched and all-NaN data", "[plot][errors]") {
    plot::Figure fig(1, 1);
    plot::Axes& ax = fig.panel(0);
    const std::vector<double> none, nan3(3, std::nan(""));
    CHECK_THROWS_WITH(ax.scatter(none, none, {.label = "SPH"}),
                      Contains("scatter 'SPH'") && Contains("no data"));
    CHECK_THROWS_WITH(ax.line(some, std::vector<double>{1, 2}),
                      Contains("x has 3 values but y has 2"));
    CHECK_THROWS_WITH(ax.line(nan3, some, {.label = "exact"}),
                      Contains("'exact'") && Contains("all 3 points are NaN"));
    CHECK_THROWS_WITH(ax.image(std::vector<double>(4, std::nan("")), 2, 2, {}),
                      Contains("all 4 cells are NaN"));
    CHECK_THROWS_WITH(ax.image(some, 2, 2, {}), Contains("3 values for a 2×2 grid"));
    CHECK_THROWS_WITH(ax.image(std::vector<double>{}, 0, 0, {}), Contains("empty grid"));
    CHECK_THROWS_WITH(ax.hline(std::nan("")), Contains("non-finite"));
    CHECK_THROWS_WITH(ax.scatter(some, some, {.size = -1}), Contains("marker size"));
    CHECK_THROWS_WITH(ax.line(some, some, {.width = 500}), Contains("line width"));
    CHECK_THROWS_WITH(ax.xlim(1, 1), Contains("xlim"));
    CHECK_THROWS_WITH(ax.ylim(0, std::nan("")), Contains("ylim"));
    CHECK(ax.skipped_points() == 0);  // refused series are not counted
}

TEST_CASE("errors: bad markup fails where it is written", "[plot][errors]") {
    plot::Figure fig(1, 1);
    CHECK_THROWS_WITH(fig.panel(0).xlabel("\\rhoo"), Contains("unknown command \\rhoo"));
    CHECK_THROWS_WITH(fig.title("x^{2"), Contains("unclosed"));
    CHECK_THROWS_WITH(fig.panel(0).scatter(some, some, {.label = "\\bad"}), Contains("\\bad"));
}

TEST_CASE("errors: a missing font and queries before a render", "[plot][errors]") {
    plot::Figure fig(1, 1, {.width = 300, .height = 200, .font = "/nonexistent/font.ttf"});
    fig.panel(0).line(some, some);
    CHECK_THROWS_WITH(fig.render(), Contains("/nonexistent/font.ttf"));
    plot::Figure fresh(1, 1);
    CHECK_THROWS_WITH(fresh.panel(0).frame(), Contains("not been rendered"));
    CHECK_THROWS_WITH(fresh.panel(0).to_pixel(0, 0), Contains("not been rendered"));
}
