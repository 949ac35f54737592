#pragma once
/// \file
/// \brief A one-dimensional Lagrangian hydrodynamics code: the reference solution of the SPH
/// scenes with planar or spherical symmetry (shock tubes with free ends, a compressing sphere,
/// the Evrard collapse).
///
/// **Why Lagrangian.**  In one dimension a mesh can move with the gas.  Each zone is a fixed
/// parcel of mass between two nodes, and the mass coordinate, not the position, labels the
/// gas.  The continuity equation is then exact, \f$ \rho = m/V \f$: no mass crosses a zone
/// edge, there is no advection term and so no advection error, and a contact discontinuity
/// sits on one node for ever instead of being smeared.  Shocks still need dissipation (below),
/// and a contact that forms at t = 0 keeps a small entropy blip in its first zones ("wall
/// heating"), but nothing else is diffused.  The method shares nothing with SPH -- no kernel,
/// no neighbours, no smoothing length -- which is why it can referee SPH: where the two agree,
/// both are right, and at high resolution this code converges to the exact solution.
///
/// **The mesh** is staggered: N zones i = 0..N-1 lie between N+1 nodes k = 0..N.  A node has
/// a position \f$ r_k \f$ and a velocity \f$ u_k \f$; a zone has a fixed mass \f$ m_i \f$, a
/// specific internal energy \f$ e_i \f$ and a volume
/// \f[ V_i = \mathcal V(r_{i+1}) - \mathcal V(r_i), \qquad
///     \mathcal V(r) = r,\ \pi r^2,\ \tfrac43\pi r^3, \qquad
///     A(r) = \mathcal V'(r) = 1,\ 2\pi r,\ 4\pi r^2 \f]
/// for slabs (per unit area), cylindrical shells (per unit length) and spherical shells; so
/// \f$ \rho_i = m_i/V_i \f$ and the ideal gas gives \f$ P_i = (\gamma - 1)\rho_i e_i \f$ and
/// \f$ c_i = \sqrt{\gamma(\gamma-1)e_i} \f$.  Node k carries half of each neighbouring zone,
/// \f$ \mu_k = \tfrac12(m_{k-1} + m_k) \f$.
///
/// **Forces.**  With \f$ \Pi_i = P_i + q_i \f$ (q the artificial viscosity), zone i pushes its
/// outer node with \f$ +\Pi_i A(r_{i+1}) \f$ and its inner node with \f$ -\Pi_i A(r_i) \f$
/// (the "corner forces"), so the momentum equation of a node is
/// \f[ \mu_k \dot u_k = A(r_k)\,(\Pi_{k-1} - \Pi_k) + \mu_k g_k . \f]
/// These are \f$ -\partial/\partial r_k \f$ of \f$ \sum_i m_i e_i \f$ when each zone changes
/// adiabatically: the discrete \f$ \rho^{-1}\partial P/\partial r \f$.
///
/// **Compatible energy update** (Caramana, Burton, Shashkov & Whalen, J. Comput. Phys. 146,
/// 227, 1998).  The internal energy is not integrated from its own equation but from the work
/// of the same corner forces that moved the nodes, evaluated with the same velocity
/// \f$ \bar u_k = \tfrac12(u_k^n + u_k^{n+1}) \f$ that moves them:
/// \f[ \mu_k (u_k^{n+1} - u_k^n) = \Delta t\, F_k^{n+1/2}, \qquad
///     r_k^{n+1} = r_k^n + \Delta t\,\bar u_k, \f]
/// \f[ m_i (e_i^{n+1} - e_i^n) = -\Delta t\,\Pi_i^{n+1/2}
///     \left[A(r_{i+1}^{n+1/2})\,\bar u_{i+1} - A(r_i^{n+1/2})\,\bar u_i\right]. \f]
/// Since \f$ \tfrac12\mu_k[(u_k^{n+1})^2 - (u_k^n)^2] = \Delta t\,F_k\,\bar u_k \f$, every corner
/// force's work enters the kinetic energy once and the internal energy once with the opposite
/// sign: \f$ E_\mathrm{kin} + E_\mathrm{th} \f$ is conserved to round-off, for any \f$ \Pi \f$
/// and any \f$ \Delta t \f$.  The scheme is their predictor-corrector, second order in time:
///  1. predictor: \f$ r^{n+1/2} = r^n + \tfrac12\Delta t\,u^n \f$,
///     \f$ u^{n+1/2} = u^n + \tfrac12\Delta t\,a^n \f$ (used only by q), and
///     \f$ e_i^{n+1/2} = e_i^n - \Pi_i^n (V_i^{n+1/2} - V_i^n)/m_i \f$, which give
///     \f$ \Pi^{n+1/2} \f$ and the forces \f$ F^{n+1/2} \f$;
///  2. corrector: the three updates above.
///
/// **Boundaries.**  A free end has vacuum outside, \f$ \Pi = 0 \f$ beyond the end node, and
/// moves; a wall holds its node at rest, \f$ u = 0 \f$; the centre of a sphere or a cylinder is
/// a node held at r = 0 (where A = 0, so it feels no force anyway).
///
/// **Artificial viscosity.**  The von Neumann-Richtmyer quadratic term (J. Appl. Phys. 21,
/// 232, 1950) plus Landshoff's linear term (Los Alamos report LA-1930, 1955), in the form of
/// Wilkins (J. Comput. Phys. 36, 281, 1980), acting only in compressing zones:
/// \f[ q_i = \rho_i\left(c_q^2\,\Delta u_i^2 + c_l\,c_i\,|\Delta u_i|\right)
///     \ \text{ if } \Delta u_i = u_{i+1} - u_i < 0, \qquad q_i = 0 \text{ otherwise}, \f]
/// with \f$ c_q = 2 \f$, \f$ c_l = 0.1 \f$ by default.  It is dissipative: q only resists
/// compression, and its work goes into heat (Caramana, Shashkov & Whalen, J. Comput. Phys. 144,
/// 70, 1998, set out the criteria a viscosity must meet).  It does not tell a shock from a
/// smooth compression: a homologous collapse is heated too.  But in a smooth flow
/// \f$ \Delta u \propto \Delta r \f$, so q falls as \f$ \Delta r \f$ (linear term) and
/// \f$ \Delta r^2 \f$ (quadratic term) under refinement, and at high resolution the reference
/// converges to the inviscid solution away from shocks.  It can be switched off for flows
/// without shocks.
///
/// **Self-gravity** (spherical only).  Node k feels the mass of the zones inside it,
/// \f$ M_k = \sum_{i<k} m_i \f$, as a point mass: \f$ g_k = -G M_k/r_k^2 \f$.  This is the exact
/// force of the discrete potential energy
/// \f[ W = -G \sum_k \frac{M_k\,\mu_k}{r_k}, \f]
/// because \f$ M_k \f$ and \f$ \mu_k \f$ do not change (continuum: \f$ W = -\int G M(r)\,dm/r \f$;
/// for the Evrard sphere \f$ W \to -\tfrac23 GM^2/R \f$).  To conserve
/// \f$ E_\mathrm{kin} + E_\mathrm{th} + W \f$ to round-off as well, the corrector uses
/// \f$ -G M_k \mu_k/(r_k^n r_k^{n+1}) \f$, a second-order approximation of the force at
/// \f$ t^{n+1/2} \f$ whose work is exactly \f$ -(W^{n+1} - W^n) \f$ since
/// \f$ 1/r^n - 1/r^{n+1} = (r^{n+1} - r^n)/(r^n r^{n+1}) \f$.  It depends on
/// \f$ r^{n+1} = r^n + \Delta t\,\bar u \f$, which makes the node update a quadratic equation,
/// \f$ x^2 - bx + c = 0 \f$ with \f$ x = r_k^{n+1} \f$,
/// \f$ b = r_k^n + \Delta t\,u_k^n + \tfrac12\Delta t^2 F_k/\mu_k \f$ and
/// \f$ c = \tfrac12\Delta t^2 G M_k/r_k^n \f$, solved in closed form by the root that tends to
/// b as \f$ \Delta t \to 0 \f$.
///
/// **Time step.**  The smallest over zones of
/// \f$ C\,\Delta r_i/(c_i + |\Delta u_i| + 2 q_i/(\rho_i|\Delta u_i|)) \f$ (sound crossing,
/// the zone's own compression, and the diffusion limit of q; the last two only where
/// \f$ \Delta u_i < 0 \f$) and over moving nodes of \f$ C\sqrt{\Delta r/|a_k|} \f$ with
/// \f$ \Delta r \f$ the narrower neighbouring zone (it limits the step of a cold gas in free
/// fall), with C = 0.3 by default.
///
/// **Failure** is never silent: a zone whose nodes cross (negative volume), a negative
/// internal energy or a number that is not finite throws sph::Error naming the zone, the time
/// and the quantity, and the state is left as it was before the failed step.
///
/// The accuracy is second order in space and time in smooth flow and first order at shocks,
/// as for every shock-capturing scheme.  The cost is a few tens of operations per zone and
/// step; the number of steps to a given time grows as N, so the cost as \f$ N^2 \f$.

