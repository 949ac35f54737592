#pragma once
/// \file
/// \brief The Riemann shock tube in 1D, 2D and 3D: particles, box and exact solution.
///
/// Two uniform gases meet at x = 0: the left state for -L <= x < 0, the right state for
/// 0 <= x < L.  The tube is periodic in x with period 2L, so a second interface sits at x = ±L;
/// its waves start at the far ends and, for the times we run, never reach the measured window
/// around x = 0.  A periodic tube has no free surfaces and no walls, so nothing but the two
/// Riemann problems happens in it.  In 2D and 3D the tube has a periodic cross-section of the
/// given width (Watkins et al. 1996 §4.3: 2.0 x 0.125 x 0.125).
///
/// **How the particles start.**  In 1D they sit on a lattice.  In 2D and 3D a perfect cubic
/// lattice has a flaw that chapter 4 shows: in the rarefaction it is stretched along x only,
/// its symmetry forbids any sideways rearrangement, and on a lattice stretched 2.3 times along
/// x (Sod's expansion from rho = 1 to 0.43) the SPH sum for dP/dx falls to about half its true
/// value at 60 neighbours.  The rarefaction then stalls.  So a multi-D tube can start from a
/// lattice (to show this), a disturbed lattice (random offsets of a fraction of the spacing:
/// the symmetry is broken and particles rearrange), or a settled glass (each side relaxed to
/// uniform density in its own periodic box, sph/setups/relax.hpp).
///
/// **Walls instead of the period.**  A periodic tube holds twice the particles of the window it
/// is measured in: the far half is there only to keep the far interface's waves away.  With
/// `ends = walls` the tube is the window, \f$ |x| \le L \f$, open in x, and each end is closed by
/// a layer of fixed boundary particles (sph::FixedParticles, `wall_cells` lattice cells of the
/// side's own spacing) that continue the lattice and hold the side's initial state.  Until the
/// first wave reaches a wall the gas next to it is the undisturbed initial state, at rest, so a
/// frozen continuation of it is exactly what the gas would see there; the fixed particles have
/// their density summed like any other (the outermost, whose kernels reach out of the layer,
/// are too far from the gas to matter).  Both gases must be at rest for that.
///
/// Particles sit on cubic lattices of equal mass: the spacing on the right is
/// \f$ \Delta x_R = \Delta x_L (\rho_L/\rho_R)^{1/D} \f$, rounded so that whole numbers of cells
/// fill the cross-section and the length (in 2D/3D the right lattice is then slightly
/// anisotropic along x, so that the mass per unit length stays exact).  The masses are then
/// calibrated so that the SPH density of each side's interior equals its nominal density
/// (chapter 2: the kernel sum over a lattice is biased, and uncorrected that bias is a
/// floor under every error we measure).

#include "sph/density.hpp"
#include "sph/eos.hpp"
#include "sph/measures/convergence.hpp"
#include "sph/measures/norms.hpp"
#include "sph/neighbours.hpp"
#include "sph/reference/riemann.hpp"
#include "sph/setups/initial_conditions.hpp"
#include "sph/setups/relax.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace sph {

/// What a shock tube is made of.
struct ShockTubeSetup {
  GasState left{1.0, 0.0, 1.0};     ///< Sod (1978): rho 1, v 0, P 1
  GasState right{0.125, 0.0, 0.1};  ///< rho 0.125, v 0, P 0.1
  double gamma = 1.4;
  double left_spacing = 1.0 / 800;  ///< lattice spacing on the left side
  double half_length = 1.0;         ///< each side is this long; the x period is twice it
  /// How the tube ends: periodic in x (the far interface at x = ±L), or fixed-particle walls
  enum class Ends { periodic, walls };
  Ends ends = Ends::periodic;
  int wall_cells = 8;     ///< walls: the fixed layer's thickness in lattice cells of each side
  double width = 0.125;   ///< cross-section width in 2D/3D (periodic)
  bool calibrate = true;  ///< scale each side's mass so its SPH density is nominal
  enum class Start { lattice, disturbed, settled };
  Start start = Start::lattice;  ///< see the file comment; 2D/3D scenes want disturbed or settled
  double disturbance = 0.2;      ///< disturbed: offsets up to this fraction of the spacing
  std::uint64_t seed = 1996;     ///< for the disturbance

  /// Sod's tube.
  static ShockTubeSetup sod() { return {}; }
  /// Monaghan & Gingold (1983), as used by Watkins et al. (1996) Table 1.
  static ShockTubeSetup monaghan_gingold() {
    ShockTubeSetup s;
    s.left = {1.0, 0.0, 1.0};
    s.right = {0.25, 0.0, 0.1795};
    return s;
  }
};

