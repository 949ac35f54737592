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
/// and any \f$ \Delta t \f$.  The time integration is a predictor-corrector of the kind they
/// use, second order in time:
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
/// converges to the inviscid solution away from shocks.  How high: with \f$ P = \rho c^2/\gamma \f$
/// the quadratic term is \f$ q/P = \gamma c_q^2 (\Delta u/c)^2 \f$, so it is negligible only
/// where the velocity jump across a zone is small next to \f$ c/(c_q\sqrt\gamma) \f$.  A cold
/// gas compressed fast is the hard case: the inner half of the uniform sphere with u = -2r and
/// e = 0.001 is heated above its adiabat by a factor 2.3 at t = 0.3 with 400 zones (14 with
/// 100).  q can be switched off for flows without shocks, or until the first shock forms.
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
/// b as \f$ \Delta t \to 0 \f$ (written for the displacement \f$ x - r_k^n \f$, so that no
/// digits cancel).
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
/// The accuracy is second order in smooth flow on a smoothly varying mesh and first order at
/// shocks, as for every shock-capturing scheme.  A step costs some 10-20 ns per zone on one
/// core; the number of steps to a given time grows as N, so the cost of a run as \f$ N^2 \f$.

#include "sph/error.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
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
  /// Measure the velocity jump against a homologous flow about r = 0: in a curved geometry use
  /// \f$ \Delta u - (\bar u/\bar r)\Delta r \f$ (zone means), which vanishes when
  /// \f$ u \propto r \f$, so that a self-similar compression is not heated (the point of
  /// Caramana, Shashkov & Whalen 1998).  Ignored in planar geometry, which has no centre.
  bool homologous_limiter = false;
};

/// Everything about a run except the initial data.
struct LagrangianOptions {
  double gamma = 5.0 / 3.0;  ///< ideal gas, P = (gamma - 1) rho e
  LagrangianEnd left = LagrangianEnd::free;
  LagrangianEnd right = LagrangianEnd::free;
  LagrangianViscosity viscosity{};
  bool self_gravity = false;                                ///< spherical geometry only
  double gravitational_constant = 1.0;                      ///< G
  double courant = 0.3;                                     ///< C of the time step
  double max_dt = std::numeric_limits<double>::infinity();  ///< a bound on every step
  long max_steps = 10'000'000;  ///< run_until throws when one call would need more
};

/// The state at one time, zone by zone (at zone centres) and node by node.
struct LagrangianProfile {
  double time = 0;
  std::vector<double> radius;           ///< zone centre, the midpoint of its two nodes
  std::vector<double> mass_coordinate;  ///< mass inside the zone centre (half its own)
  std::vector<double> density;
  std::vector<double> pressure;
  std::vector<double> internal_energy;   ///< e, per unit mass
  std::vector<double> velocity;          ///< mean of the zone's two node velocities
  std::vector<double> viscous_pressure;  ///< q
  std::vector<double> node_radius;       ///< the N + 1 node positions
  std::vector<double> node_velocity;     ///< the N + 1 node velocities
};

