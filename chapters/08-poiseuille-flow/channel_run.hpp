#pragma once
/// \file
/// \brief One run of the Poiseuille channel (chapter 8): the scene, the choices a run can make,
/// and what it records on the way -- the error against the start-up series, the rows'
/// alternation, the density's excursion, the momentum the walls take.
///
/// Every step of the chapter calls `run_channel` with a `RunChoices` and reads the `ChannelRun`
/// it returns.  The scene is a template over the viscosity term and the boundaries, so that a
/// run with Watkins' term compiles no one-pass term and a free run compiles no constraint.

#include "app/stopwatch.hpp"
#include "sph/boundaries/fixed_particles.hpp"
#include "sph/boundaries/parabolic_walls.hpp"
#include "sph/eos.hpp"
#include "sph/error.hpp"
#include "sph/forces.hpp"
#include "sph/potential/uniform_field.hpp"
#include "sph/reference/poiseuille.hpp"
#include "sph/scene.hpp"
#include "sph/setups/poiseuille_channel.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_shear_viscosity.hpp"
#include "sph/terms/morris_fox_zhu_1997.hpp"
#include "sph/terms/pressure.hpp"
#include "sph/terms/watkins_1996.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace app::poiseuille {

/// The three ways of making the shear viscosity that the chapter compares.
enum class Viscosity {
  watkins,    ///< Watkins et al.'s two passes, curl of the curl (sph/terms/watkins_1996.hpp)
  one_pass,   ///< Morris, Fox & Zhu's one-pass Laplacian (sph/terms/morris_fox_zhu_1997.hpp)
  artificial  ///< Monaghan's linear term on all pairs (sph/terms/monaghan_shear_viscosity.hpp)
};
inline const char* name(Viscosity v) {
  switch (v) {
    case Viscosity::watkins:
      return "Watkins (two passes)";
    case Viscosity::one_pass:
      return "Morris (one pass)";
    case Viscosity::artificial:
      return "Monaghan AV, all pairs";
  }
  return "?";
}
/// The explicit viscous limit each term declares for its time step, in units of
/// \f$ h^2/\nu \f$: \f$ 0.125 \f$ of Morris et al. on the coefficient that damps the fastest
/// motion -- \f$ \nu \f$ for the one pass, \f$ \nu_b + \tfrac43\nu \f$ for Watkins' term
/// (\f$ \tfrac43\nu \f$ here) and for Monaghan's (\f$ 3\nu \f$, its bulk part included).
inline double viscous_limit_factor(Viscosity v) {
  switch (v) {
    case Viscosity::watkins:
      return 0.125 * 3.0 / 4.0;
    case Viscosity::one_pass:
      return 0.125;
    case Viscosity::artificial:
      return 0.125 / 3.0;
  }
  return 0;
}

/// Everything a run of the channel may choose.  The defaults are Watkins et al.'s flow and the
/// choices of the text: a weakly compressible gas at Mach 0.1, a fixed step of a quarter of h/c
/// or the viscous limit of the term, whichever is smaller.
struct RunChoices {
  sph::setups::PoiseuilleChannel channel;  ///< lattice, a, N, walls (Watkins: 70, 0.4, 30)
  double g = 3.6;                          ///< the driving acceleration (Watkins: 3.6)
  double mu = 0.15;                        ///< \f$ \mu_s \f$ (Watkins: 0.15; \f$ \rho = 1 \f$)
  double sound_speed = 19.2;               ///< c: 10 axis speeds
  bool rest_pressure = false;              ///< P = c^2 rho (true) or c^2 (rho - rho_0)
  double step_factor = 0.25;               ///< dt = min(step_factor h/c, the viscous limit)
  double fixed_step = 0;                   ///< a given dt instead (0: the rule above)
  bool confine = false;                    ///< the fluid moves along x only
  bool lend_velocity = true;               ///< the walls lend eq 17's pseudo-velocity
  bool lend_curl = true;                   ///< and eq 19's pseudo-curl
  bool start_steady = false;               ///< start on eq 15's parabola, not at rest
  Viscosity viscosity = Viscosity::watkins;

