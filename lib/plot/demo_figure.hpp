/// \file
/// \brief The demonstration figure of the figure engine, shared by the `plot_demo` program
/// and the tests: three panels showing what a paper figure needs.
///
///  - (a) a noisy sampled function as a particle scatter, the exact function as a reference
///        line, a legend;
///  - (b) error against run time on log-log axes for two methods, markers on lines, and a
///        dotted reference slope;
///  - (c) a colour-mapped 2D field with a colour bar.
#pragma once

#include "plot/figure.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace plot::demo {

/// A small deterministic generator (the same numbers on every platform): xorshift64* and
/// Box-Muller.
class Noise {
  public:
    explicit Noise(std::uint64_t seed) : state_(seed | 1) {}
    double uniform() {
        state_ ^= state_ >> 12;
        state_ ^= state_ << 25;
        state_ ^= state_ >> 27;
        return static_cast<double>((state_ * 2685821657736338717ULL) >> 11) * 0x1.0p-53;
    }
    double normal() {
        const double u = 1.0 - uniform(), v = uniform();
        return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * v);
    }

  private:
    std::uint64_t state_;
};

/// The function sampled in panel (a): a damped wave.
inline double damped_wave(double x) { return std::exp(-0.25 * x) * std::sin(2.0 * x) + 1.2; }

/// The three-panel demonstration figure at \p width × \p height pixels.
inline Figure make_figure(int width = 2100, int height = 640) {
    Figure fig(1, 3, {.width = width, .height = height});
    fig.title("Figure engine demonstration");
    fig.stamp({.scheme = "demo data",
               .kernel = "M4",
               .neighbours = 5,
               .particles = 400,
               .run_time = 0.12});

    // (a) A particle scatter of a noisy sampled function, with the exact curve.
    {
        Noise noise(1997);
        std::vector<double> x, y, xe, ye;
        for (int i = 0; i < 400; ++i) {
            x.push_back(8.0 * noise.uniform());
            y.push_back(damped_wave(x.back()) + 0.06 * noise.normal());
        }
        for (int i = 0; i <= 400; ++i) {
            xe.push_back(8.0 * i / 400.0);
            ye.push_back(damped_wave(xe.back()));
        }
        Axes& a = fig.panel(0);
        a.xlabel("x [length]").ylabel("\\rho [mass length^{-3}]").xlim(0, 8);
        a.scatter(x, y, {.label = "SPH particles", .color = black, .size = 3.0});
        a.line(xe, ye, {.label = "exact", .color = red, .style = Dash::dashed, .width = 1.6});
        a.hline(1.2, {.color = grey, .style = Dash::dotted, .width = 1.2});
        a.legend(Corner::upper_right);
    }

    // (b) Error against run time, log-log, two methods and a reference slope.
    {
        std::vector<double> t1, e1, t2, e2, tr, er;
        for (int k = 0; k < 6; ++k) {
            const double n = 50.0 * std::pow(2.0, k);  // particles
            t1.push_back(2e-3 * std::pow(n, 1.3));
            e1.push_back(0.8 * std::pow(n, -0.9) * (1 + 0.08 * std::sin(3.0 * k)));
            t2.push_back(3e-3 * std::pow(n, 1.35));
            e2.push_back(0.5 * std::pow(n, -1.3) * (1 + 0.1 * std::cos(2.0 * k)));
        }
        for (double t : {0.3, 30.0}) {
            tr.push_back(t);
            er.push_back(2e-3 * std::pow(t, -1.0));
        }
        Axes& b = fig.panel(1);
        b.xscale(Scale::log).yscale(Scale::log).xlabel("t_{run} [s]").ylabel("L_1 error in \\rho");
        b.line(t1, e1,
               {.label = "Monaghan & Gingold AV",
                .color = blue,
                .width = 1.5,
                .marker = Marker::circle});
        b.line(t2, e2,
               {.label = "Selhammar (1997)",
                .color = red,
                .style = Dash::dashed,
                .width = 1.5,
                .marker = Marker::square,
                .marker_filled = false});
        b.line(
            tr, er,
            {.label = "\\propto t_{run}^{-1}", .color = grey, .style = Dash::dotted, .width = 1.3});
        b.legend(Corner::upper_right);
    }

    // (c) A colour-mapped field on a grid: two Gaussian blobs and a wave.
    {
        const int nx = 160, ny = 160;
        Eigen::ArrayXXd rho(nx, ny);
        for (int i = 0; i < nx; ++i) {
            for (int j = 0; j < ny; ++j) {
                const double x = -1 + 2 * (i + 0.5) / nx, y = -1 + 2 * (j + 0.5) / ny;
                rho(i, j) =
                    0.2 + std::exp(-((x - 0.35) * (x - 0.35) + (y - 0.2) * (y - 0.2)) / 0.05) +
                    0.6 * std::exp(-((x + 0.4) * (x + 0.4) + (y + 0.35) * (y + 0.35)) / 0.02) +
                    0.1 * std::sin(6 * x) * std::cos(4 * y);
            }
        }
        Axes& c = fig.panel(2);
        c.xlabel("x [length]").ylabel("y [length]").equal_aspect();
        c.image(rho, {-1, 1, -1, 1},
                {.map = Colormap::viridis, .colorbar_label = "\\rho [mass length^{-2}]"});
        c.text(-0.9, 0.85, "t = 0.2", {.color = white});
    }
    return fig;
}

}  // namespace plot::demo
