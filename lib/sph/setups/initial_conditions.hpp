#pragma once
/// \file
/// \brief Initial conditions: lattices, cuts, disturbances, random sets, and masses that make the
/// SPH density equal the density we intend.
///
/// A particle set is built in three steps, each a short function here:
///   1. **positions**: a lattice filling a box (cubic, body-centred; in 2D also hexagonal), a
///      uniform random set, or a settled set (sph/setups/relax.hpp);
///   2. **shape**: keep the points inside a sphere or a box (cut_sphere, cut_box), move them a
///      little (disturb);
///   3. **particles**: give each point a mass (make_particles), and, where the density must be
///      exact, calibrate the masses against the SPH density itself (calibrate_mass_to_density).
///
/// Random numbers come from a SplitMix64 generator of our own (not std::uniform_real_distribution,
/// whose algorithm differs between standard libraries), so a seed gives the same set everywhere.
///
/// A generator that puts two particles on the same spot is a bug: the kernel gradient vanishes at
/// r = 0, so nothing would ever push them apart.  require_distinct_positions finds such pairs.

#include "sph/box.hpp"
#include "sph/density.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

namespace sph {

// ---------------------------------------------------------------------------------------------
// Random numbers
// ---------------------------------------------------------------------------------------------

/// SplitMix64 (Steele, Lea & Flood 2014): a small, fast generator with a fixed algorithm, so a
/// seed gives the same numbers with every compiler and standard library.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}

  /// The next 64 random bits.
  std::uint64_t bits() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }
  /// Uniform in [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }

 private:
  std::uint64_t state_;
};

// ---------------------------------------------------------------------------------------------
// Lattices
// ---------------------------------------------------------------------------------------------

/// The lattices we can fill a box with.
enum class LatticeType {
  cubic,         ///< one point per cubic cell, at its centre (2D: square; 1D: evenly spaced)
  body_centred,  ///< two points per cubic cell, at 1/4 and 3/4 of its diagonal (2D: centred square)
  hexagonal,     ///< 2D only: rows of points one spacing apart, alternate rows shifted by half
};

/// The name of a lattice type, for tables and figure legends.
inline const char* lattice_name(LatticeType type) {
  switch (type) {
    case LatticeType::cubic:
      return "cubic";
    case LatticeType::body_centred:
      return "body-centred cubic";
    case LatticeType::hexagonal:
      return "hexagonal";
  }
  return "?";
}

/// Points of a lattice per cell: 1 (cubic, hexagonal) or 2 (body-centred).
inline int points_per_cell(LatticeType type) { return type == LatticeType::body_centred ? 2 : 1; }

/// A lattice filling the box [lower, upper) exactly, with `cells[a]` cells along axis a.
///
/// Because the number of cells is a whole number on every axis, the lattice tiles a periodic box
/// without a seam.  Cubic: one point at each cell centre.  Body-centred: points at 1/4 and 3/4 of
/// each cell's diagonal, so both sub-lattices sit symmetrically in the box.  Hexagonal (2D): a
/// cell is one point of one row; `cells[1]` rows must be even to be periodic, and the lattice is
/// regular (all nearest neighbours equidistant) only if the row spacing is \f$ \sqrt3/2 \f$ times
/// the point spacing -- choose the box or use lattice() for that.
template <int D>
std::vector<Vec<D>> lattice(LatticeType type, const Vec<D>& lower, const Vec<D>& upper,
                            const std::array<int, D>& cells) {
  require(type != LatticeType::hexagonal || D == 2,
          "lattice: the hexagonal lattice exists only in 2D");
  std::size_t count = static_cast<std::size_t>(points_per_cell(type));
  Vec<D> cell_size;
  for (int a = 0; a < D; ++a) {
    require(cells[a] >= 1, std::string("lattice: need at least one cell along ") + axis_name(a));
    require(upper[a] > lower[a], std::string("lattice: the box is empty along ") + axis_name(a));
    cell_size[a] = (upper[a] - lower[a]) / cells[a];
    count *= static_cast<std::size_t>(cells[a]);
  }
  // The positions of the lattice's points inside one cell, in units of the cell.
  std::vector<Vec<D>> basis;
  if (type == LatticeType::body_centred) {
    basis = {Vec<D>::Constant(0.25), Vec<D>::Constant(0.75)};
  } else {
    basis = {Vec<D>::Constant(0.5)};
  }
  std::vector<Vec<D>> points;
  points.reserve(count);
  std::array<int, D> index{};
  while (true) {
    // One cell: its corner, then each basis point (hexagonal: odd rows shifted half a cell).
    Vec<D> corner;
    for (int a = 0; a < D; ++a) corner[a] = lower[a] + index[a] * cell_size[a];
    for (const Vec<D>& b : basis) {
      Vec<D> x = corner + b.cwiseProduct(cell_size);
      if (type == LatticeType::hexagonal && index[D - 1] % 2 == 1) x[0] += 0.5 * cell_size[0];
      if (type == LatticeType::hexagonal && x[0] >= upper[0]) x[0] -= upper[0] - lower[0];
      points.push_back(x);
    }
    // Advance the odometer over the cells (x fastest).
    int a = 0;
    while (a < D && index[a] == cells[a] - 1) index[a++] = 0;
    if (a == D) break;
    ++index[a];
  }
  return points;
}