#include "sph/error.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace sph {

/// The symmetry of a one-dimensional flow: what r means and what a zone's volume is.
enum class LagrangianGeometry {
  planar,       ///< slabs, per unit area: r is a Cartesian coordinate
  cylindrical,  ///< cylindrical shells, per unit length
  spherical,    ///< spherical shells
};

/// What holds an end of the mesh.
enum class LagrangianEnd {
  free,    ///< vacuum outside: P = q = 0 beyond the end node, which moves
  wall,    ///< a rigid wall: the end node stays at rest
  centre,  ///< the centre r = 0 (left end only): the node stays at r = 0
};

/// The von Neumann-Richtmyer + Landshoff artificial viscosity.
struct LagrangianViscosity {
  bool enabled = true;
  double quadratic = 2.0;  ///< c_q: q = rho (c_q^2 du^2 + c_l c |du|) in compression
  double linear = 0.1;     ///< c_l
};

/// Everything about a run except the initial data.
struct LagrangianOptions {
  double gamma = 5.0 / 3.0;                 ///< ideal gas, P = (gamma - 1) rho e
  LagrangianEnd left = LagrangianEnd::free;
  LagrangianEnd right = LagrangianEnd::free;
  LagrangianViscosity viscosity{};
  bool self_gravity = false;                ///< spherical only
  double gravitational_constant = 1.0;      ///< G
  double courant = 0.3;                     ///< C of the time step
  double max_dt = std::numeric_limits<double>::infinity();  ///< an upper bound on every step
  long max_steps = 10'000'000;              ///< run_until throws when one call needs more
};

