#pragma once
/// \file
/// \brief What a shock tube's run is measured by, beyond the \f$ L_1 \f$ norms of
/// sph::shock_tube_errors: the velocity scatter Watkins et al. (1996) quote, the widths of the
/// shock and the contact in smoothing lengths, and how far the two gases interpenetrate.
///
/// None of the three is defined in the papers that quote them ("a scatter of about 11 %",
/// "smoothed over a range of about 2h", "very little interpenetration"), so each definition is
/// written here once, and every chapter that quotes one uses the same.

#include "app/shock_tube_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace app {

/// The RMS of \f$ (v_i - v_{\rm exact}(x_i))/v_* \f$ over the particles with
/// \f$ lo \le x_i \le hi \f$ (zero if there are none), \f$ v_* \f$ the exact star velocity.
template <int D>
double velocity_scatter(const TubeRun<D>& run, double t, double lo, double hi) {
  const double v_star = run.exact.star_velocity();
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < run.particles.size(); ++i) {
    const double x = run.particles.position[i][0];
    if (x < lo || x > hi) continue;
    const double d = (run.particles.velocity[i][0] - run.exact.sample(x, t).velocity) / v_star;
    sum += d * d;
    ++n;
  }
  return n ? std::sqrt(sum / n) : 0.0;
}

/// The widths of the shock and the contact, in units of h_star, the mean smoothing length of
/// the particles between them (the exact contact and shock).
struct FrontWidths {
  double shock = 0;    ///< where v falls from 90 % to 10 % of \f$ v_* \f$, over h_star
  double contact = 0;  ///< where \f$ \rho \f$ goes 10 % to 90 % of its jump, over h_star
  double h_star = 0;
};

/// The two widths of FrontWidths.  The particles are averaged in bins of h_star/2 along x (in
/// 2D and 3D a bin holds a slab of the tube), and each front is found on the binned profile
/// (linear between bin centres): walking outwards from the middle of the shocked region to
/// the first crossing of the level nearer the far state (10 % of the jump left for the
/// shock's velocity, 10 % of the way from the left star density for the contact), then back
/// towards the middle to the nearest crossing of the other level.  A front is the distance
/// between the two; oscillations behind it do not enter, however large.
template <int D>
FrontWidths front_widths(const TubeRun<D>& run, double t) {
  const auto& p = run.particles;
  const double contact = run.exact.contact_position(t), shock = run.exact.shock_position(t);
  FrontWidths w;
  int n = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.position[i][0];
    if (x > contact && x < shock) {
      w.h_star += p.smoothing_length[i];
      ++n;
    }
  }
  if (n == 0) return w;
  w.h_star /= n;
  const double bin = w.h_star / 2, lo = contact - 6 * w.h_star, hi = shock + 6 * w.h_star;
  const auto bins = static_cast<std::size_t>(std::ceil((hi - lo) / bin));
  std::vector<double> v(bins, 0.0), rho(bins, 0.0);
  std::vector<int> count(bins, 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.position[i][0];
    if (x < lo || x >= hi) continue;
    const auto k = std::min(bins - 1, static_cast<std::size_t>((x - lo) / bin));
    v[k] += p.velocity[i][0];
    rho[k] += p.density[i];
    ++count[k];
  }
  for (std::size_t k = 0; k < bins; ++k) {
    if (count[k] == 0) continue;
    v[k] /= count[k];
    rho[k] /= count[k];
  }
  const auto centre = [&](double k) { return lo + (k + 0.5) * bin; };
  const auto middle_bin = [&] {
    return static_cast<std::ptrdiff_t>((0.5 * (contact + shock) - lo) / bin);
  };
  // The first crossing of `level` by f, walking from bin `from` by `step` (+1 or -1): the
  // position, linear between the two bins around it, and the bin it was reached from (NaN
  // and `from` if the walk ends first).
  struct Crossing {
    double x;
    std::ptrdiff_t bin;
  };
  const auto crossing = [&](const std::vector<double>& f, std::ptrdiff_t from, std::ptrdiff_t step,
                            double level) {
    std::ptrdiff_t a = from;
    while (a >= 0 && a < static_cast<std::ptrdiff_t>(bins) &&
           count[static_cast<std::size_t>(a)] == 0)
      a += step;
    if (a < 0 || a >= static_cast<std::ptrdiff_t>(bins))
      return Crossing{std::numeric_limits<double>::quiet_NaN(), from};
    const bool above = f[static_cast<std::size_t>(a)] > level;
    for (std::ptrdiff_t b = a + step; b >= 0 && b < static_cast<std::ptrdiff_t>(bins); b += step) {
      if (count[static_cast<std::size_t>(b)] == 0) continue;
      const double fa = f[static_cast<std::size_t>(a)], fb = f[static_cast<std::size_t>(b)];
      if ((fb > level) != above) {
        const double s = (level - fa) / (fb - fa);
        return Crossing{centre(static_cast<double>(a) + s * static_cast<double>(b - a)), b};
      }
      a = b;
    }
    return Crossing{std::numeric_limits<double>::quiet_NaN(), from};
  };
  // A front from the middle outwards (`step`): the far level first, then back to the near one.
  const auto front = [&](const std::vector<double>& f, std::ptrdiff_t step, double far_level,
                         double near_level) {
    const Crossing far = crossing(f, middle_bin(), step, far_level);
    if (std::isnan(far.x)) return far.x;
    return std::abs(far.x - crossing(f, far.bin, -step, near_level).x);
  };

  const double v_star = run.exact.star_velocity(), v_ahead = run.exact.sample(hi, t).velocity;
  const auto v_level = [&](double f) { return v_ahead + f * (v_star - v_ahead); };
  w.shock = front(v, +1, v_level(0.1), v_level(0.9)) / w.h_star;
  const double rho_l = run.exact.star_density_left(), rho_r = run.exact.star_density_right();
  const auto rho_level = [&](double f) { return rho_l + f * (rho_r - rho_l); };
  w.contact = front(rho, -1, rho_level(0.1), rho_level(0.9)) / w.h_star;
  return w;
}

/// How far the two gases have passed into each other, in the window \f$ |x| \le 0.6 \f$ (away
/// from the periodic tube's second interface): the gas that began on the left (the first
/// `run.left_count` particles) against the gas that began on the right.
struct GasOverlap {
  std::size_t crossed = 0;  ///< particles of either gas beyond the other's rearmost particle
  double depth = 0;         ///< that overlap's length, in units of h_star (0: none)
};
template <int D>
GasOverlap gas_overlap(const TubeRun<D>& run, double h_star) {
  const auto& p = run.particles;
  double front_left = -std::numeric_limits<double>::infinity();
  double rear_right = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.position[i][0];
    if (std::abs(x) > 0.6) continue;
    if (i < run.left_count) {
      front_left = std::max(front_left, x);
    } else {
      rear_right = std::min(rear_right, x);
    }
  }
  GasOverlap o;
  if (!(front_left > rear_right)) return o;
  o.depth = (front_left - rear_right) / h_star;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.position[i][0];
    if (std::abs(x) > 0.6) continue;
    o.crossed += i < run.left_count ? x > rear_right : x < front_left;
  }
  return o;
}

}  // namespace app