/// The number of cells along each axis for a lattice of (about) the given spacing in the box:
/// the nearest whole number, at least one (hexagonal rows: the nearest even number, spaced
/// \f$ \sqrt3/2 \f$ of the point spacing).  The spacing realised is the box length divided by it,
/// within half a cell of the request.
///
/// `spacing` is the side of the cubic cell: for the cubic lattice the distance between
/// neighbours, for the body-centred lattice the cell holding two points, for the hexagonal
/// lattice the distance between neighbours in a row.
template <int D>
std::array<int, D> lattice_cells(LatticeType type, const Vec<D>& lower, const Vec<D>& upper,
                                 double spacing) {
  require(std::isfinite(spacing) && spacing > 0,
          "lattice: the spacing must be positive and finite");
  std::array<int, D> cells{};
  for (int a = 0; a < D; ++a) {
    double step = spacing;
    if (type == LatticeType::hexagonal && a == 1) step = spacing * std::sqrt(3.0) / 2.0;
    const double n = std::round((upper[a] - lower[a]) / step);
    require(n < 1e7, "lattice: more than 10^7 cells along one axis");
    cells[a] = std::max(1, static_cast<int>(n));
    if (type == LatticeType::hexagonal && a == 1 && cells[a] % 2 == 1) ++cells[a];
  }
  return cells;
}

/// A lattice of about the given spacing filling the box exactly (see lattice_cells).
template <int D>
std::vector<Vec<D>> lattice(LatticeType type, const Vec<D>& lower, const Vec<D>& upper,
                            double spacing) {
  return lattice<D>(type, lower, upper, lattice_cells<D>(type, lower, upper, spacing));
}

// ---------------------------------------------------------------------------------------------
// Shapes and disturbances
// ---------------------------------------------------------------------------------------------

/// The points with \f$ |\mathbf x - \mathbf c| < R \f$ (a sphere, disc or rod cut from a set).
template <int D>
std::vector<Vec<D>> cut_sphere(const std::vector<Vec<D>>& points, const Vec<D>& centre,
                               double radius) {
  require(radius > 0, "cut_sphere: the radius must be positive");
  std::vector<Vec<D>> kept;
  for (const Vec<D>& x : points) {
    if ((x - centre).squaredNorm() < radius * radius) kept.push_back(x);
  }
  return kept;
}

/// The points with lower <= x < upper on every axis.
template <int D>
std::vector<Vec<D>> cut_box(const std::vector<Vec<D>>& points, const Vec<D>& lower,
                            const Vec<D>& upper) {
  std::vector<Vec<D>> kept;
  for (const Vec<D>& x : points) {
    bool inside = true;
    for (int a = 0; a < D; ++a) inside = inside && x[a] >= lower[a] && x[a] < upper[a];
    if (inside) kept.push_back(x);
  }
  return kept;
}

/// Move every point by an independent uniform random offset in \f$ [-A, A) \f$ on each axis
/// (Selhammar 1997 §5: "a slightly disturbed lattice"), then wrap it into the box on the box's
/// periodic axes.  Keep A below half the spacing so that no two points can meet.
template <int D>
void disturb(std::vector<Vec<D>>& points, double amplitude, std::uint64_t seed,
             const Box<D>& box = Box<D>::open()) {
  require(std::isfinite(amplitude) && amplitude >= 0,
          "disturb: the amplitude must be non-negative");
  Random random(seed);
  for (Vec<D>& x : points) {
    for (int a = 0; a < D; ++a) x[a] += random.uniform(-amplitude, amplitude);
    x = box.wrap(x);
  }
}