/// The state at one time, zone by zone (zone centres) and node by node.
struct LagrangianProfile {
  double time = 0;
  std::vector<double> radius;           ///< zone centre, the midpoint of its two nodes
  std::vector<double> mass_coordinate;  ///< mass inside the zone centre (half the zone's own)
  std::vector<double> density;
  std::vector<double> pressure;
  std::vector<double> internal_energy;  ///< e, per unit mass
  std::vector<double> velocity;         ///< mean of the zone's two node velocities
  std::vector<double> viscous_pressure; ///< q
  std::vector<double> node_radius;      ///< N + 1 node positions
  std::vector<double> node_velocity;    ///< N + 1 node velocities
};

namespace lagrangian_detail {

/// \f$ \mathcal V(b) - \mathcal V(a) \f$, factored so that a thin shell loses no digits.
inline double volume(LagrangianGeometry g, double a, double b) {
  switch (g) {
    case LagrangianGeometry::planar: return b - a;
    case LagrangianGeometry::cylindrical: return std::numbers::pi * (b - a) * (b + a);
    case LagrangianGeometry::spherical: break;
  }
  return 4.0 / 3.0 * std::numbers::pi * (b - a) * (b * b + a * b + a * a);
}

/// \f$ A(r) = \mathcal V'(r) \f$.
inline double area(LagrangianGeometry g, double r) {
  switch (g) {
    case LagrangianGeometry::planar: return 1.0;
    case LagrangianGeometry::cylindrical: return 2.0 * std::numbers::pi * r;
    case LagrangianGeometry::spherical: break;
  }
  return 4.0 * std::numbers::pi * r * r;
}

/// \f$ \int_a^b f(r) A(r)\,dr \f$ by 5-point Gauss-Legendre quadrature on `pieces` equal
/// sub-intervals (exact for polynomials of degree 9 on each); f is never called at a or b.
template <class F>
double integrate_over_volume(LagrangianGeometry g, double a, double b, int pieces, F&& f) {
  static constexpr double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831,
                                  -0.9061798459386640, 0.9061798459386640};
  static constexpr double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                  0.2369268850561891, 0.2369268850561891};
  const double h = (b - a) / pieces;
  double sum = 0;
  for (int p = 0; p < pieces; ++p) {
    const double mid = a + (p + 0.5) * h;
    for (int j = 0; j < 5; ++j) {
      const double r = mid + 0.5 * h * x[j];
      sum += w[j] * f(r) * area(g, r);
    }
  }
  return 0.5 * h * sum;
}

inline const char* name(LagrangianEnd end) {
  switch (end) {
    case LagrangianEnd::free: return "free";
    case LagrangianEnd::wall: return "wall";
    case LagrangianEnd::centre: break;
  }
  return "centre";
}

}  // namespace lagrangian_detail

/// The one-dimensional Lagrangian solver.  Set it up from zones or from profiles, then step.
///
/// \code
/// sph::LagrangianOptions o;                       // gamma 5/3, free ends, q on
/// o.left = sph::LagrangianEnd::centre;            // a sphere from r = 0
/// auto edges = sph::Lagrangian1D::equal_mass_edges(sph::LagrangianGeometry::spherical, 0, 1,
///     400, [](double) { return 0.75 / std::numbers::pi; });
/// auto sphere = sph::Lagrangian1D::from_profile(sph::LagrangianGeometry::spherical, edges,
///     [](double) { return 0.75 / std::numbers::pi; }, [](double r) { return -2 * r; },
///     [](double) { return 1e-3; }, o);
/// sphere.run_until(0.4, [](const sph::Lagrangian1D& s) { /* s.density(0), s.time() */ });
/// \endcode
class Lagrangian1D {
 public:
  using Geometry = LagrangianGeometry;
  using End = LagrangianEnd;
  using Profile = std::function<double(double)>;
  using Callback = std::function<void(const Lagrangian1D&)>;

  /// From zones: N + 1 node positions (increasing) and velocities, N zone masses and specific
  /// internal energies.  Throws sph::Error for bad input.
  Lagrangian1D(Geometry geometry, std::vector<double> node_radius,
               std::vector<double> node_velocity, std::vector<double> zone_mass,
               std::vector<double> zone_energy, const LagrangianOptions& options = {})
      : geometry_(geometry), options_(options), r_(std::move(node_radius)),
        u_(std::move(node_velocity)), m_(std::move(zone_mass)), e_(std::move(zone_energy)) {
    validate();
    const std::size_t N = m_.size();
    node_mass_.assign(N + 1, 0.0);
    inner_mass_.assign(N + 1, 0.0);
    for (std::size_t i = 0; i < N; ++i) {
      node_mass_[i] += 0.5 * m_[i];
      node_mass_[i + 1] += 0.5 * m_[i];
      inner_mass_[i + 1] = inner_mass_[i] + m_[i];
    }
    fixed_left_ = options_.left != End::free;
    fixed_right_ = options_.right != End::free;
    for (auto* v : {&Pi_, &c_, &Pi_half_, &e_half_, &e_new_}) v->assign(N, 0.0);
    for (auto* v : {&a_, &F_, &r_half_, &u_half_, &F_half_, &r_new_, &u_new_, &u_bar_})
      v->assign(N + 1, 0.0);
  }

