// The benchmark program: what one step of each kind costs on this machine, with 1 thread and
// with all threads.  Run it as `build/bench/bench` (or `--quick` for a smoke run).  The numbers
// go in the design page and the chapters' text; timed tests are not used for this, since test
// machines are shared and noisy.
#include "bench_derivatives.hpp"
#include "bench_evrard.hpp"
#include "bench_gravity.hpp"
#include "bench_hydro.hpp"
#if __has_include("bench_neighbours.hpp")
#include "bench_neighbours.hpp"
#define SPH_BENCH_NEIGHBOURS 1
#endif

#include <CLI/CLI.hpp>
#include <omp.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  CLI::App app{
      "SPH course benchmarks: neighbour search, hydrodynamic steps in 1D/2D/3D, self-gravity, the "
      "Evrard collapse, second derivatives"};
  bool quick = false;
  std::string only;
  app.add_flag("--quick", quick, "small sizes, a few seconds (for smoke tests)");
  app.add_option("--only", only,
                 "run one part: neighbours, hydro, viscosities (the end of hydro alone), gravity, "
                 "evrard or derivatives")
      ->check(CLI::IsMember(
          {"neighbours", "hydro", "viscosities", "gravity", "evrard", "derivatives"}));
  CLI11_PARSE(app, argc, argv);
  std::printf("SPH course benchmark: %d hardware threads\n", omp_get_num_procs());
#ifdef SPH_BENCH_NEIGHBOURS
  if (only.empty() || only == "neighbours") bench::bench_neighbours(quick);
#endif
  if (only.empty() || only == "hydro") bench::bench_hydro(quick);
  if (only == "viscosities") bench::bench_viscosities(quick);
  if (only.empty() || only == "gravity") bench::bench_gravity(quick);
  if (only.empty() || only == "evrard") bench::bench_evrard(quick);
  if (only.empty() || only == "derivatives") bench::bench_derivatives(quick);
  return 0;
}