/// A ball of exactly n points: the body-centred lattice whose cell holds two points per
/// \f$ 2V/n \f$ (V the ball's volume), each coordinate moved by up to `disturbance` of the
/// spacing, and the n points nearest the centre kept, sorted by their distance from it (ties in
/// lattice order).  Selhammar's "slightly disturbed cubic centred grid" of his spheres
/// (sect. 5.2 and 5.3); the homologous sphere and the Evrard sphere start from it.
inline std::vector<Vec<3>> disturbed_lattice_ball(int n, double radius, double disturbance,
                                                  std::uint64_t seed) {
  require(n >= 1, "disturbed_lattice_ball: need at least one point");
  require(std::isfinite(radius) && radius > 0,
          "disturbed_lattice_ball: the radius must be positive and finite");
  require(disturbance >= 0 && disturbance < 0.5,
          "disturbed_lattice_ball: the disturbance must lie in [0, 0.5) of the spacing");
  const double volume = 4.0 / 3.0 * std::numbers::pi * std::pow(radius, 3) / n;
  const double spacing = std::cbrt(2 * volume);  // the body-centred cell holds two points
  const int half = static_cast<int>(std::ceil(1.3 * radius / spacing));
  const double side = half * spacing;
  auto points =
      lattice<3>(LatticeType::body_centred, Vec<3>::Constant(-side), Vec<3>::Constant(side),
                 std::array<int, 3>{2 * half, 2 * half, 2 * half});
  disturb<3>(points, disturbance * spacing, seed);
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return points[a].squaredNorm() < points[b].squaredNorm();
  });
  std::vector<Vec<3>> kept(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) kept[k] = points[order[k]];
  return kept;
}

/// n equal masses (total 1) at random in the unit ball; with `cusp`, each radius r is mapped to
/// r^(3/2), which turns the uniform density into one proportional to 1/r (the mass inside r
/// goes from r^3 to r^2), the profile of the Evrard collapse.  Each particle's h is set from the
/// density at its radius so that about `neighbours` particles lie within 2h: the sphere on
/// which the gravity modules are measured (tests, bench), without a density pass.
inline Particles<3> random_ball(std::size_t n, std::uint64_t seed, bool cusp,
                                double neighbours = 64) {
  require(n >= 1 && neighbours > 0, "random_ball: need n >= 1 and a positive neighbour number");
  constexpr double pi = std::numbers::pi;
  Random random(seed);
  Particles<3> p;
  while (p.size() < n) {
    Vec<3> x(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
    const double r = x.norm();
    if (r >= 1 || r == 0) continue;
    if (cusp) x *= std::sqrt(r);
    p.add(x, Vec<3>::Zero(), 1.0 / static_cast<double>(n));
  }
  for (std::size_t i = 0; i < n; ++i) {
    // number density: n / (4 pi / 3) uniform, n / (2 pi r) for the 1/r profile
    const double r = std::max(p.position[i].norm(), 1e-3);
    const double density =
        cusp ? static_cast<double>(n) / (2 * pi * r) : static_cast<double>(n) / (4.0 / 3.0 * pi);
    p.smoothing_length[i] = 0.5 * std::cbrt(neighbours / (4.0 / 3.0 * pi * density));
  }
  return p;
}

/// Put points that are near in space near in memory: sort them by cells of size `cell`, the
/// first axis slowest, then the second, ... (stable: the order inside a cell is kept).  A pass
/// over neighbours reads each neighbour's fields from the particle arrays, and when the
/// particles of a neighbourhood sit close together in those arrays the reads hit the cache.
/// lattice() counts x fastest, so along a tube the neighbours of a particle lie a whole
/// cross-section apart in memory; ordered by cells of about the kernel support, the 3D Sod
/// step is 3 % faster (bench, 2 threads).  Only the order changes (the results only by
/// round-off, through the order of the sums).
template <int D>
void order_by_cells(std::vector<Vec<D>>& points, double cell) {
  require(std::isfinite(cell) && cell > 0,
          "order_by_cells: the cell size must be positive and finite");
  if (points.empty()) return;
  const Vec<D> lo = bounds<D>(points).lo;
  std::vector<std::array<long, D>> key(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < D; ++a)
      key[i][a] = static_cast<long>(std::floor((points[i][a] - lo[a]) / cell));
  }
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&key](std::size_t i, std::size_t j) { return key[i] < key[j]; });
  std::vector<Vec<D>> sorted(points.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted[k] = points[order[k]];
  points = std::move(sorted);
}

/// n points drawn independently and uniformly in [lower, upper): a Poisson set, the
/// "random, unsettled" distribution of Watkins et al. (1996, §3, Fig. 3).
template <int D>
std::vector<Vec<D>> uniform_random(const Vec<D>& lower, const Vec<D>& upper, std::size_t n,
                                   std::uint64_t seed) {
  for (int a = 0; a < D; ++a) {
    require(upper[a] > lower[a],
            std::string("uniform_random: the box is empty along ") + axis_name(a));
  }
  Random random(seed);
  std::vector<Vec<D>> points(n);
  for (Vec<D>& x : points) {
    for (int a = 0; a < D; ++a) x[a] = random.uniform(lower[a], upper[a]);
  }
  return points;
}

