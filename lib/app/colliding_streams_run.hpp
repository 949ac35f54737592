#pragma once
/// \file
/// \brief app::run_colliding_streams: two cold streams run into each other, with the paths of a
/// sample of particles recorded for an x-t diagram, a step budget, and the count of particles
/// that have passed one another.
///
/// The colliding streams (sph::make_colliding_streams) are the test of particle penetration:
/// without enough viscosity the streams pass through each other, or pile up until the time
/// step collapses.  A run of them is therefore allowed to fail, and its failure is a result:
///
/// \code
/// template <int D>
/// struct Inviscid : sph::Scene<D> { using Terms = sph::Terms<sph::PressureHernquistKatz>; };
/// const auto run = app::run_colliding_streams<Inviscid<1>>(
///     "no viscosity", sph::CollidingStreamsSetup{}, sph::SmoothingLengthRule::from_density(4),
///     {}, {.t_end = 0.4, .max_steps = 20000});
/// if (!run.stopped.empty()) std::printf("stopped at t = %g: %s\n", run.t_reached,
///                                       run.stopped.c_str());
/// std::printf("%s\n", run.inversions.summary().c_str());
/// \endcode
///
/// The tracked particles are every k-th particle of the right-moving stream, counted from its
/// front (the particle nearest x = 0) backwards, each paired with its mirror image in the
/// left-moving stream, so that an x-t diagram of their paths is symmetric about x = 0.  The
/// step budget goes in as sph::Settings::max_steps; when a run exceeds it, or its time step
/// falls below the simulation's minimum, the simulation throws sph::Error.  The runner catches
/// it, records the positions where the run stopped, and keeps the message.  The order
/// inversions (sph::order_inversions) are counted at the end, against the initial positions.
///
/// Header-only, like the other shared pieces of lib/app that use lib/sph.

#include "app/stopwatch.hpp"
#include "sph/error.hpp"
#include "sph/measures/penetration.hpp"
#include "sph/setups/colliding_streams.hpp"
#include "sph/simulation.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace app {

/// How long the streams run, what is recorded, and the step budget.
struct StreamsRunOptions {
  double t_end = 0.4;           ///< the run stops at this time (or earlier, see StreamsRun)
  int outputs = 200;            ///< times, evenly spaced up to t_end, at which paths are sampled
  int paths = 24;               ///< particles tracked per stream
  long max_steps = 10'000'000;  ///< the step budget
};

/// What a chapter keeps of one run of the colliding streams.
template <int D>
struct StreamsRun {
  std::string name;
  sph::Particles<D> particles;             ///< where the run stopped
  std::vector<sph::Vec<D>> initial;        ///< the initial positions
  int left_count = 0;                      ///< particles 0 .. left_count-1 move right
  std::vector<std::size_t> tracked;        ///< the particles whose paths are kept
  std::vector<double> times;               ///< the output times reached
  std::vector<std::vector<double>> paths;  ///< paths[k][m]: x of tracked[k] at times[m]
  sph::OrderInversions inversions;         ///< pairs that have passed each other
  long steps = 0;
  double seconds = 0;    ///< wall time, set-up included
  double t_reached = 0;  ///< t_end, or the time at which the run stopped
  double last_dt = 0;    ///< the last time step
  std::string stopped;   ///< why the run stopped early, or empty
};

/// Runs the streams of \p setup with the scene \p Scene (its terms given by \p terms, an ideal
/// gas of the set-up's \f$ \gamma \f$, the smoothing-length rule \p smoothing) until
/// `options.t_end`, or until the simulation cannot go on, and returns what was recorded.
template <class Scene>
StreamsRun<Scene::D> run_colliding_streams(const std::string& name,
                                           const sph::CollidingStreamsSetup& setup,
                                           const sph::SmoothingLengthRule& smoothing,
                                           const typename Scene::Terms& terms,
                                           const StreamsRunOptions& options = {}) {
  constexpr int D = Scene::D;
  const Stopwatch clock;
  auto streams = sph::make_colliding_streams<D>(setup);
  StreamsRun<D> run;
  run.name = name;
  run.initial = streams.particles.position;
  run.left_count = streams.left_count;
  // Every k-th particle of each stream, in mirror-image pairs about x = 0.
  const int stride = std::max(1, streams.left_count / options.paths);
  for (int k = streams.left_count - 1; k >= 0; k -= stride) {
    run.tracked.push_back(static_cast<std::size_t>(k));
    run.tracked.push_back(static_cast<std::size_t>(2 * streams.left_count - 1 - k));
  }
  run.paths.resize(run.tracked.size());

  sph::Settings settings;
  settings.smoothing = smoothing;
  settings.max_steps = options.max_steps;
  sph::Simulation<Scene> sim(streams.particles, streams.box, sph::IdealGas(setup.gamma), terms,
                             settings);
  const auto record = [&] {
    run.times.push_back(sim.time());
    for (std::size_t k = 0; k < run.tracked.size(); ++k) {
      run.paths[k].push_back(sim.particles().position[run.tracked[k]][0]);
    }
  };
  record();
  try {
    for (int m = 1; m <= options.outputs; ++m) {
      sim.run_until(options.t_end * m / options.outputs);
      record();
    }
  } catch (const sph::Error& e) {
    run.stopped = e.what();
    record();
  }
  run.particles = sim.particles();
  run.inversions = sph::order_inversions<D>(run.initial, run.particles.position, streams.box);
  run.steps = sim.steps();
  run.seconds = clock.seconds();
  run.t_reached = sim.time();
  run.last_dt = sim.last_limit().dt;
  return run;
}

}  // namespace app