  /// From functions of position: node velocities u(r_k); zone masses
  /// \f$ m_i = \int \rho\,dV \f$ and energies \f$ e_i = \int \rho e\,dV / m_i \f$ by Gauss
  /// quadrature inside each zone.  A profile with a jump needs an edge at the jump.
  static Lagrangian1D from_profile(Geometry geometry, std::vector<double> edges,
                                   const Profile& density, const Profile& velocity,
                                   const Profile& internal_energy,
                                   const LagrangianOptions& options = {}) {
    require(edges.size() >= 3, "Lagrangian1D: need at least 2 zones (3 edges), got " +
                                   show(static_cast<long>(edges.size())) + " edges");
    check_edges(geometry, edges);
    const std::size_t N = edges.size() - 1;
    std::vector<double> u(N + 1), m(N), e(N);
    for (std::size_t k = 0; k <= N; ++k) u[k] = velocity(edges[k]);
    for (std::size_t i = 0; i < N; ++i) {
      const auto rho = [&](double r) {
        const double value = density(r);
        require(std::isfinite(value) && value > 0.0,
                "Lagrangian1D: density(r) = " + show(value) + " at r = " + show(r) +
                    " (zone " + show(static_cast<long>(i)) + "); it must be positive and finite");
        return value;
      };
      const auto rho_e = [&](double r) {
        const double value = internal_energy(r);
        require(std::isfinite(value) && value > 0.0,
                "Lagrangian1D: internal energy e(r) = " + show(value) + " at r = " + show(r) +
                    " (zone " + show(static_cast<long>(i)) +
                    "); it must be positive and finite");
        return rho(r) * value;
      };
      m[i] = lagrangian_detail::integrate_over_volume(geometry, edges[i], edges[i + 1], 4, rho);
      e[i] = lagrangian_detail::integrate_over_volume(geometry, edges[i], edges[i + 1], 4, rho_e) /
             m[i];
    }
    return Lagrangian1D(geometry, std::move(edges), std::move(u), std::move(m), std::move(e),
                        options);
  }

  /// N + 1 equally spaced edges on [r_min, r_max].
  static std::vector<double> uniform_edges(double r_min, double r_max, int zones) {
    require(zones >= 1, "Lagrangian1D: uniform_edges needs at least one zone, got " + show(zones));
    require(std::isfinite(r_min) && std::isfinite(r_max) && r_max > r_min,
            "Lagrangian1D: uniform_edges needs finite r_min < r_max, got [" + show(r_min) + ", " +
                show(r_max) + "]");
    std::vector<double> edges(zones + 1);
    for (int k = 0; k <= zones; ++k) edges[k] = r_min + (r_max - r_min) * k / zones;
    edges[zones] = r_max;
    return edges;
  }

  /// Piecewise uniform edges: zones[j] equal zones on [breaks[j], breaks[j+1]], e.g.
  /// uniform_edges({-5, -4, 4}, {100, 800}) for two slabs with an edge at -4.
  static std::vector<double> uniform_edges(const std::vector<double>& breaks,
                                           const std::vector<int>& zones) {
    require(breaks.size() >= 2 && zones.size() + 1 == breaks.size(),
            "Lagrangian1D: uniform_edges needs one zone count per interval (" +
                show(static_cast<long>(breaks.size())) + " breaks, " +
                show(static_cast<long>(zones.size())) + " zone counts)");
    std::vector<double> edges{breaks.front()};
    for (std::size_t j = 0; j < zones.size(); ++j) {
      const std::vector<double> part = uniform_edges(breaks[j], breaks[j + 1], zones[j]);
      edges.insert(edges.end(), part.begin() + 1, part.end());
    }
    return edges;
  }

  /// Edges of `zones` zones of equal mass on [r_min, r_max] for the density profile rho(r):
  /// the cumulative mass is tabulated on 32 sub-cells per zone and inverted by bisection.
  /// For a uniform sphere from 0 this is \f$ r_k = R(k/N)^{1/3} \f$, for the Evrard sphere
  /// \f$ r_k = R\sqrt{k/N} \f$.
  static std::vector<double> equal_mass_edges(Geometry geometry, double r_min, double r_max,
                                              int zones, const Profile& density) {
    const std::vector<double> grid = uniform_edges(r_min, r_max, 32 * zones);
    require(geometry == Geometry::planar || r_min >= 0.0,
            "Lagrangian1D: a curved mesh needs r_min >= 0, got " + show(r_min));
    const auto rho = [&](double r) {
      const double value = density(r);
      require(std::isfinite(value) && value > 0.0,
              "Lagrangian1D: density(r) = " + show(value) + " at r = " + show(r) +
                  "; it must be positive and finite");
      return value;
    };
    const auto mass = [&](double a, double b) {
      return lagrangian_detail::integrate_over_volume(geometry, a, b, 1, rho);
    };
    std::vector<double> cumulative(grid.size(), 0.0);
    for (std::size_t j = 1; j < grid.size(); ++j)
      cumulative[j] = cumulative[j - 1] + mass(grid[j - 1], grid[j]);
    const double total = cumulative.back();
    std::vector<double> edges(zones + 1);
    edges[0] = r_min;
    edges[zones] = r_max;
    std::size_t cell = 0;
    for (int k = 1; k < zones; ++k) {
      const double target = total * k / zones;
      while (cumulative[cell + 1] < target) ++cell;
      double low = grid[cell], high = grid[cell + 1];
      for (int iteration = 0; iteration < 64; ++iteration) {  // cell width / 2^64: to round-off
        const double mid = 0.5 * (low + high);
        (cumulative[cell] + mass(grid[cell], mid) < target ? low : high) = mid;
      }
      edges[k] = 0.5 * (low + high);
    }
    return edges;
  }