/// Throw sph::Error naming the first two points closer than `min_separation` (by default:
/// exactly coincident).  On a periodic box the distance is measured to the nearest image.
/// Costs a cell-grid pass, O(N).
template <int D>
void require_distinct_positions(const std::vector<Vec<D>>& points,
                                const Box<D>& box = Box<D>::open(), double min_separation = 0.0) {
  if (points.size() < 2) return;
  require(std::isfinite(min_separation) && min_separation >= 0,
          "require_distinct_positions: the minimum separation must be non-negative");
  // Sort an index by cell (exact duplicates are caught by a lexicographic sort when the
  // separation is zero; a cell grid of that size handles the general case).
  if (min_separation == 0.0) {
    std::vector<std::size_t> order(points.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    auto less = [&](std::size_t i, std::size_t j) {
      for (int a = 0; a < D; ++a) {
        if (points[i][a] != points[j][a]) return points[i][a] < points[j][a];
      }
      return i < j;
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t k = 1; k < order.size(); ++k) {
      const std::size_t i = std::min(order[k - 1], order[k]), j = std::max(order[k - 1], order[k]);
      require(points[i] != points[j], "initial conditions: particles " + show(i) + " and " +
                                          show(j) + " coincide at " + to_string<D>(points[i]));
    }
    return;
  }
  CellGrid<D> grid;
  std::vector<Vec<D>> wrapped(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) wrapped[i] = box.wrap(points[i]);
  grid.build(wrapped, box, min_separation);
  for (std::size_t i = 0; i < wrapped.size(); ++i) {
    grid.for_each_within(
        wrapped[i], min_separation, [&](std::uint32_t j, Image image, const Vec<D>&, double r2) {
          if (j == i && image == 0) return;
          require(false, "initial conditions: particles " + show(std::min<std::size_t>(i, j)) +
                             " and " + show(std::max<std::size_t>(i, j)) + " are " +
                             show(std::sqrt(r2)) + " apart, closer than " + show(min_separation) +
                             ", at " + to_string<D>(points[i]));
        });
  }
}

// ---------------------------------------------------------------------------------------------
// Particles and masses
// ---------------------------------------------------------------------------------------------

/// Particles at the given points, each of mass `mass`, at rest, with internal energy
/// `internal_energy` and no smoothing length yet (the neighbour search chooses it).
template <int D>
Particles<D> make_particles(const std::vector<Vec<D>>& points, double mass,
                            double internal_energy = 0.0) {
  require(!points.empty(), "make_particles: no points");
  require(std::isfinite(mass) && mass > 0,
          "make_particles: the mass must be positive and finite (got " + show(mass) + ")");
  Particles<D> p;
  p.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    p.position[i] = points[i];
    p.mass[i] = mass;
    p.internal_energy[i] = internal_energy;
  }
  return p;
}

/// The mass of each of n equal particles that together fill `volume` at `density`.
inline double equal_mass(double density, double volume, std::size_t n) {
  require(density > 0 && volume > 0 && n > 0,
          "equal_mass: density, volume and count must be positive");
  return density * volume / static_cast<double>(n);
}

/// What calibrate_mass_to_density did.
struct MassCalibration {
  int iterations = 0;              ///< sweeps of the mass update
  double initial_error = 0;        ///< max_i |rho_i / rho_target(x_i) - 1| before
  double final_error = 0;          ///< the same after
  std::size_t worst_particle = 0;  ///< where final_error is reached
};