/// A shock tube ready to run: its particles, its box, and the exact solution to compare
/// with.
template <int D>
struct ShockTube {
  Particles<D> particles;
  Box<D> box;
  RiemannSolution exact;
  int left_count = 0, right_count = 0;
  double right_spacing = 0;  ///< mean right spacing along x
};

namespace detail {

// Relax one side's points to uniform density (a glass) in the side's own periodic box.
template <int D>
void settle_side(std::vector<Vec<D>>& points, const Box<D>& box) {
  double volume = 1;
  for (int a = 0; a < D; ++a) volume *= box.length(a);
  const double spacing = root<D>(volume / static_cast<double>(points.size()));
  Particles<D> p = make_particles<D>(points, 1.0);
  for (auto& h : p.smoothing_length) h = 1.2 * spacing;
  RelaxOptions options;
  relax_to_uniform_density<D>(p, box, options);
  points = p.position;
}

// Equal-mass lattices on both sides, nominal masses (before calibration).
template <int D>
ShockTube<D> shock_tube_lattices(const ShockTubeSetup& s) {
  require(s.left_spacing > 0 && s.half_length > 0 && s.width > 0,
          "shock tube: spacing, length and width must be positive");
  require(s.left_spacing < 0.1 * s.half_length,
          "shock tube: the left spacing must be well below the tube length");
  const double L = s.half_length;
  const bool walls = s.ends == ShockTubeSetup::Ends::walls;
  if (walls) {
    require(s.wall_cells >= 4, "shock tube: a wall needs at least 4 cells of fixed particles");
    require(s.left.velocity == 0 && s.right.velocity == 0,
            "shock tube: a tube closed by walls needs both gases at rest (--v-left, --v-right): "
            "gas moving at a wall launches a wave from it at t = 0");
  }
  // Left: cubic, isotropic.
  std::array<int, D> left_cells{}, right_cells{};
  left_cells[0] = std::max(1, static_cast<int>(std::lround(L / s.left_spacing)));
  const double dx_left = L / left_cells[0];
  for (int a = 1; a < D; ++a)
    left_cells[a] = std::max(1, static_cast<int>(std::lround(s.width / dx_left)));
  // Right: equal masses need (rho_L / rho_R) times the volume per particle.
  const double volume_ratio = s.left.density / s.right.density;
  const double dx_right = dx_left * root<D>(volume_ratio);
  double cross_left = 1, cross_right = 1;
  for (int a = 1; a < D; ++a) {
    right_cells[a] = std::max(1, static_cast<int>(std::lround(s.width / dx_right)));
    cross_left *= left_cells[a];
    cross_right *= right_cells[a];
  }
  // Particles per unit length on the right: (rho_R / rho_L) of the left's, per cross-section.
  const double per_length = left_cells[0] / L * cross_left / volume_ratio;
  right_cells[0] = std::max(1, static_cast<int>(std::lround(per_length * L / cross_right)));

  ShockTube<D> tube{Particles<D>{},    Box<D>{}, RiemannSolution(s.left, s.right, s.gamma), 0, 0,
                    L / right_cells[0]};
  Vec<D> lower = Vec<D>::Zero(), upper = Vec<D>::Constant(s.width);
  lower[0] = -L;
  upper[0] = L;
  tube.box = Box<D>::periodic_box(lower, upper);
  if (walls) {
    // Open in x; each side's lattice continues through the wall for wall_cells more cells.
    tube.box.periodic[0] = false;
    left_cells[0] += s.wall_cells;
    right_cells[0] += s.wall_cells;
    lower[0] -= s.wall_cells * dx_left;
    upper[0] += s.wall_cells * tube.right_spacing;
  }
  Vec<D> mid_low = lower, mid_high = upper;
  mid_high[0] = 0.0;
  mid_low[0] = 0.0;
  auto left_points = lattice<D>(LatticeType::cubic, lower, mid_high, left_cells);
  auto right_points = lattice<D>(LatticeType::cubic, mid_low, upper, right_cells);
  if (s.start != ShockTubeSetup::Start::lattice) {
    // Each side moves inside its own periodic box, so no particle crosses the interface.
    disturb<D>(left_points, s.disturbance * dx_left, s.seed, Box<D>::periodic_box(lower, mid_high));
    disturb<D>(right_points, s.disturbance * dx_right, s.seed + 1,
               Box<D>::periodic_box(mid_low, upper));
  }
  if (s.start == ShockTubeSetup::Start::settled) {
    settle_side<D>(left_points, Box<D>::periodic_box(lower, mid_high));
    settle_side<D>(right_points, Box<D>::periodic_box(mid_low, upper));
  }
  // Along the tube, slab after slab (neighbours near each other in memory).
  order_by_cells<D>(left_points, 2.0 * dx_left);
  order_by_cells<D>(right_points, 2.0 * dx_right);
  double cell_volume = dx_left;
  for (int a = 1; a < D; ++a) cell_volume *= s.width / left_cells[a];
  const double mass = s.left.density * cell_volume;
  const IdealGas gas(s.gamma);
  // Beyond |x| = L (walls only) the particles are fixed.
  const auto kind = [&](const Vec<D>& x) {
    return std::abs(x[0]) > L ? ParticleKind::fixed : ParticleKind::fluid;
  };
  for (const auto& x : left_points) {
    tube.particles.add(x, Vec<D>::Unit(0) * s.left.velocity, mass,
                       gas.internal_energy(s.left.density, s.left.pressure), 0.0, kind(x));
  }
  for (const auto& x : right_points) {
    tube.particles.add(x, Vec<D>::Unit(0) * s.right.velocity, mass,
                       gas.internal_energy(s.right.density, s.right.pressure), 0.0, kind(x));
  }
  tube.left_count = static_cast<int>(left_points.size());
  tube.right_count = static_cast<int>(right_points.size());
  return tube;
}

}  // namespace detail