  // --- running ---------------------------------------------------------------------------

  /// The step the stability and accuracy limits allow now (before max_dt); infinite for a
  /// cold gas at rest with no force.
  double stable_time_step() const {
    evaluate_now();
    return stable_dt_;
  }

  /// One step of min(stable_time_step(), max_dt); returns its length.
  double step() {
    const double dt = std::min(stable_time_step(), options_.max_dt);
    require(std::isfinite(dt), "Lagrangian1D: no time step limit at t = " + show(time_) +
                                   " (a cold gas at rest with no force); set max_dt");
    advance(dt);
    return dt;
  }

  /// One step of the given length (no stability check).
  void advance(double dt) {
    require(std::isfinite(dt) && dt > 0.0,
            "Lagrangian1D: time step dt = " + show(dt) + " (must be positive and finite)");
    evaluate_now();
    predictor(dt);
    corrector(dt);
    valid_ = false;
  }

  /// Steps until t_end, the last one shortened to land on it; `after_step` is called after
  /// each step.  Returns the number of steps; throws sph::Error after options.max_steps.
  long run_until(double t_end, const Callback& after_step = {}) {
    require(std::isfinite(t_end) && t_end >= time_,
            "Lagrangian1D: run_until(" + show(t_end) + ") from t = " + show(time_) +
                " (must be finite and not in the past)");
    long taken = 0;
    while (time_ < t_end) {
      require(taken < options_.max_steps,
              "Lagrangian1D: max_steps = " + show(options_.max_steps) + " reached at t = " +
                  show(time_) + " before t_end = " + show(t_end) + " (last dt " +
                  show(last_dt_) + ")");
      double dt = std::min(stable_time_step(), options_.max_dt);
      const double remaining = t_end - time_;
      const bool last = dt >= remaining * (1.0 - 1e-12);
      if (last) dt = remaining;
      advance(dt);
      if (last) time_ = t_end;
      ++taken;
      if (after_step) after_step(*this);
    }
    return taken;
  }

  // --- the state -------------------------------------------------------------------------

  Geometry geometry() const { return geometry_; }
  const LagrangianOptions& options() const { return options_; }
  double gamma() const { return options_.gamma; }
  double time() const { return time_; }
  long steps() const { return steps_; }
  double last_time_step() const { return last_dt_; }
  std::size_t zones() const { return m_.size(); }
  std::size_t nodes() const { return r_.size(); }

  const std::vector<double>& node_radius() const { return r_; }
  const std::vector<double>& node_velocity() const { return u_; }
  const std::vector<double>& zone_mass() const { return m_; }
  const std::vector<double>& zone_energy() const { return e_; }
  /// \f$ M_k = \sum_{i<k} m_i \f$, the mass inside node k.
  double mass_inside(std::size_t k) const { return inner_mass_.at(k); }

  double volume(std::size_t i) const { return lagrangian_detail::volume(geometry_, r_[i], r_[i + 1]); }
  double density(std::size_t i) const { return m_[i] / volume(i); }
  double pressure(std::size_t i) const { return (gamma() - 1.0) * density(i) * e_[i]; }
  double internal_energy(std::size_t i) const { return e_[i]; }
  double sound_speed(std::size_t i) const { return std::sqrt(gamma() * (gamma() - 1.0) * e_[i]); }
  /// q of zone i for the current velocities.
  double viscous_pressure(std::size_t i) const {
    return viscosity(density(i), sound_speed(i), u_[i + 1] - u_[i]);
  }
  double zone_centre(std::size_t i) const { return 0.5 * (r_[i] + r_[i + 1]); }

  // --- diagnostics -----------------------------------------------------------------------

