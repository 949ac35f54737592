#pragma once
/// \file
/// \brief Single numbers a chapter reads off a particle set for its tables: the momentum drift
/// of a run, the largest speed, the radius that holds a given share of the particles, and the
/// median smoothing length.
///
/// \code
/// const sph::Vec<3> p0 = sph::total_momentum(start);
/// ... run ...
/// std::printf("%.1e %.4f %.4f\n", app::momentum_drift(p, p0), app::peak_speed(p),
///             app::radius_holding(p, 0.9));
/// \endcode
///
/// The totals themselves (momentum, energies, centre of mass) are
/// lib/sph/measures/diagnostics.hpp's.

#include "sph/measures/diagnostics.hpp"

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace app {

/// How far the total momentum of \p p has moved from \p start:
/// \f$ |\mathbf P(t) - \mathbf P(0)| / \sum_i m_i|\mathbf v_i| \f$, against the momentum scale
/// of chapter 3 (sph::momentum_scale); 0 for a gas at rest.
template <int D>
double momentum_drift(const sph::Particles<D>& p, const std::type_identity_t<sph::Vec<D>>& start) {
  const double scale = sph::momentum_scale(p);
  return scale > 0 ? (sph::total_momentum(p) - start).norm() / scale : 0.0;
}

/// The net force of accelerations \p a on particles of masses \p mass, as a fraction of its
/// scale: \f$ |\sum_i m_i\mathbf a_i| / \sum_i m_i|\mathbf a_i| \f$ (zero for forces that are
/// equal and opposite pair by pair).
template <int D>
double net_force_fraction(const std::vector<double>& mass, const std::vector<sph::Vec<D>>& a) {
  sph::Vec<D> net = sph::Vec<D>::Zero();
  double total = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    net += mass[i] * a[i];
    total += mass[i] * a[i].norm();
  }
  return net.norm() / total;
}

/// The largest speed \f$ |\mathbf v_i| \f$ of the particles.
template <int D>
double peak_speed(const sph::Particles<D>& p) {
  double v = 0;
  for (const auto& x : p.velocity) v = std::max(v, x.norm());
  return v;
}

/// The distance from \p centre within which the share \p fraction of the particles lies (the
/// nearest entry of the sorted distances; for particles of equal mass, the radius of the sphere
/// that holds that share of the mass).
template <int D>
double radius_holding(const sph::Particles<D>& p, double fraction,
                      const std::type_identity_t<sph::Vec<D>>& centre) {
  std::vector<double> r(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) r[i] = (p.position[i] - centre).norm();
  const auto k = static_cast<std::size_t>(fraction * double(r.size() - 1));
  std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(k), r.end());
  return r[k];
}

/// The same about the particles' centre of mass.
template <int D>
double radius_holding(const sph::Particles<D>& p, double fraction) {
  return radius_holding(p, fraction, sph::centre_of_mass(p));
}

/// The median smoothing length of the particles (the upper median for an even count).
template <int D>
double median_smoothing_length(const sph::Particles<D>& p) {
  std::vector<double> h = p.smoothing_length;
  std::nth_element(h.begin(), h.begin() + h.size() / 2, h.end());
  return h[h.size() / 2];
}

}  // namespace app