/// Scale the masses so that the SPH density equals the density we intend, to round-off.
///
/// **Why.**  An SPH sum over a lattice is not the continuum integral it approximates: on a cubic
/// lattice of spacing \f$ \Delta x \f$ the M4 kernel gives \f$ \sum_j m W_{ij} \ne m/\Delta x^D \f$
/// (in 1D +0.18 % at \f$ h = 1.2\Delta x \f$; chapter 2 tabulates the bias).  A scene that sets
/// \f$ m = \rho\,\Delta x^D \f$ therefore starts with the wrong density, and through the equation
/// of state with the wrong pressure: a shock tube begins with small pressure jumps that never go
/// away, and the error floor of a convergence study is this bias.  The cure is to measure the
/// kernel sum on the actual particle set and divide it out.
///
/// **How.**  With the neighbour list and smoothing lengths fixed, the density is linear in the
/// masses, \f$ \rho_i = \sum_j A_{ij} m_j \f$.  We solve \f$ \rho_i = \rho_{\rm target}(\mathbf
/// x_i) \f$ by the multiplicative update
/// \f[ m_i \leftarrow m_i\, \frac{\rho_{\rm target}(\mathbf x_i)}{\rho_i}, \f]
/// which keeps every mass positive.  On a uniform lattice (all particles alike) one sweep is
/// exact: it is \f$ m = \rho_{\rm target} / \sum_j W_{ij} \f$.  Where the particles of each
/// region are alike -- two lattices meeting at a density jump, with the pair-averaged sum -- the
/// update converges geometrically.  It does not always: it is a Jacobi-like iteration for a
/// linear system whose matrix is the kernel itself, so on a disordered set (a glass) it is a
/// deconvolution that converges slowly while the masses scatter more and more (use
/// calibrate_mean_density there), and with the gather sum and different h on the two sides of a
/// jump the target may not be reachable at all.  We stop when the largest relative error falls
/// below `tolerance` or after `max_iterations` sweeps, and report the error reached: it is the
/// caller's decision whether that is good enough.
///
/// The smoothing lengths are not changed: use a fixed h or the neighbour-number rule, which do
/// not depend on the masses.  (With the density rule, h depends on m; call the search again
/// afterwards and, if needed, calibrate again.)
///
/// `target(x)` is the intended density at position x.
template <int D, class K = Kernel<D>, class Target>
MassCalibration calibrate_mass_to_density(Particles<D>& p, const NeighbourList<D>& list,
                                          Target&& target,
                                          DensityForm form = DensityForm::selhammar(),
                                          int max_iterations = 100, double tolerance = 1e-13) {
  require(list.particles() == p.size(), "calibrate_mass_to_density: the neighbour list is for " +
                                            show(list.particles()) + " particles, the set has " +
                                            show(p.size()));
  const std::size_t n = p.size();
  std::vector<double> wanted(n);
  for (std::size_t i = 0; i < n; ++i) {
    wanted[i] = target(p.position[i]);
    require(std::isfinite(wanted[i]) && wanted[i] > 0,
            "calibrate_mass_to_density: the target density at particle " + show(i) + " is " +
                show(wanted[i]) + " (must be positive)");
  }
  // The largest relative error of the current density, and where it is.
  auto worst = [&](MassCalibration& report) {
    double e = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double d = std::abs(p.density[i] / wanted[i] - 1.0);
      if (d > e || !std::isfinite(d)) {
        e = d;
        report.worst_particle = i;
      }
    }
    return e;
  };
  MassCalibration report;
  compute_density<D, K>(p, list, form);
  report.initial_error = report.final_error = worst(report);
  while (report.final_error > tolerance && report.iterations < max_iterations) {
    for (std::size_t i = 0; i < n; ++i) p.mass[i] *= wanted[i] / p.density[i];
    compute_density<D, K>(p, list, form);
    ++report.iterations;
    report.final_error = worst(report);
  }
  return report;
}

/// Scale all masses by one factor so that the *mean* SPH density over the particles equals
/// `target`; returns the factor.  This removes the bias of a disordered set (a glass) without
/// touching its scatter -- the per-particle calibration above would try to remove the scatter
/// too, which on a disordered set is a deconvolution of the kernel: it converges slowly and
/// turns density noise into larger mass noise (chapter 2 shows it).  Needs p.density.
template <int D>
double calibrate_mean_density(Particles<D>& p, double target) {
  require(std::isfinite(target) && target > 0,
          "calibrate_mean_density: the target must be positive");
  require(p.density.size() == p.size() && p.size() > 0,
          "calibrate_mean_density: compute the density first");
  double mean = 0;
  for (double rho : p.density) mean += rho / static_cast<double>(p.size());
  require(std::isfinite(mean) && mean > 0,
          "calibrate_mean_density: the mean density is not positive");
  const double factor = target / mean;
  for (double& m : p.mass) m *= factor;
  for (double& rho : p.density) rho *= factor;  // the density is linear in the masses
  return factor;
}

/// The same with one target density everywhere.
template <int D, class K = Kernel<D>>
MassCalibration calibrate_mass_to_density(Particles<D>& p, const NeighbourList<D>& list,
                                          double target,
                                          DensityForm form = DensityForm::selhammar(),
                                          int max_iterations = 100, double tolerance = 1e-13) {
  return calibrate_mass_to_density<D, K>(
      p, list, [target](const Vec<D>&) { return target; }, form, max_iterations, tolerance);
}

}  // namespace sph