  double total_mass() const { return inner_mass_.back(); }
  /// \f$ \sum_k \mu_k u_k \f$: conserved in planar geometry with free ends.
  double momentum() const {
    double sum = 0;
    for (std::size_t k = 0; k < r_.size(); ++k) sum += node_mass_[k] * u_[k];
    return sum;
  }
  /// \f$ \sum_k \tfrac12 \mu_k u_k^2 \f$.
  double kinetic_energy() const {
    double sum = 0;
    for (std::size_t k = 0; k < r_.size(); ++k) sum += 0.5 * node_mass_[k] * u_[k] * u_[k];
    return sum;
  }
  /// \f$ \sum_i m_i e_i \f$.
  double thermal_energy() const {
    double sum = 0;
    for (std::size_t i = 0; i < m_.size(); ++i) sum += m_[i] * e_[i];
    return sum;
  }
  /// \f$ W = -G\sum_k M_k\mu_k/r_k \f$, 0 without self-gravity.
  double potential_energy() const {
    if (!options_.self_gravity) return 0.0;
    double sum = 0;
    for (std::size_t k = 1; k < r_.size(); ++k) sum += inner_mass_[k] * node_mass_[k] / r_[k];
    return -options_.gravitational_constant * sum;
  }
  double total_energy() const { return kinetic_energy() + thermal_energy() + potential_energy(); }

  /// The profile at the current time.
  LagrangianProfile profile() const {
    LagrangianProfile p;
    const std::size_t N = zones();
    p.time = time_;
    p.node_radius = r_;
    p.node_velocity = u_;
    for (auto* v : {&p.radius, &p.mass_coordinate, &p.density, &p.pressure, &p.internal_energy,
                    &p.velocity, &p.viscous_pressure})
      v->resize(N);
    for (std::size_t i = 0; i < N; ++i) {
      p.radius[i] = zone_centre(i);
      p.mass_coordinate[i] = inner_mass_[i] + 0.5 * m_[i];
      p.density[i] = density(i);
      p.pressure[i] = pressure(i);
      p.internal_energy[i] = e_[i];
      p.velocity[i] = 0.5 * (u_[i] + u_[i + 1]);
      p.viscous_pressure[i] = viscous_pressure(i);
    }
    return p;
  }

 private:
  using Vector = std::vector<double>;

  static void check_edges(Geometry geometry, const Vector& r) {
    for (std::size_t k = 0; k < r.size(); ++k) {
      require(std::isfinite(r[k]), "Lagrangian1D: node " + show(static_cast<long>(k)) +
                                       " position is not finite (" + show(r[k]) + ")");
      if (k > 0)
        require(r[k] > r[k - 1], "Lagrangian1D: node positions must increase: node " +
                                     show(static_cast<long>(k)) + " at r = " + show(r[k]) +
                                     " is not beyond node " + show(static_cast<long>(k - 1)) +
                                     " at r = " + show(r[k - 1]));
    }
    require(geometry == Geometry::planar || r.front() >= 0.0,
            "Lagrangian1D: a cylindrical or spherical mesh needs r >= 0, the first node is at r = " +
                show(r.front()));
  }

  void validate() const {
    const LagrangianOptions& o = options_;
    require(std::isfinite(o.gamma) && o.gamma > 1.0,
            "Lagrangian1D: gamma = " + show(o.gamma) + " (must be finite and > 1)");
    require(std::isfinite(o.courant) && o.courant > 0.0 && o.courant <= 1.0,
            "Lagrangian1D: Courant number " + show(o.courant) + " (must be in (0, 1])");
    require(o.max_dt > 0.0, "Lagrangian1D: max_dt = " + show(o.max_dt) + " (must be positive)");
    require(o.max_steps > 0, "Lagrangian1D: max_steps = " + show(o.max_steps) + " (must be > 0)");
    require(std::isfinite(o.viscosity.quadratic) && o.viscosity.quadratic >= 0.0 &&
                std::isfinite(o.viscosity.linear) && o.viscosity.linear >= 0.0,
            "Lagrangian1D: viscosity coefficients c_q = " + show(o.viscosity.quadratic) +
                ", c_l = " + show(o.viscosity.linear) + " (must be finite and >= 0)");
    if (o.self_gravity) {
      require(geometry_ == Geometry::spherical,
              "Lagrangian1D: self-gravity needs spherical geometry");
      require(std::isfinite(o.gravitational_constant) && o.gravitational_constant > 0.0,
              "Lagrangian1D: gravitational constant G = " + show(o.gravitational_constant) +
                  " (must be positive and finite)");
    }
    const std::size_t N = m_.size();
    require(N >= 2, "Lagrangian1D: need at least 2 zones, got " + show(static_cast<long>(N)));
    require(r_.size() == N + 1 && u_.size() == N + 1 && e_.size() == N,
            "Lagrangian1D: sizes do not match: " + show(static_cast<long>(r_.size())) +
                " node positions, " + show(static_cast<long>(u_.size())) + " node velocities, " +
                show(static_cast<long>(N)) + " zone masses, " + show(static_cast<long>(e_.size())) +
                " zone energies (need N + 1, N + 1, N, N)");
    check_edges(geometry_, r_);
    for (std::size_t i = 0; i < N; ++i) {
      const std::string zone = "zone " + show(static_cast<long>(i));
      require(std::isfinite(m_[i]) && m_[i] > 0.0,
              "Lagrangian1D: " + zone + " has mass " + show(m_[i]) + " (must be positive)");
      require(std::isfinite(e_[i]) && e_[i] > 0.0,
              "Lagrangian1D: " + zone + " has internal energy " + show(e_[i]) +
                  " (must be positive)");
    }
    for (std::size_t k = 0; k <= N; ++k)
      require(std::isfinite(u_[k]), "Lagrangian1D: node " + show(static_cast<long>(k)) +
                                        " velocity is not finite (" + show(u_[k]) + ")");
    require(o.right != End::centre, "Lagrangian1D: the centre can only be the left end");
    if (o.left == End::centre)
      require(r_.front() == 0.0, "Lagrangian1D: the left end is the centre, so the first node "
                                 "must be at r = 0, not " + show(r_.front()));
    if (geometry_ != Geometry::planar && r_.front() == 0.0)
      require(o.left == End::centre,
              std::string("Lagrangian1D: a curved mesh that starts at r = 0 needs the centre as "
                          "its left end, not a ") + lagrangian_detail::name(o.left) + " end");
    const auto at_rest = [&](End end, std::size_t k, const char* side) {
      if (end != End::free)
        require(u_[k] == 0.0, std::string("Lagrangian1D: the ") + side + " end is a " +
                                  lagrangian_detail::name(end) + ", so its node velocity must " +
                                  "be 0, not " + show(u_[k]));
    };
    at_rest(o.left, 0, "left");
    at_rest(o.right, N, "right");
  }