  sph::PoiseuilleFlow flow() const {
    return sph::PoiseuilleFlow(channel.half_width, g, mu / channel.density);
  }
  double h() const { return channel.smoothing_length(); }
  /// The step: fixed_step, or the smaller of a quarter (step_factor) of the sound crossing
  /// time of a smoothing length, h/c, and the viscous limit the viscosity term declares.
  double dt() const {
    if (fixed_step > 0) return fixed_step;
    return std::min(sound_step(), viscous_limit());
  }
  /// The sound's part of the rule: step_factor h/c.
  double sound_step() const { return step_factor * h() / sound_speed; }
  /// The viscous limit of the term (viscous_limit_factor) for this lattice's h.
  double viscous_limit() const {
    return viscous_limit_factor(viscosity) * h() * h() * channel.density / mu;
  }
};

/// What a run records at each sample time.
struct Sample {
  double t = 0;
  double l1_series = 0;          ///< mean |v_x - series| over the fluid, over the axis speed
  double l1_steady = 0;          ///< mean |v_x - eq 15| over the fluid, over the axis speed
  double alternation = 0;        ///< the rows' alternating mode, over the axis speed (see measure)
  double density_excursion = 0;  ///< max |rho/rho_0 - 1| over the fluid (rho_0: the lattice's)
  double drag = 0;               ///< -(x force of pressure and viscosity on the fluid) / M_fluid g
  double from_walls = 0;         ///< x force of the wall particles' pairs on the fluid / M_fluid g
  double from_gas = 0;           ///< |force of the fluid's pairs among themselves| / M_fluid g
};

/// A profile: y and v_x of every fluid particle at time t, and all the particles then.
struct Profile {
  double t = 0;
  std::vector<double> y, vx;
  sph::Particles<2> particles;
};

/// What a run returns.
struct ChannelRun {
  std::vector<Sample> samples;
  std::vector<Profile> profiles;  ///< at the requested times
  sph::Particles<2> last;         ///< the particles at the end
  long steps = 0;
  double seconds = 0;  ///< wall time of the steps
  double dt = 0;
  double t_end = 0;
  std::string stopped;  ///< empty, or why the run stopped early (a blow-up, with its message)
  double stopped_at = 0;
};

/// The scene: isothermal gas, the pressure force, viscosity term Term, a uniform field g along
/// x, fixed walls (Bounds: free fluid or fluid moving along x), and Watkins' predictor-corrector.
template <class Gas, class Term, class Bounds>
struct ChannelScene : sph::Scene<2> {
  using Eos = Gas;
  using Terms = sph::Terms<sph::PressureHernquistKatz, Term>;
  using External = sph::UniformField<2>;
  using Boundaries = Bounds;
  using Integrator = sph::PredictorCorrector<2>;
};