/// Build a shock tube.  With `s.calibrate`, each side's masses are scaled (a few sweeps, since
/// h may depend on the masses) until the mean SPH density of its interior -- the particles
/// farther than 3 max h from both interfaces -- equals the nominal density.
template <int D, class K = Kernel<D>>
ShockTube<D> make_shock_tube(const ShockTubeSetup& s, const SmoothingLengthRule& rule,
                             DensityForm form = DensityForm::selhammar()) {
  ShockTube<D> tube = detail::shock_tube_lattices<D>(s);
  if (!s.calibrate) return tube;
  Particles<D>& p = tube.particles;
  NeighbourSearch<D, K> search;
  // The far ends of each side's lattice: the period's end, or the outer face of a wall.
  double outer[2] = {s.half_length, s.half_length};
  if (s.ends == ShockTubeSetup::Ends::walls) {
    outer[0] += s.wall_cells * s.half_length / std::lround(s.half_length / s.left_spacing);
    outer[1] += s.wall_cells * tube.right_spacing;
  }
  for (int sweep = 0; sweep < 4; ++sweep) {
    search.update(p, tube.box, rule);
    compute_density<D, K>(p, search.list(), form);
    // Each side's interior: farther than 1.5 kernel supports (of that side's largest h) from
    // both interfaces.
    double h_max[2] = {0, 0};
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int side = p.position[i][0] < 0 ? 0 : 1;
      h_max[side] = std::max(h_max[side], p.smoothing_length[i]);
    }
    double sum[2] = {0, 0};
    int count[2] = {0, 0};
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double x = p.position[i][0];
      const int side = x < 0 ? 0 : 1;
      const double margin = 1.5 * K::support * h_max[side];
      if (std::abs(x) < margin || outer[side] - std::abs(x) < margin) continue;
      sum[side] += p.density[i];
      ++count[side];
    }
    require(count[0] > 0 && count[1] > 0,
            "shock tube: too few particles for the kernel size (no interior to calibrate)");
    const double scale[2] = {s.left.density / (sum[0] / count[0]),
                             s.right.density / (sum[1] / count[1])};
    for (std::size_t i = 0; i < p.size(); ++i) p.mass[i] *= scale[p.position[i][0] < 0 ? 0 : 1];
  }
  return tube;
}

/// The window in which a shock tube is compared with its exact solution: |x| <= 0.5, well
/// inside the waves of the far interface for t <= 0.2.
inline Selection shock_tube_window() { return Selection::range(-0.5, 0.5); }

/// How long a tube's exact solution describes its measured window, in the frame that moves with
/// the mean of the two gases' velocities, \f$ v_f = (v_L + v_R)/2 \f$ (zero for Sod's tube; the
/// velocity of a tube boosted as a whole).
struct ExactValidity {
  double frame_velocity = 0;  ///< \f$ v_f \f$
  double until = 0;           ///< the exact solution holds in the window for t <= until
  double end_reached = 0;     ///< when the fastest wave from x = 0 reaches the tube's end
  std::string reason;         ///< which waves arrive, and when
};