  double viscosity(double rho, double c, double du) const {
    if (!options_.viscosity.enabled || du >= 0.0) return 0.0;
    const double cq = options_.viscosity.quadratic;
    return rho * (cq * cq * du * du - options_.viscosity.linear * c * du);
  }

  /// \f$ \Pi = P + q \f$ of every zone for positions r, velocities u and energies e; the sound
  /// speeds go to c if given.
  void zone_pressures(const Vector& r, const Vector& u, const Vector& e, Vector& Pi,
                      Vector* c) const {
    const double g = gamma();
    for (std::size_t i = 0; i < m_.size(); ++i) {
      const double rho = m_[i] / lagrangian_detail::volume(geometry_, r[i], r[i + 1]);
      const double ci = std::sqrt(g * (g - 1.0) * e[i]);
      Pi[i] = (g - 1.0) * rho * e[i] + viscosity(rho, ci, u[i + 1] - u[i]);
      if (c) (*c)[i] = ci;
    }
  }

  /// The hydrodynamic force \f$ A(r_k)(\Pi_{k-1} - \Pi_k) \f$ on every node (vacuum beyond a
  /// free end).
  void node_forces(const Vector& r, const Vector& Pi, Vector& F) const {
    const std::size_t N = m_.size();
    for (std::size_t k = 0; k <= N; ++k) {
      const double inside = k > 0 ? Pi[k - 1] : 0.0;
      const double outside = k < N ? Pi[k] : 0.0;
      F[k] = lagrangian_detail::area(geometry_, r[k]) * (inside - outside);
    }
  }

  bool fixed(std::size_t k) const {
    return (k == 0 && fixed_left_) || (k + 1 == r_.size() && fixed_right_);
  }

  /// \f$ g_k = -GM_k/r_k^2 \f$ at positions r.
  double gravity(std::size_t k, double r) const {
    if (!options_.self_gravity || inner_mass_[k] == 0.0) return 0.0;
    return -options_.gravitational_constant * inner_mass_[k] / (r * r);
  }

