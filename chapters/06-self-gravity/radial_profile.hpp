#pragma once
/// \file
/// \brief Radial profiles of a three-dimensional particle set about a centre: every particle's
/// radius, radial velocity, density and pressure, and their averages in logarithmic bins
/// (app::radial_profile), and a one-dimensional reference put into the same bins
/// (app::binned_reference); the shock on a binned velocity profile (app::find_shock); the binned
/// profile's errors against a one-dimensional reference (app::profile_errors).  The radius of a
/// mass shell is app::radius_holding (lib/app/particle_measures.hpp).
///
/// A spherical problem run in 3D is compared with a 1D calculation through these:
///
/// \code
/// const app::RadialProfile prof = app::radial_profile(particles, sph::centre_of_mass(particles));
/// const app::Shock shock = app::find_shock(prof.bin_r, prof.bin_v);
/// const app::ProfileErrors e = app::profile_errors(prof, ref_r, ref_rho, ref_v);
/// \endcode

#include "app/curve_reading.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace app {

/// A particle set seen from a centre.
struct RadialProfile {
  std::vector<double> r, v, rho, pressure;  ///< every particle: radius, v_r, density, pressure
  /// The bins that hold particles: mean radius, mean v_r, mean \f$ \log_{10}\rho \f$, and the
  /// fraction of the binned particles they hold (their mass fraction, for equal masses).
  std::vector<double> bin_r, bin_v, bin_log_rho, bin_weight;
};

/// The logarithmic bin of radius \p r among \p bins between \p r_min and \p r_max (which
/// \p r must lie within).
inline int radial_bin(double r, int bins, double r_min, double r_max) {
  return std::min(bins - 1, static_cast<int>(bins * std::log(r / r_min) / std::log(r_max / r_min)));
}

namespace radial_profile_detail {

/// Weighted sums per bin of radius, radial velocity and \f$ \log_{10}\rho \f$, and the
/// binned means they give.
struct BinSums {
  std::vector<double> r, v, log_rho, weight;
  double total = 0;
  explicit BinSums(int bins) : r(bins), v(bins), log_rho(bins), weight(bins) {}
  void add(int b, double w, double radius, double velocity, double density) {
    r[b] += w * radius, v[b] += w * velocity, log_rho[b] += w * std::log10(density);
    weight[b] += w, total += w;
  }
  void means_into(RadialProfile& prof) const {
    for (std::size_t b = 0; b < r.size(); ++b) {
      if (weight[b] == 0) continue;
      prof.bin_r.push_back(r[b] / weight[b]);
      prof.bin_v.push_back(v[b] / weight[b]);
      prof.bin_log_rho.push_back(log_rho[b] / weight[b]);
      prof.bin_weight.push_back(weight[b] / total);
    }
  }
};

}  // namespace radial_profile_detail

/// The radial profile of the particles \p p about \p centre, with \p bins logarithmic bins
/// between \p r_min and \p r_max; the radial velocity is \f$ \mathbf v\cdot\hat{\mathbf r} \f$.
inline RadialProfile radial_profile(const sph::Particles<3>& p, const sph::Vec<3>& centre,
                                    int bins = 60, double r_min = 0.01, double r_max = 1.0) {
  RadialProfile prof;
  radial_profile_detail::BinSums sums(bins);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const sph::Vec<3> d = p.position[i] - centre;
    const double r = d.norm();
    const double v = r > 0 ? p.velocity[i].dot(d) / r : 0.0;
    prof.r.push_back(r);
    prof.v.push_back(v);
    prof.rho.push_back(p.density[i]);
    prof.pressure.push_back(p.pressure[i]);
    if (r < r_min || r >= r_max) continue;
    sums.add(radial_bin(r, bins, r_min, r_max), 1.0, r, v, p.density[i]);
  }
  sums.means_into(prof);
  return prof;
}

/// A 1D reference profile \p r -> (\p rho, \p v) on an evenly spaced grid, put into the bins
/// of radial_profile(): each cell weighs its shell's mass, \f$ \rho r^2 \f$, as each particle
/// weighs its own mass there, so that a quantity measured on the bins (a shock's width) can be
/// compared with the particles' as the bins see it.  Only the binned fields are filled.
inline RadialProfile binned_reference(const std::vector<double>& r, const std::vector<double>& rho,
                                      const std::vector<double>& v, int bins = 60,
                                      double r_min = 0.01, double r_max = 1.0) {
  RadialProfile prof;
  radial_profile_detail::BinSums sums(bins);
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (r[k] < r_min || r[k] >= r_max) continue;
    sums.add(radial_bin(r[k], bins, r_min, r_max), rho[k] * r[k] * r[k], r[k], v[k], rho[k]);
  }
  sums.means_into(prof);
  return prof;
}

/// A shock on a radial velocity profile: where it stands and how wide it is.
struct Shock {
  double position = 0, width = 0;
};

/// The shock on the radial velocity profile \p r -> \p v (r increasing) of a collapse: its
/// position is where v has risen from the infall's most negative value (outside r = 0.05) to
/// half of it, its width the distance over which it rises from 80 % to 20 % of that value.
/// Zero for both when no infall is found.
inline Shock find_shock(const std::vector<double>& r, const std::vector<double>& v) {
  std::size_t low = 0;
  bool found = false;
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (r[k] < 0.05) continue;
    if (!found || v[k] < v[low]) low = k;
    found = true;
  }
  if (!found || v[low] >= 0) return {};
  const auto crossing = [&](double fraction) {
    const double level = fraction * v[low];
    for (std::size_t k = low; k > 0; --k) {  // inwards from the infall's peak
      if (v[k - 1] >= level) {
        const double w = (level - v[k]) / (v[k - 1] - v[k]);
        return r[k] + w * (r[k - 1] - r[k]);
      }
    }
    return r[0];
  };
  return {crossing(0.5), crossing(0.8) - crossing(0.2)};
}

/// The errors of a binned profile against a reference: \f$ L_1 \f$ of \f$ \log_{10}\rho \f$
/// and of \f$ v_r \f$, weighted by the bins' mass fractions.
struct ProfileErrors {
  double log_rho = 0, v = 0;
};

/// The errors of the bins of \p prof against the reference profile \p ref_r -> (\p ref_rho,
/// \p ref_v), interpolated linearly at each bin's mean radius.
inline ProfileErrors profile_errors(const RadialProfile& prof, const std::vector<double>& ref_r,
                                    const std::vector<double>& ref_rho,
                                    const std::vector<double>& ref_v) {
  ProfileErrors e;
  for (std::size_t b = 0; b < prof.bin_r.size(); ++b) {
    const double r = prof.bin_r[b];
    e.log_rho += prof.bin_weight[b] *
                 std::abs(prof.bin_log_rho[b] - std::log10(interpolate(ref_r, ref_rho, r)));
    e.v += prof.bin_weight[b] * std::abs(prof.bin_v[b] - interpolate(ref_r, ref_v, r));
  }
  return e;
}

}  // namespace app
