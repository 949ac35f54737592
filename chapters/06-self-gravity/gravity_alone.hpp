#pragma once
/// \file
/// \brief app::gravity_alone: one evaluation of a gravity module on its own, outside a step,
/// with its accelerations, potential energy, wall time and net force; and app::median_seconds,
/// the median wall time of repeated calls.
///
/// This is how the chapter measures one gravity module against another (a tree against direct
/// summation) on the same particles:
///
/// \code
/// const app::GravityField exact = app::gravity_alone(sph::DirectGravity{}, particles);
/// sph::TreeGravity tree;
/// const app::GravityField approximate = app::gravity_alone(tree, particles);
/// // compare approximate.a[i] with exact.a[i]; read tree.statistics() afterwards
/// \endcode

#include "app/curve_reading.hpp"
#include "app/particle_measures.hpp"
#include "app/stopwatch.hpp"
#include "sph/box.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace app {

/// The gravitational field of a set of particles as one module computes it.
struct GravityField {
  std::vector<sph::Vec<3>> a;   ///< the gravitational acceleration of each particle
  double potential_energy = 0;  ///< the module's potential energy of the set
  double seconds = 0;           ///< wall time of the accelerations (not of the energy)
  double net_force = 0;         ///< \f$ |\sum_i m_i\mathbf a_i| / \sum_i m_i|\mathbf a_i| \f$
};

/// The accelerations and potential energy that \p gravity gives the particles \p p in open
/// space, the time the accelerations took, and their net force against its scale (zero for
/// forces that are equal and opposite pair by pair).  The module is taken by reference, so
/// that the statistics of this evaluation (a tree's interaction counts) can be read after it.
template <class G>
GravityField gravity_alone(G&& gravity, sph::Particles<3> p) {
  std::fill(p.acceleration.begin(), p.acceleration.end(), sph::Vec<3>::Zero());
  const Stopwatch clock;
  gravity.add_accelerations(p, sph::Box<3>::open());
  GravityField f;
  f.seconds = clock.seconds();
  f.potential_energy = gravity.potential_energy(p, sph::Box<3>::open());
  f.net_force = net_force_fraction(p.mass, p.acceleration);
  f.a = std::move(p.acceleration);
  return f;
}

/// The median wall time, in seconds, of \p repeats calls of \p f (a timing less disturbed by
/// a busy machine than one call).
template <class F>
double median_seconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int k = 0; k < repeats; ++k) {
    const Stopwatch clock;
    f();
    t.push_back(clock.seconds());
  }
  return percentile(t, 0.5);
}

}  // namespace app