  /// Pi, c, accelerations and the stable step of the current state (cached until it changes).
  void evaluate_now() const {
    if (valid_) return;
    zone_pressures(r_, u_, e_, Pi_, &c_);
    node_forces(r_, Pi_, F_);
    const std::size_t N = m_.size();
    const double C = options_.courant;
    double dt = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k <= N; ++k) a_[k] = fixed(k) ? 0.0 : F_[k] / node_mass_[k] + gravity(k, r_[k]);
    for (std::size_t i = 0; i < N; ++i) {
      const double dr = r_[i + 1] - r_[i];
      const double du = u_[i + 1] - u_[i];
      double speed = c_[i];
      if (du < 0.0) {
        speed -= du;
        if (options_.viscosity.enabled) {
          const double cq = options_.viscosity.quadratic;
          speed += 2.0 * (cq * cq * (-du) + options_.viscosity.linear * c_[i]);
        }
      }
      if (speed > 0.0) dt = std::min(dt, C * dr / speed);
    }
    for (std::size_t k = 0; k <= N; ++k) {
      if (a_[k] == 0.0) continue;
      const double left = k > 0 ? r_[k] - r_[k - 1] : std::numeric_limits<double>::infinity();
      const double right = k < N ? r_[k + 1] - r_[k] : std::numeric_limits<double>::infinity();
      dt = std::min(dt, C * std::sqrt(std::min(left, right) / std::abs(a_[k])));
    }
    stable_dt_ = dt;
    valid_ = true;
  }

  [[noreturn]] void fail(const std::string& what, const char* stage, double dt) const {
    throw Error("Lagrangian1D: " + what + " " + stage + " from t = " + show(time_) +
                " to t = " + show(time_ + dt) + " (step " + show(steps_ + 1) + ", dt = " +
                show(dt) + "); the state is left at t = " + show(time_));
  }

  std::string zone_name(std::size_t i) const {
    return "zone " + show(static_cast<long>(i)) + " (of " + show(static_cast<long>(m_.size())) +
           ", nodes at r = " + show(r_[i]) + ", " + show(r_[i + 1]) + ")";
  }

  /// Check that every zone of positions r has a positive volume and energy e is >= 0.
  void check_zones(const Vector& r, const Vector& u, const Vector& e, const char* stage,
                   double dt) const {
    if (geometry_ != Geometry::planar && !(r[0] >= 0.0))
      fail("node 0 crossed the centre: r = " + show(r[0]), stage, dt);
    for (std::size_t k = 0; k < r.size(); ++k)
      if (!std::isfinite(u[k]) || !std::isfinite(r[k]))
        fail("node " + show(static_cast<long>(k)) + " is not finite: r = " + show(r[k]) +
                 ", u = " + show(u[k]), stage, dt);
    for (std::size_t i = 0; i < m_.size(); ++i) {
      if (!(r[i + 1] > r[i]))
        fail(zone_name(i) + " inverted: negative volume, its nodes moved to r = " + show(r[i]) +
                 " and " + show(r[i + 1]), stage, dt);
      if (!(e[i] >= 0.0))
        fail(zone_name(i) + " has negative internal energy e = " + show(e[i]), stage, dt);
    }
  }

  void predictor(double dt) {
    const std::size_t N = m_.size();
    for (std::size_t k = 0; k <= N; ++k) {
      r_half_[k] = r_[k] + 0.5 * dt * u_[k];
      u_half_[k] = u_[k] + 0.5 * dt * a_[k];
    }
    for (std::size_t i = 0; i < N; ++i) {
      const double V0 = lagrangian_detail::volume(geometry_, r_[i], r_[i + 1]);
      const double V1 = lagrangian_detail::volume(geometry_, r_half_[i], r_half_[i + 1]);
      e_half_[i] = e_[i] - Pi_[i] * (V1 - V0) / m_[i];
    }
    check_zones(r_half_, u_half_, e_half_, "in the predictor half step", dt);
    zone_pressures(r_half_, u_half_, e_half_, Pi_half_, nullptr);
    node_forces(r_half_, Pi_half_, F_half_);
  }

  void corrector(double dt) {
    const std::size_t N = m_.size();
    const double G = options_.gravitational_constant;
    for (std::size_t k = 0; k <= N; ++k) {
      if (fixed(k)) {
        r_new_[k] = r_[k];
        u_new_[k] = u_bar_[k] = 0.0;
        continue;
      }
      const double a = F_half_[k] / node_mass_[k];
      if (options_.self_gravity && inner_mass_[k] > 0.0) {
        // x^2 - b x + c = 0 for x = r^{n+1} (the force -G M mu / (r^n r^{n+1})), written for
        // the displacement d = x - r^n so that no digits cancel:
        //   d^2 + (r - beta) d - (beta r - c) = 0,  beta = dt u + dt^2 a / 2,
        // and its root that vanishes with dt, d = 2s / (p + sqrt(p^2 + 4s)).
        const double r = r_[k];
        const double beta = dt * u_[k] + 0.5 * dt * dt * a;
        const double p = r - beta;
        const double s = beta * r - 0.5 * dt * dt * G * inner_mass_[k] / r;
        const double discriminant = p * p + 4.0 * s;
        if (!(p > 0.0 && discriminant >= 0.0))
          fail("node " + show(static_cast<long>(k)) + " at r = " + show(r) +
                   " would fall through the centre (the gravity update has no root)",
               "in the corrector", dt);
        const double d = 2.0 * s / (p + std::sqrt(discriminant));
        r_new_[k] = r + d;
        u_bar_[k] = d / dt;
        u_new_[k] = 2.0 * u_bar_[k] - u_[k];
      } else {
        u_new_[k] = u_[k] + dt * a;
        u_bar_[k] = 0.5 * (u_[k] + u_new_[k]);
        r_new_[k] = r_[k] + dt * u_bar_[k];
      }
    }
    for (std::size_t i = 0; i < N; ++i) {
      const double work = Pi_half_[i] * (lagrangian_detail::area(geometry_, r_half_[i + 1]) * u_bar_[i + 1] -
                                         lagrangian_detail::area(geometry_, r_half_[i]) * u_bar_[i]);
      e_new_[i] = e_[i] - dt * work / m_[i];
    }
    check_zones(r_new_, u_new_, e_new_, "in the corrector", dt);
    std::swap(r_, r_new_);
    std::swap(u_, u_new_);
    std::swap(e_, e_new_);
    time_ += dt;
    last_dt_ = dt;
    ++steps_;
  }

  Geometry geometry_;
  LagrangianOptions options_;
  Vector r_, u_, m_, e_;          // node positions, velocities; zone masses, energies
  Vector node_mass_, inner_mass_;  // mu_k and M_k
  bool fixed_left_ = false, fixed_right_ = false;
  double time_ = 0, last_dt_ = 0;
  long steps_ = 0;
  // Work arrays: the forces of the current state are cached for stable_time_step().
  mutable Vector Pi_, c_, a_, F_;
  mutable double stable_dt_ = 0;
  mutable bool valid_ = false;
  Vector r_half_, u_half_, e_half_, Pi_half_, F_half_, r_new_, u_new_, u_bar_, e_new_;
};

}  // namespace sph