namespace lagrangian_detail {

/// \f$ \mathcal V(b) - \mathcal V(a) \f$, factored so that a thin shell loses no digits.
template <LagrangianGeometry G>
inline double volume(double a, double b) {
  if constexpr (G == LagrangianGeometry::planar) return b - a;
  if constexpr (G == LagrangianGeometry::cylindrical) return std::numbers::pi * (b - a) * (b + a);
  if constexpr (G == LagrangianGeometry::spherical)
    return 4.0 / 3.0 * std::numbers::pi * (b - a) * (b * b + a * b + a * a);
}

/// \f$ A(r) = \mathcal V'(r) \f$.
template <LagrangianGeometry G>
inline double area(double r) {
  if constexpr (G == LagrangianGeometry::planar) return 1.0;
  if constexpr (G == LagrangianGeometry::cylindrical) return 2.0 * std::numbers::pi * r;
  if constexpr (G == LagrangianGeometry::spherical) return 4.0 * std::numbers::pi * r * r;
}

/// Calls f(std::integral_constant<LagrangianGeometry, g>{}): the geometry is chosen once, and
/// the loops inside f know it at compile time.
template <class F>
decltype(auto) with_geometry(LagrangianGeometry g, F&& f) {
  using G = LagrangianGeometry;
  switch (g) {
    case G::planar:
      return f(std::integral_constant<G, G::planar>{});
    case G::cylindrical:
      return f(std::integral_constant<G, G::cylindrical>{});
    case G::spherical:
      break;
  }
  return f(std::integral_constant<G, G::spherical>{});
}

inline double volume(LagrangianGeometry g, double a, double b) {
  return with_geometry(g, [&](auto G) { return volume<G()>(a, b); });
}
inline double area(LagrangianGeometry g, double r) {
  return with_geometry(g, [&](auto G) { return area<G()>(r); });
}

/// \f$ \int_a^b f(r) A(r)\,dr \f$ by 5-point Gauss-Legendre quadrature on `pieces` equal
/// sub-intervals (exact for polynomials of degree 9 on each); f is never called at a or b.
template <class F>
double integrate_over_volume(LagrangianGeometry g, double a, double b, int pieces, F&& f) {
  static constexpr double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                  0.9061798459386640};
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

/// f(r), which must be positive and finite: "density(r) = -1 at r = 0.3 ..." otherwise.
inline double positive_value(const std::function<double(double)>& f, double r, const char* what) {
  const double value = f(r);
  if (!(std::isfinite(value) && value > 0.0))
    throw Error(std::string("Lagrangian1D: ") + what + " = " + show(value) + " at r = " + show(r) +
                " (must be positive and finite)");
  return value;
}

inline const char* name(LagrangianEnd end) {
  switch (end) {
    case LagrangianEnd::free:
      return "free";
    case LagrangianEnd::wall:
      return "wall";
    case LagrangianEnd::centre:
      break;
  }
  return "centre";
}

inline std::string count(std::size_t n) { return show(static_cast<long>(n)); }

}  // namespace lagrangian_detail