/// \section ch08_measure What a sample measures
///
/// Every fluid particle keeps the row it started in (`row`, 0 at the bottom).  The rows'
/// alternation is the amplitude of the shortest wave the rows can carry,
/// \f[ A = \Big|\frac{1}{n_\mathrm{rows}}\sum_k (-1)^k\,\overline{\delta v}_k\Big|, \qquad
///     \overline{\delta v}_k = \text{mean over row } k \text{ of } v_x - v_\mathrm{ref}(y), \f]
/// in units of the axis speed: zero for any smooth error, and the size of the paper's
/// "alternately higher and lower" rows when they appear.
template <class Sim>
Sample measure(const Sim& sim, const RunChoices& c, double rho0, const std::vector<int>& row,
               int rows) {
  const auto& p = sim.particles();
  const sph::PoiseuilleFlow flow = c.flow();
  const double t = sim.time(), v0 = flow.axis_speed();
  Sample s;
  s.t = t;
  std::vector<double> row_sum(rows, 0.0);
  std::vector<int> row_count(rows, 0);
  double fluid_mass = 0, fluid_force = 0;
  long n = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] != sph::ParticleKind::fluid) continue;
    const double y = p.position[i][1], v = p.velocity[i][0];
    const double series = flow.from_rest(y, t, 1e-8);
    s.l1_series += std::abs(v - series);
    s.l1_steady += std::abs(v - flow.steady(y));
    s.density_excursion = std::max(s.density_excursion, std::abs(p.density[i] / rho0 - 1));
    row_sum[row[i]] += v - series;
    ++row_count[row[i]];
    fluid_mass += p.mass[i];
    fluid_force += p.mass[i] * (p.acceleration[i][0] - c.g);
    ++n;
  }
  s.l1_series /= n * v0;
  s.l1_steady /= n * v0;
  double alternating = 0;
  for (int k = 0; k < rows; ++k)
    if (row_count[k] > 0) alternating += (k % 2 == 0 ? 1.0 : -1.0) * row_sum[k] / row_count[k];
  s.alternation = std::abs(alternating) / rows / v0;
  const double drive = fluid_mass * c.g;
  s.drag = -fluid_force / drive;
  /// The momentum account walks the pairs once more, with the scene's own pair function, and
  /// sorts the force on the fluid into what its wall neighbours give it and what the fluid
  /// gives itself.  For a viscosity whose pairs push equally and oppositely the second is zero
  /// to round-off, and the gas's momentum changes only by the drive and the walls' push, which
  /// the walls take up; for one that does not, it is the part of the fluid's force that no
  /// pair hands to a wall.  (The walk sees the state after the step with the derived fields of
  /// the step's one evaluation, at its midpoint: the split is exact, its sum differs from the
  /// step's force by a part in \f$ \delta t \f$.)
  const auto in = sim.view();
  double walls_x = 0, gas[2] = {0, 0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] != sph::ParticleKind::fluid) continue;
    for (const auto& nb : sim.neighbours().of(i)) {
      const auto pf = sph::pair_force<2, typename Sim::K>(in, sim.terms(), i, nb);
      double a[2];
      for (int k = 0; k < 2; ++k) a[k] = -pf.f * pf.r_ij[k] + pf.extra.a[k];
      if (p.kind[nb.index] == sph::ParticleKind::fluid) {
        for (int k = 0; k < 2; ++k) gas[k] += p.mass[i] * a[k];
      } else {
        walls_x += p.mass[i] * a[0];
      }
    }
  }
  s.from_walls = walls_x / drive;
  s.from_gas = std::hypot(gas[0], gas[1]) / drive;
  return s;
}

