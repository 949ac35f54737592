/// \file
/// \brief plot_demo: writes the figure engine's demonstration figure.
///
/// Usage: `plot_demo OUTPUT.png`
#include "plot/demo_figure.hpp"
#include "plot/error.hpp"

#include <chrono>
#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTPUT.png\n", argv[0]);
        return 2;
    }
    try {
        const auto start = std::chrono::steady_clock::now();
        plot::Figure fig = plot::demo::make_figure();
        fig.save_png(argv[1]);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("wrote %s (%d×%d px) in %.2f s\n", argv[1], fig.width(), fig.height(), seconds);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
