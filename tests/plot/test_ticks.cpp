// Tick placement and labels, and the colour maps.
#include "plot/color.hpp"
#include "plot/ticks.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

using plot::Scale;

namespace {

std::vector<std::string> labels(const plot::TickSet& set) {
    std::vector<std::string> out;
    for (const auto& t : set.ticks)
        if (t.major && !t.label.empty()) out.push_back(t.label);
    return out;
}

std::size_t count_minor(const plot::TickSet& set) {
    std::size_t n = 0;
    for (const auto& t : set.ticks) n += !t.major;
    return n;
}

}  // namespace

TEST_CASE("ticks: linear axes take nice 1-2-5 steps with 4 to 8 labels", "[plot][ticks]") {
    CHECK(labels(plot::make_ticks(Scale::linear, 0, 1, 8)) ==
          std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"});
    CHECK(labels(plot::make_ticks(Scale::linear, -0.5, 0.5, 8)) ==
          std::vector<std::string>{"−0.4", "−0.2", "0.0", "0.2", "0.4"});
    CHECK(labels(plot::make_ticks(Scale::linear, 0, 8, 8)) ==
          std::vector<std::string>{"0", "2", "4", "6", "8"});
    CHECK(labels(plot::make_ticks(Scale::linear, 0, 3, 8)) ==
          std::vector<std::string>{"0.0", "0.5", "1.0", "1.5", "2.0", "2.5", "3.0"});
    // Fewer labels when fewer are asked for (the axes ask for fewer when labels would touch).
    CHECK(labels(plot::make_ticks(Scale::linear, 0, 1, 3)).size() == 3);
    for (double hi : {0.7, 1.3, 7.0, 42.0, 999.0, 1e4}) {
        INFO("range 0.." << hi);
        const auto n = labels(plot::make_ticks(Scale::linear, 0, hi, 8)).size();
        CHECK(n >= 4);
        CHECK(n <= 8);
    }
}

TEST_CASE("ticks: no -0 and no round-off noise in labels", "[plot][ticks]") {
    const auto set = plot::make_ticks(Scale::linear, -0.3, 0.3, 8);
    for (const auto& l : labels(set)) {
        CHECK(l.size() <= 6);
        CHECK(l != "−0.0");
    }
    CHECK(plot::format_number(-0.0001, 2) == "0.00");
    CHECK(plot::format_number(-1.5, 1) == "−1.5");
}

TEST_CASE("ticks: linear minor ticks divide the step", "[plot][ticks]") {
    // Step 0.2: four minor divisions; 0..1 has 5 intervals × 3 minor ticks = 15.
    CHECK(count_minor(plot::make_ticks(Scale::linear, 0, 1, 8)) == 15);
}

TEST_CASE("ticks: very large or small values share an exponent", "[plot][ticks]") {
    const auto big = plot::make_ticks(Scale::linear, 0, 3e5, 8);
    CHECK(big.multiplier == "×10^{5}");
    CHECK(labels(big).front() == "0.0");
    CHECK(labels(big).back() == "3.0");
    const auto small = plot::make_ticks(Scale::linear, 0, 2e-4, 8);
    CHECK(small.multiplier == "×10^{-4}");
    CHECK(plot::make_ticks(Scale::linear, 0, 100, 8).multiplier.empty());
}

TEST_CASE("ticks: log axes label decades, minor ticks at 2..9", "[plot][ticks]") {
    const auto set = plot::make_ticks(Scale::log, 1e-3, 1e2, 8);
    CHECK(labels(set) ==
          std::vector<std::string>{"10^{-3}", "10^{-2}", "10^{-1}", "10^{0}", "10^{1}", "10^{2}"});
    CHECK(count_minor(set) == 5 * 8);
    for (const auto& t : set.ticks) {
        if (!t.major) continue;
        const double decade = std::log10(t.value);
        CHECK(decade == Approx(std::round(decade)).margin(1e-12));
    }
}

TEST_CASE("ticks: many decades label every k-th decade", "[plot][ticks]") {
    const auto set = plot::make_ticks(Scale::log, 1e-30, 1e30, 8);
    const auto l = labels(set);
    CHECK(l.size() <= 8);
    CHECK(l.size() >= 4);
    CHECK(std::find(l.begin(), l.end(), "10^{0}") != l.end());
    CHECK(count_minor(set) == 0);  // 60 decades: no 2..9 ticks
}

TEST_CASE("ticks: log axes under two decades label intermediate values", "[plot][ticks]") {
    CHECK(labels(plot::make_ticks(Scale::log, 0.2, 70, 8)) ==
          std::vector<std::string>{"0.2", "0.5", "1", "2", "5", "10", "20", "50"});
    CHECK(labels(plot::make_ticks(Scale::log, 2, 8, 8)) ==
          std::vector<std::string>{"2", "3", "4", "5", "6", "7", "8"});
    CHECK(labels(plot::make_ticks(Scale::log, 2e-6, 9e-5, 8)) ==
          std::vector<std::string>{"2×10^{-6}", "5×10^{-6}", "10^{-5}", "2×10^{-5}", "5×10^{-5}"});
    // Within one mantissa step: nice linear values.
    const auto narrow = labels(plot::make_ticks(Scale::log, 2.1, 2.9, 8));
    CHECK(narrow.size() >= 3);
    CHECK(narrow.front() == "2.2");
    // Mantissas that would crowd into one end of the axis (0.08, 0.09, 0.1 on an axis to 0.175)
    // give way to linear values that spread over it.
    const auto set = plot::make_ticks(Scale::log, 0.078, 0.175, 8);
    std::vector<double> at;
    for (const auto& t : set.ticks)
        if (!t.label.empty()) at.push_back(t.value);
    REQUIRE(at.size() >= 3);
    INFO("labels " << at.front() << " to " << at.back());
    CHECK(std::log(at.back() / at.front()) >= 0.5 * std::log(0.175 / 0.078));
}

TEST_CASE("colour maps: viridis table and SPLASH red", "[plot][colormap]") {
    using plot::Colormap;
    using plot::map_color;
    // matplotlib's viridis: entries 0, 128 and 255.
    CHECK(map_color(Colormap::viridis, 0.0).r == Approx(0.267004).margin(1e-6));
    CHECK(map_color(Colormap::viridis, 0.0).b == Approx(0.329415).margin(1e-6));
    CHECK(map_color(Colormap::viridis, 128.0 / 255.0).g == Approx(0.566949).margin(1e-6));
    CHECK(map_color(Colormap::viridis, 1.0).r == Approx(0.993248).margin(1e-6));
    CHECK(map_color(Colormap::viridis, 1.0).g == Approx(0.906157).margin(1e-6));
    // Perceptually ordered: viridis gets lighter all the way (luma rises monotonically).
    double previous = -1.0;
    for (int i = 0; i <= 100; ++i) {
        const auto c = map_color(Colormap::viridis, i / 100.0);
        const double luma = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
        CHECK(luma > previous);
        previous = luma;
    }
    // SPLASH red: black -> red -> yellow -> white through its control points.
    CHECK(map_color(Colormap::red, 0.0) == plot::Color{0, 0, 0});
    CHECK(map_color(Colormap::red, 1.0) == plot::Color{1, 1, 1});
    const auto mid = map_color(Colormap::red, 0.475);
    CHECK(mid.r == Approx(0.686));
    CHECK(mid.g == Approx(0.004));
    CHECK(map_color(Colormap::red, 0.745).g == Approx(0.518));
    // Clamped outside [0, 1]; NaN goes to the low end.
    CHECK(map_color(Colormap::viridis, -3.0) == map_color(Colormap::viridis, 0.0));
    CHECK(map_color(Colormap::viridis, 7.0) == map_color(Colormap::viridis, 1.0));
    CHECK(map_color(Colormap::red, std::nan("")) == plot::Color{0, 0, 0});
    CHECK(plot::to_rgb8({1.0, 0.5, 0.0}) == std::array<std::uint8_t, 3>{255, 128, 0});
}