/// One run from rest to t_end, sampled every `sample_every` in time, with profiles at
/// `profile_times`.  A run that blows up (a non-finite force, a particle through a wall) is
/// returned with `stopped` set and its samples so far, when `allow_stop`; otherwise the error
/// goes on to the caller.
template <class Gas, class Term, class Bounds>
ChannelRun run_scene(const RunChoices& c, Gas gas, Term term, Bounds bounds, double t_end,
                     double sample_every, std::vector<double> profile_times, bool allow_stop) {
  /// Each particle's row, counted from the lowest fluid row, is fixed at the start: the
  /// alternation of `measure` follows the rows the particles began in, wherever they go.
  sph::Particles<2> p = c.channel.particles();
  const double dx = c.channel.spacing();
  if (c.start_steady) {
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.kind[i] == sph::ParticleKind::fluid)
        p.velocity[i][0] = c.flow().steady(p.position[i][1]);
  }
  double lowest = 1;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.kind[i] == sph::ParticleKind::fluid) lowest = std::min(lowest, p.position[i][1]);
  std::vector<int> row(p.size(), 0);
  int rows = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    row[i] = static_cast<int>(std::lround((p.position[i][1] - lowest) / dx));
    if (p.kind[i] == sph::ParticleKind::fluid) rows = std::max(rows, row[i] + 1);
  }
  /// The scene's settings are the paper's: one constant h, the gather density of their eq A1,
  /// and a constant step.  The rest density of the weakly compressible gas is the lattice's.
  const double rho0 = c.channel.lattice_density<sph::Kernel<2>>();
  sph::Settings settings;
  settings.smoothing = sph::SmoothingLengthRule::fixed();
  settings.density = sph::DensityForm::watkins();
  settings.fixed_timestep = c.dt();
  settings.max_steps = 50'000'000;
  ChannelRun out;
  out.dt = c.dt();
  out.t_end = t_end;
  std::sort(profile_times.begin(), profile_times.end());
  sph::Simulation<ChannelScene<Gas, Term, Bounds>> sim(
      std::move(p), sph::setups::PoiseuilleChannel::box(), gas, term, bounds,
      sph::UniformField<2>(sph::Vec<2>(c.g, 0.0)), settings);
  const auto take_profile = [&](double t) {
    Profile pr;
    pr.t = t;
    for (std::size_t i = 0; i < sim.particles().size(); ++i) {
      if (sim.particles().kind[i] != sph::ParticleKind::fluid) continue;
      pr.y.push_back(sim.particles().position[i][1]);
      pr.vx.push_back(sim.particles().velocity[i][0]);
    }
    pr.particles = sim.particles();
    out.profiles.push_back(std::move(pr));
  };
  /// Steps of dt, the last one shortened to land on t_end; a sample whenever a sample time is
  /// reached (within half a step), and always one at the end.
  std::size_t next_profile = 0;
  double next_sample = 0;
  const double half = 0.5 * c.dt();
  const Stopwatch clock;
  const auto record = [&] {
    const double t = sim.time();
    if (t >= next_sample - half || t >= t_end - 1e-9 * c.dt()) {
      out.samples.push_back(measure(sim, c, rho0, row, rows));
      while (next_sample <= t + half) next_sample += sample_every;
    }
    while (next_profile < profile_times.size() && t >= profile_times[next_profile] - half)
      take_profile(profile_times[next_profile++]);
  };
  try {
    record();
    while (t_end - sim.time() > 1e-9 * c.dt()) {
      sim.step(t_end - sim.time());
      ++out.steps;
      record();
    }
  } catch (const sph::Error& e) {
    /// A blow-up.  Its first sign is usually a fluid particle at or through a plate, where the
    /// walls' eq 17 has no answer: the message names it, since the force check may name a
    /// wall particle that merely sees it.
    std::string why = e.what();
    const auto& q = sim.particles();
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (q.kind[i] == sph::ParticleKind::fluid &&
          !(std::abs(q.position[i][1]) < c.channel.half_width)) {
        why += "; fluid particle " + sph::show(i) + " is at y = " + sph::show(q.position[i][1]) +
               ", at or beyond the plate at |y| = " + sph::show(c.channel.half_width);
        break;
      }
    }
    if (!allow_stop) throw sph::Error(why);
    out.stopped = why;
    out.stopped_at = sim.time();
    take_profile(sim.time());  // (the velocities are still those of the last good step)
  }
  out.seconds = clock.seconds();
  out.last = sim.particles();
  return out;
}

/// The run with the choices' viscosity, walls and confinement.
inline ChannelRun run_channel(const RunChoices& c, double t_end, double sample_every,
                              const std::vector<double>& profile_times = {},
                              bool allow_stop = false) {
  sph::ParabolicWalls<2> walls(0.0, c.channel.half_width, 1);
  walls.lend_velocity = c.lend_velocity;
  walls.lend_curl = c.lend_curl;
  const auto with_bounds = [&](auto term) {
    const auto with_gas = [&](auto gas) {
      if (c.confine)
        return run_scene(c, gas, term, sph::FixedParticlesMovingAlong(0), t_end, sample_every,
                         profile_times, allow_stop);
      return run_scene(c, gas, term, sph::FixedParticles{}, t_end, sample_every, profile_times,
                       allow_stop);
    };
    if (c.rest_pressure) return with_gas(sph::Isothermal(c.sound_speed));
    return with_gas(
        sph::WeaklyCompressible(c.sound_speed, c.channel.lattice_density<sph::Kernel<2>>()));
  };
  if (c.viscosity == Viscosity::one_pass)
    return with_bounds(sph::MorrisFoxZhu1997<2, sph::ParabolicWalls<2>>(c.mu, walls));
  if (c.viscosity == Viscosity::artificial) {
    return with_bounds(sph::MonaghanShearViscosity<2, sph::ParabolicWalls<2>>::for_viscosity(
        c.mu / c.channel.density, c.sound_speed, c.h(), walls));
  }
  using Watkins =
      sph::WatkinsViscosity<2, sph::Kernel<2>, sph::ConstantViscosity, sph::ParabolicWalls<2>>;
  return with_bounds(Watkins(sph::ConstantViscosity{c.mu, 0.0}, walls));
}

}  // namespace app::poiseuille