/// The one-dimensional Lagrangian solver.  Set it up from zones or from profiles, then step.
///
/// \code
/// sph::LagrangianOptions o;             // gamma 5/3, free ends, q on
/// o.left = sph::LagrangianEnd::centre;  // a sphere from r = 0
/// const auto rho = [](double) { return 0.75 / std::numbers::pi; };  // M = R = 1
/// auto sphere = sph::Lagrangian1D::from_profile(sph::LagrangianGeometry::spherical,
///     sph::Lagrangian1D::equal_mass_edges(sph::LagrangianGeometry::spherical, 0, 1, 400, rho),
///     rho, [](double r) { return -2 * r; }, [](double) { return 1e-3; }, o);
/// sphere.run_until(0.4, [](const sph::Lagrangian1D& s) { /* s.time(), s.density(0) */ });
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
      : geometry_(geometry),
        options_(options),
        r_(std::move(node_radius)),
        u_(std::move(node_velocity)),
        m_(std::move(zone_mass)),
        e_(std::move(zone_energy)) {
    validate();
    const std::size_t N = m_.size();
    node_mass_.assign(N + 1, 0.0);
    inner_mass_.assign(N + 1, 0.0);
    inverse_mass_.resize(N);
    for (std::size_t i = 0; i < N; ++i) {
      node_mass_[i] += 0.5 * m_[i];
      node_mass_[i + 1] += 0.5 * m_[i];
      inner_mass_[i + 1] = inner_mass_[i] + m_[i];
      inverse_mass_[i] = 1.0 / m_[i];
    }
    inverse_node_mass_.resize(N + 1);
    for (std::size_t k = 0; k <= N; ++k) inverse_node_mass_[k] = 1.0 / node_mass_[k];
    fixed_left_ = options_.left != End::free;
    fixed_right_ = options_.right != End::free;
    for (auto* v : {&Pi_, &c_, &Pi_half_, &c_half_, &e_half_, &e_new_}) v->assign(N, 0.0);
    for (auto* v :
         {&A_, &F_, &a_, &r_half_, &u_half_, &A_half_, &F_half_, &r_new_, &u_new_, &u_bar_})
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
                                   lagrangian_detail::count(edges.size()) + " edges");
    check_edges(geometry, edges);
    const std::size_t N = edges.size() - 1;
    std::vector<double> u(N + 1), m(N), e(N);
    for (std::size_t k = 0; k <= N; ++k) u[k] = velocity(edges[k]);
    const auto rho = [&](double r) {
      return lagrangian_detail::positive_value(density, r, "density(r)");
    };
    const auto rho_e = [&](double r) {
      return rho(r) * lagrangian_detail::positive_value(internal_energy, r, "internal energy e(r)");
    };
    for (std::size_t i = 0; i < N; ++i) {
      m[i] = lagrangian_detail::integrate_over_volume(geometry, edges[i], edges[i + 1], 4, rho);
      e[i] = lagrangian_detail::integrate_over_volume(geometry, edges[i], edges[i + 1], 4, rho_e);
      e[i] /= m[i];
    }
    return Lagrangian1D(geometry, std::move(edges), std::move(u), std::move(m), std::move(e),
                        options);
  }

  /// N + 1 equally spaced edges on [r_min, r_max].
  static std::vector<double> uniform_edges(double r_min, double r_max, int zones) {
    require(zones >= 1, "Lagrangian1D: uniform_edges needs at least 1 zone, got " + show(zones));
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
                lagrangian_detail::count(breaks.size()) + " breaks, " +
                lagrangian_detail::count(zones.size()) + " zone counts)");
    std::vector<double> edges{breaks.front()};
    for (std::size_t j = 0; j < zones.size(); ++j) {
      const std::vector<double> part = uniform_edges(breaks[j], breaks[j + 1], zones[j]);
      edges.insert(edges.end(), part.begin() + 1, part.end());
    }
    return edges;
  }

  /// Edges of `zones` zones of equal mass on [r_min, r_max] for the density rho(r): the
  /// cumulative mass is tabulated on 32 cells per zone and inverted by bisection.  For a
  /// uniform sphere from 0 this gives \f$ r_k = R(k/N)^{1/3} \f$, for the Evrard sphere
  /// \f$ r_k = R\sqrt{k/N} \f$.
  static std::vector<double> equal_mass_edges(Geometry geometry, double r_min, double r_max,
                                              int zones, const Profile& density) {
    require(geometry == Geometry::planar || r_min >= 0.0,
            "Lagrangian1D: a cylindrical or spherical mesh needs r_min >= 0, got " + show(r_min));
    const std::vector<double> grid = uniform_edges(r_min, r_max, 32 * zones);
    const auto mass = [&](double a, double b) {
      return lagrangian_detail::integrate_over_volume(geometry, a, b, 1, [&](double r) {
        return lagrangian_detail::positive_value(density, r, "density(r)");
      });
    };
    std::vector<double> cumulative(grid.size(), 0.0);
    for (std::size_t j = 1; j < grid.size(); ++j)
      cumulative[j] = cumulative[j - 1] + mass(grid[j - 1], grid[j]);
    std::vector<double> edges(zones + 1);
    edges[0] = r_min;
    edges[zones] = r_max;
    std::size_t cell = 0;
    for (int k = 1; k < zones; ++k) {
      const double target = cumulative.back() * k / zones;
      while (cumulative[cell + 1] < target) ++cell;
      double low = grid[cell], high = grid[cell + 1];
      for (int halving = 0; halving < 64; ++halving) {  // to round-off
        const double mid = 0.5 * (low + high);
        (cumulative[cell] + mass(grid[cell], mid) < target ? low : high) = mid;
      }
      edges[k] = 0.5 * (low + high);
    }
    return edges;
  }

  // --- running ---------------------------------------------------------------------------

  /// The step the stability and accuracy limits allow now (max_dt not applied); infinite for
  /// a cold gas at rest on which no force acts.
  double stable_time_step() const {
    evaluate_now();
    return stable_dt_;
  }

  /// One step of min(stable_time_step(), max_dt); returns its length.
  double step() {
    const double dt = std::min(stable_time_step(), options_.max_dt);
    if (!std::isfinite(dt))
      throw Error("Lagrangian1D: no limit on the time step at t = " + show(time_) +
                  " (a cold gas at rest with no force); set max_dt");
    advance(dt);
    return dt;
  }

  /// One step of the given length, without a stability check.
  void advance(double dt) {
    if (!(std::isfinite(dt) && dt > 0.0))
      throw Error("Lagrangian1D: time step dt = " + show(dt) + " (must be positive and finite)");
    evaluate_now();
    lagrangian_detail::with_geometry(geometry_, [&](auto G) {
      predictor<G()>(dt);
      corrector<G()>(dt);
    });
    valid_ = false;
  }

  /// Steps until t_end, the last step shortened to land on it; `after_step` is called after
  /// each step.  Returns the number of steps; throws sph::Error if it would take more than
  /// options().max_steps.
  long run_until(double t_end, const Callback& after_step = {}) {
    require(std::isfinite(t_end) && t_end >= time_, "Lagrangian1D: run_until(" + show(t_end) +
                                                        ") from t = " + show(time_) +
                                                        " (must be finite and not in the past)");
    long taken = 0;
    while (time_ < t_end) {
      if (taken >= options_.max_steps)
        throw Error("Lagrangian1D: max_steps = " + show(options_.max_steps) +
                    " reached at t = " + show(time_) + " before t_end = " + show(t_end) +
                    " (last dt = " + show(last_dt_) + ")");
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
  long steps() const { return steps_; }  ///< taken since the start
  double last_time_step() const { return last_dt_; }
  std::size_t zones() const { return m_.size(); }
  std::size_t nodes() const { return r_.size(); }

  const std::vector<double>& node_radius() const { return r_; }
  const std::vector<double>& node_velocity() const { return u_; }
  const std::vector<double>& zone_mass() const { return m_; }
  const std::vector<double>& zone_energy() const { return e_; }
  /// \f$ \mu_k \f$, the mass a node carries (half of each neighbouring zone).
  double node_mass(std::size_t k) const { return node_mass_.at(k); }
  /// \f$ M_k = \sum_{i<k} m_i \f$, the mass inside node k.
  double mass_inside(std::size_t k) const { return inner_mass_.at(k); }

  double volume(std::size_t i) const {
    return lagrangian_detail::volume(geometry_, r_[i], r_[i + 1]);
  }
  double density(std::size_t i) const { return m_[i] / volume(i); }
  double pressure(std::size_t i) const { return (gamma() - 1.0) * density(i) * e_[i]; }
  double internal_energy(std::size_t i) const { return e_[i]; }
  double sound_speed(std::size_t i) const { return std::sqrt(gamma() * (gamma() - 1.0) * e_[i]); }
  /// q of zone i for the current velocities.
  double viscous_pressure(std::size_t i) const {
    return viscosity(density(i), sound_speed(i), velocity_jump(r_, u_, i));
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
  /// \f$ W = -G\sum_k M_k\mu_k/r_k \f$; 0 without self-gravity.
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
    using lagrangian_detail::count;
    for (std::size_t k = 0; k < r.size(); ++k) {
      if (!std::isfinite(r[k]))
        throw Error("Lagrangian1D: node " + count(k) + " position is not finite (" + show(r[k]) +
                    ")");
      if (k > 0 && !(r[k] > r[k - 1]))
        throw Error("Lagrangian1D: node positions must increase: node " + count(k) +
                    " at r = " + show(r[k]) + " is not beyond node " + count(k - 1) +
                    " at r = " + show(r[k - 1]));
    }
    require(geometry == Geometry::planar || r.front() >= 0.0,
            "Lagrangian1D: a cylindrical or spherical mesh needs r >= 0, the first node is at "
            "r = " +
                show(r.front()));
  }

  void validate() const {
    using lagrangian_detail::count;
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
    require(N >= 2, "Lagrangian1D: need at least 2 zones, got " + count(N));
    require(r_.size() == N + 1 && u_.size() == N + 1 && e_.size() == N,
            "Lagrangian1D: sizes do not match: " + count(r_.size()) + " node positions, " +
                count(u_.size()) + " node velocities, " + count(N) + " zone masses, " +
                count(e_.size()) + " zone energies (need N + 1, N + 1, N, N)");
    check_edges(geometry_, r_);
    for (std::size_t i = 0; i < N; ++i) {
      if (!(std::isfinite(m_[i]) && m_[i] > 0.0))
        throw Error("Lagrangian1D: zone " + count(i) + " has mass " + show(m_[i]) +
                    " (must be positive and finite)");
      if (!(std::isfinite(e_[i]) && e_[i] > 0.0))
        throw Error("Lagrangian1D: zone " + count(i) + " has internal energy " + show(e_[i]) +
                    " (must be positive and finite)");
    }
    for (std::size_t k = 0; k <= N; ++k)
      if (!std::isfinite(u_[k]))
        throw Error("Lagrangian1D: node " + count(k) + " velocity is not finite (" + show(u_[k]) +
                    ")");
    require(o.right != End::centre, "Lagrangian1D: the centre can only be the left end");
    if (o.left == End::centre)
      require(r_.front() == 0.0,
              "Lagrangian1D: the left end is the centre, so the first node "
              "must be at r = 0, not " +
                  show(r_.front()));
    if (geometry_ != Geometry::planar && r_.front() == 0.0)
      require(o.left == End::centre,
              std::string("Lagrangian1D: a curved mesh that starts at r = 0 needs the centre "
                          "as its left end, not a ") +
                  lagrangian_detail::name(o.left) + " end");
    const auto at_rest = [&](End end, std::size_t k, const char* side) {
      if (end != End::free)
        require(u_[k] == 0.0, std::string("Lagrangian1D: the ") + side + " end is a " +
                                  lagrangian_detail::name(end) + ", so its node velocity " +
                                  "must be 0, not " + show(u_[k]));
    };
    at_rest(o.left, 0, "left");
    at_rest(o.right, N, "right");
  }

  /// q for density rho, sound speed c and velocity jump du, with the coefficients
  /// \f$ c_q^2 \f$ and \f$ c_l \f$ (both 0 when q is off); min(du, 0) instead of a branch lets
  /// the loops vectorise.
  static double viscosity(double rho, double c, double du, double cq2, double cl) {
    const double compression = std::min(du, 0.0);
    return rho * compression * (cq2 * compression - cl * c);
  }
  double viscosity(double rho, double c, double du) const {
    const auto [cq2, cl] = viscosity_coefficients();
    return viscosity(rho, c, du, cq2, cl);
  }
  std::pair<double, double> viscosity_coefficients() const {
    const LagrangianViscosity& q = options_.viscosity;
    return q.enabled ? std::pair{q.quadratic * q.quadratic, q.linear} : std::pair{0.0, 0.0};
  }

  /// \f$ \Pi = P + q \f$ and the sound speed c of every zone for positions r, velocities u
  /// and energies e.
  template <Geometry G>
  void zone_pressures(const Vector& r, const Vector& u, const Vector& e, Vector& Pi,
                      Vector& c) const {
    const double g1 = gamma() - 1.0, gg1 = gamma() * g1;
    const auto [cq2, cl] = viscosity_coefficients();
    const std::size_t N = m_.size();
    const double *rk = r.data(), *ei = e.data(), *mi = m_.data();
    double *Pi_i = Pi.data(), *ci = c.data();
    for (std::size_t i = 0; i < N; ++i) {
      const double rho = mi[i] / lagrangian_detail::volume<G>(rk[i], rk[i + 1]);
      ci[i] = std::sqrt(gg1 * ei[i]);
      Pi_i[i] = g1 * rho * ei[i] + viscosity(rho, ci[i], velocity_jump(r, u, i), cq2, cl);
    }
  }

  /// The velocity jump across zone i that q sees: \f$ u_{k+1} - u_k \f$, or with the
  /// homologous limiter in a curved geometry its part that a flow \f$ u \propto r \f$ does
  /// not explain.
  double velocity_jump(const Vector& r, const Vector& u, std::size_t i) const {
    const double du = u[i + 1] - u[i];
    if (!options_.viscosity.homologous_limiter || geometry_ == Geometry::planar) return du;
    const double r_bar = 0.5 * (r[i] + r[i + 1]);
    const double u_bar = 0.5 * (u[i] + u[i + 1]);
    if (!(r_bar > 0)) return du;
    const double deviation = du - u_bar / r_bar * (r[i + 1] - r[i]);
    // (a deviation at the level of round-off is none: otherwise the linear term's time-step
    // limit would switch on and off with the last bits)
    return std::abs(deviation) > 1e-10 * std::abs(du) ? deviation : 0.0;
  }

  /// The hydrodynamic force \f$ A_k(\Pi_{k-1} - \Pi_k) \f$ on every node, with the areas
  /// \f$ A_k \f$ given; vacuum beyond a free end.
  void node_forces(const Vector& area, const Vector& Pi, Vector& F) const {
    const std::size_t N = m_.size();
    F[0] = -area[0] * Pi[0];
    for (std::size_t k = 1; k < N; ++k) F[k] = area[k] * (Pi[k - 1] - Pi[k]);
    F[N] = area[N] * Pi[N - 1];
  }

  bool fixed(std::size_t k) const {
    return (k == 0 && fixed_left_) || (k + 1 == r_.size() && fixed_right_);
  }

  /// \f$ g_k = -GM_k/r_k^2 \f$ at position r.
  double gravity(std::size_t k, double r) const {
    if (!options_.self_gravity || inner_mass_[k] == 0.0) return 0.0;
    return -options_.gravitational_constant * inner_mass_[k] / (r * r);
  }

  /// Pi, c, the accelerations and the stable step of the current state, cached until the
  /// state changes.
  void evaluate_now() const {
    if (valid_) return;
    lagrangian_detail::with_geometry(geometry_, [&](auto G) {
      zone_pressures<G()>(r_, u_, e_, Pi_, c_);
      for (std::size_t k = 0; k < r_.size(); ++k) A_[k] = lagrangian_detail::area<G()>(r_[k]);
    });
    node_forces(A_, Pi_, F_);
    const std::size_t N = m_.size();
    const double C = options_.courant;
    for (std::size_t k = 0; k <= N; ++k)
      a_[k] = fixed(k) ? 0.0 : F_[k] * inverse_node_mass_[k] + gravity(k, r_[k]);
    // Zones: sound crossing, own compression, diffusion limit of q.
    const bool q = options_.viscosity.enabled;
    const double cq2 = options_.viscosity.quadratic * options_.viscosity.quadratic;
    const double cl = options_.viscosity.linear;
    double inverse_dt = 0;  // the largest speed / width
    for (std::size_t i = 0; i < N; ++i) {
      const double du = u_[i + 1] - u_[i];
      double speed = c_[i];
      if (du < 0.0) speed += -du;
      // (q's own limit with the jump q sees: with the homologous limiter, none in a
      // self-similar compression)
      const double dq = q ? std::min(velocity_jump(r_, u_, i), 0.0) : 0.0;
      if (dq < 0.0) speed += 2.0 * (cq2 * (-dq) + cl * c_[i]);
      inverse_dt = std::max(inverse_dt, speed / (r_[i + 1] - r_[i]));
    }
    // Nodes: dt^2 |a| < width, with the narrower neighbouring zone.
    double inverse_dt2 = 0;
    for (std::size_t k = 0; k <= N; ++k) {
      if (a_[k] == 0.0) continue;
      const double left = k > 0 ? r_[k] - r_[k - 1] : r_[k + 1] - r_[k];
      const double right = k < N ? r_[k + 1] - r_[k] : left;
      inverse_dt2 = std::max(inverse_dt2, std::abs(a_[k]) / std::min(left, right));
    }
    const double inverse = std::max(inverse_dt, std::sqrt(inverse_dt2));
    stable_dt_ = inverse > 0.0 ? C / inverse : std::numeric_limits<double>::infinity();
    valid_ = true;
  }

  [[noreturn]] void fail(const std::string& what, const char* stage, double dt) const {
    throw Error("Lagrangian1D: " + what + " " + stage + " from t = " + show(time_) +
                " to t = " + show(time_ + dt) + " (step " + show(steps_ + 1) +
                ", dt = " + show(dt) + "); the state is left at t = " + show(time_));
  }

  /// Every zone of the trial state (r, u, e) has a positive volume and e >= 0, every number
  /// is finite; otherwise fail() names the first culprit.
  void check_zones(const Vector& r, const Vector& u, const Vector& e, const char* stage,
                   double dt) const {
    using lagrangian_detail::count;
    const double huge = std::numeric_limits<double>::max();
    bool ok = geometry_ == Geometry::planar || r[0] >= 0.0;
    for (std::size_t k = 0; k < r.size(); ++k) {  // &= rather than &&: no branches
      ok &= std::abs(r[k]) <= huge;
      ok &= std::abs(u[k]) <= huge;
    }
    for (std::size_t i = 0; i < m_.size(); ++i) {
      ok &= r[i + 1] > r[i];
      ok &= e[i] >= 0.0;
    }
    if (ok) return;
    if (!(geometry_ == Geometry::planar || r[0] >= 0.0))
      fail("node 0 crossed the centre: r = " + show(r[0]), stage, dt);
    for (std::size_t k = 0; k < r.size(); ++k)
      if (!(std::isfinite(u[k]) && std::isfinite(r[k])))
        fail("node " + count(k) + " is not finite: r = " + show(r[k]) + ", u = " + show(u[k]),
             stage, dt);
    const auto zone = [&](std::size_t i) {
      return "zone " + count(i) + " (of " + count(m_.size()) + ", between r = " + show(r_[i]) +
             " and " + show(r_[i + 1]) + " at the start of the step)";
    };
    for (std::size_t i = 0; i < m_.size(); ++i) {
      if (!(r[i + 1] > r[i]))
        fail(zone(i) + " inverted: negative volume, its nodes moved to r = " + show(r[i]) +
                 " and " + show(r[i + 1]),
             stage, dt);
      if (!(e[i] >= 0.0))
        fail(zone(i) + " has negative internal energy e = " + show(e[i]), stage, dt);
    }
  }

  template <Geometry G>
  void predictor(double dt) {
    const std::size_t N = m_.size();
    for (std::size_t k = 0; k <= N; ++k) {
      r_half_[k] = r_[k] + 0.5 * dt * u_[k];
      u_half_[k] = u_[k] + 0.5 * dt * a_[k];
      A_half_[k] = lagrangian_detail::area<G>(r_half_[k]);
    }
    for (std::size_t i = 0; i < N; ++i) {
      const double V0 = lagrangian_detail::volume<G>(r_[i], r_[i + 1]);
      const double V1 = lagrangian_detail::volume<G>(r_half_[i], r_half_[i + 1]);
      e_half_[i] = e_[i] - Pi_[i] * (V1 - V0) * inverse_mass_[i];
    }
    check_zones(r_half_, u_half_, e_half_, "in the predictor half step", dt);
    zone_pressures<G>(r_half_, u_half_, e_half_, Pi_half_, c_half_);
    node_forces(A_half_, Pi_half_, F_half_);
  }

  template <Geometry G>
  void corrector(double dt) {
    const std::size_t N = m_.size();
    const double G_newton = options_.gravitational_constant;
    for (std::size_t k = 0; k <= N; ++k) {
      if (fixed(k)) {
        r_new_[k] = r_[k];
        u_new_[k] = u_bar_[k] = 0.0;
        continue;
      }
      const double a = F_half_[k] * inverse_node_mass_[k];
      if (options_.self_gravity && inner_mass_[k] > 0.0) {
        // x^2 - b x + c = 0 for x = r^{n+1} (the force -G M mu / (r^n r^{n+1})), written for
        // the displacement d = x - r^n so that no digits cancel:
        //   d^2 + (r - beta) d - (beta r - c) = 0,  beta = dt u + dt^2 a / 2,
        // with the root that vanishes with dt, d = 2s / (p + sqrt(p^2 + 4s)).
        const double r = r_[k];
        const double beta = dt * u_[k] + 0.5 * dt * dt * a;
        const double p = r - beta;
        const double s = beta * r - 0.5 * dt * dt * G_newton * inner_mass_[k] / r;
        const double discriminant = p * p + 4.0 * s;
        if (!(p > 0.0 && discriminant >= 0.0))
          fail("node " + lagrangian_detail::count(k) + " at r = " + show(r) +
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
    // The work of the corner forces, with the velocities that moved the nodes.
    for (std::size_t i = 0; i < N; ++i) {
      const double work = Pi_half_[i] * (A_half_[i + 1] * u_bar_[i + 1] - A_half_[i] * u_bar_[i]);
      e_new_[i] = e_[i] - dt * work * inverse_mass_[i];
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
  Vector r_, u_, m_, e_;           // node positions and velocities; zone masses and energies
  Vector node_mass_, inner_mass_;  // mu_k and M_k
  Vector inverse_mass_, inverse_node_mass_;
  bool fixed_left_ = false, fixed_right_ = false;
  double time_ = 0, last_dt_ = 0;
  long steps_ = 0;
  // The forces of the current state, cached for stable_time_step() and the next step.
  mutable Vector Pi_, c_, A_, F_, a_;
  mutable double stable_dt_ = 0;
  mutable bool valid_ = false;
  // Work arrays of a step: the half step and the trial new state.
  Vector r_half_, u_half_, A_half_, e_half_, Pi_half_, c_half_, F_half_;
  Vector r_new_, u_new_, u_bar_, e_new_;
};

}  // namespace sph