/// The time until which the Riemann solution at x = 0 describes the window |x| <= `window` of
/// the tube \p s (in the frame moving with \f$ v_f \f$).  With walls the window is the whole
/// tube, and it holds until the fastest wave from the centre reaches a wall.  A periodic tube
/// of period 2L has a second interface at x = ±L, the two states the other way round, whose own
/// Riemann problem launches waves towards the window from both sides: the solution holds until
/// the first of them reaches the window's edge or meets a wave from the centre (after which the
/// waves the meeting makes may run into the window; the bound is cautious, never late).  The
/// outer waves of a fan move no slower than the sound speed of the gas they run into, so where
/// the far problem has no star state (its gases fly apart) its heads \f$ v \mp c \f$ are used.
inline ExactValidity exact_solution_validity(const ShockTubeSetup& s, double window = 0.5) {
  ExactValidity v;
  const double L = s.half_length;
  const bool walls = s.ends == ShockTubeSetup::Ends::walls;
  v.frame_velocity = walls ? 0.0 : 0.5 * (s.left.velocity + s.right.velocity);
  GasState left = s.left, right = s.right;
  left.velocity -= v.frame_velocity;
  right.velocity -= v.frame_velocity;
  const RiemannSolution centre(left, right, s.gamma);
  const double c_min = centre.left_wave().head_speed, c_max = centre.right_wave().head_speed;
  const double fastest = std::max(-c_min, c_max);
  v.end_reached = fastest > 0 ? L / fastest : std::numeric_limits<double>::infinity();
  const auto text = [](double x) { return show(x); };
  if (walls) {
    v.until = v.end_reached;
    v.reason = "the fastest wave from the interface (speed " + text(fastest) +
               ") reaches the wall at |x| = " + text(L) + " at t = " + text(v.until);
    return v;
  }
  double f_min = right.velocity - sound_speed(right, s.gamma);
  double f_max = left.velocity + sound_speed(left, s.gamma);
  try {
    const RiemannSolution far(right, left, s.gamma);
    f_min = far.left_wave().head_speed;
    f_max = far.right_wave().head_speed;
  } catch (const Error&) {
    // the far interface opens a vacuum: its fans' heads, the sound speeds, bound its waves
  }
  const double inf = std::numeric_limits<double>::infinity();
  const double reach = std::max(L - window, 0.0);
  v.until = std::min({f_min < 0 ? reach / -f_min : inf, f_max > 0 ? reach / f_max : inf,
                      c_max > f_min ? L / (c_max - f_min) : inf,
                      f_max > c_min ? L / (f_max - c_min) : inf});
  v.reason = "the waves of the far interface at x = ±" + text(L) + " (speeds " + text(f_min) +
             " and " + text(f_max) + ") reach the window |x| <= " + text(window) +
             " or meet the waves from the centre at t = " + text(v.until) +
             "; the fastest wave from the centre (speed " + text(fastest) +
             ") reaches the tube's periodic end at t = " + text(v.end_reached);
  return v;
}

/// The x-velocity of every particle (the quantity the exact solution knows).
template <int D>
std::vector<double> x_velocity(const Particles<D>& p) {
  std::vector<double> v(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) v[i] = p.velocity[i][0];
  return v;
}

/// L1, L2, Linf of rho, v_x and P against the exact solution at time t, in the window.
template <int D>
std::vector<ErrorNorms> shock_tube_errors(const Particles<D>& p, const RiemannSolution& exact,
                                          double t, const Selection& window = shock_tube_window()) {
  auto at = [&](const Vec<D>& x) { return exact.sample(x[0], t); };
  return {
      error_norms<D>(
          "rho", p.position, p.density, [&](const Vec<D>& x) { return at(x).density; }, window),
      error_norms<D>(
          "v", p.position, x_velocity(p), [&](const Vec<D>& x) { return at(x).velocity; }, window),
      error_norms<D>(
          "P", p.position, p.pressure, [&](const Vec<D>& x) { return at(x).pressure; }, window)};
}

/// The same as a Measurement for an error-against-run-time study: L1(rho), L1(v), L1(P).
template <int D>
Measurement shock_tube_measurement(const Particles<D>& p, const RiemannSolution& exact, double t,
                                   double spacing) {
  Measurement m;
  m.resolution = spacing;
  for (const ErrorNorms& e : shock_tube_errors(p, exact, t))
    m.errors.push_back({"L1(" + e.quantity + ")", e.L1});
  return m;
}

}  // namespace sph
