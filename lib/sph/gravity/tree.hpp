#pragma once
/// \file
/// \brief Self-gravity with a Barnes-Hut octree (Barnes & Hut 1986): O(N log N) instead of
/// O(N^2), at a controlled force error.
///
/// **Why a tree works.**  Seen from far away, a group of particles pulls almost like one point
/// mass at its centre of mass.  Expand the potential of a group of size s about its centre of
/// mass: the monopole term is \f$ -GM/d \f$, the dipole term vanishes (we expand about the
/// centre of mass), and the next, the quadrupole, is smaller by \f$ (s/d)^2 \f$.  Keeping the
/// terms up to order p leaves a relative error of about \f$ (s/d)^{p+1} \f$: with the monopole
/// alone (p = 1) \f$ (s/d)^2 \f$, with the quadrupole (p = 2) \f$ (s/d)^3 \f$.  A tree groups the
/// particles at every scale -- the root holds all of them, each node splits into up to eight
/// children, the leaves hold a few particles each -- so that every particle can see the near
/// particles one by one and ever larger groups ever farther away.  The number of interactions
/// per particle grows like log N rather than N.
///
/// **Monopole and quadrupole.**  A node keeps its mass M, centre of mass \f$ \mathbf X \f$ and
/// traceless quadrupole \f$ Q_{ab} = \sum_j m_j (3 x_{j,a} x_{j,b} - |\mathbf x_j|^2\delta_{ab})
/// \f$, the \f$ \mathbf x_j \f$ measured from \f$ \mathbf X \f$.  At \f$ \mathbf r = \mathbf x_i
/// - \mathbf X \f$ its potential and pull are
/// \f[ \Phi = -G\left[\frac{M}{r} + \frac{\mathbf r\cdot Q\mathbf r}{2r^5}\right], \qquad
///     \mathbf a = -\nabla\Phi = -G\frac{M}{r^3}\mathbf r + G\frac{Q\mathbf r}{r^5}
///       - \frac52 G\frac{\mathbf r\cdot Q\mathbf r}{r^7}\,\mathbf r. \f]
/// The quadrupole costs about twenty more operations per node and buys one more power of s/d: at
/// the same accuracy the nodes may be larger, so fewer of them are opened.
///
/// **Opening criterion.**  Each node knows \f$ r_\mathrm{max} \f$, the largest distance from
/// its centre of mass to any of its particles (a true bound, not the cell's size), and
/// \f$ h_\mathrm{max} \f$, the largest smoothing length among its particles.  A particle at
/// distance d from the centre of mass uses the node as a multipole only if
///  1. it is far: \f$ r_\mathrm{max} < \theta\, d \f$ (after Salmon & Warren 1994).  The
///     original criterion compares the cell's side with d; it fails when the centre of mass
///     sits near a corner of a large, mostly empty cell, so that a particle just beside the
///     cell's particles still accepts it.  The bound \f$ r_\mathrm{max} \f$ measures the mass
///     itself and cannot be fooled that way;
///  2. no particle of the node is within the softening range:
///     \f$ d - r_\mathrm{max} \ge 2\max(h_i, h_\mathrm{max}) \f$.  Then every pair between the
///     particle and the node is farther apart than both kernels' support, where the softened
///     force of gravity/softening.hpp is exactly Newton's -- and so is the multipole expansion.
///
/// Otherwise the node is opened: its children are tested in turn, and a leaf that is opened
/// interacts particle by particle: Newton's force for the pairs beyond both kernels' support, the
/// softened pair force of gravity/softening.hpp for the others.
///
/// **The relative criterion** (Springel 2005, GADGET-2), an option.  The geometric criterion
/// bounds each node's error relative to that node's own pull, so a particle whose total pull
/// is small -- near the centre of a sphere, where the pulls of all sides cancel -- gets a large
/// relative error, while a particle under a strong pull gets more accuracy than it needs.  The
/// relative criterion bounds the error against the particle's own acceleration instead: with
/// \f$ |\mathbf a_i| \f$ from its last evaluation, a node of mass M is accepted where the
/// first term the expansion leaves out is small against it,
/// \f[ \frac{GM}{d^2}\left(\frac{r_\mathrm{max}}{d}\right)^{p+1} \le \alpha\,|\mathbf a_i|,
///     \qquad p = 1 \text{ (monopoles)},\ 2 \text{ (quadrupoles)}, \f]
/// and, as before, where no particle of the node is within the softening range, and the node's
/// sphere does not reach the particle (\f$ d > r_\mathrm{max} \f$: GADGET-2's test that the
/// particle is not inside the node).  It needs a first evaluation: one without accelerations of
/// the same particles (the first, another particle count, or the first after
/// forget_accelerations(), which a caller must call before handing the tree a different set of
/// as many particles), and any particle whose last acceleration is zero, uses the geometric
/// criterion.  A target of the walk uses its smallest \f$ |\mathbf a| \f$.  The result then
/// depends on the last evaluation, still the same for any number of threads.
///
/// **How small must theta be?**  On a random uniform sphere of \f$ 10^4 \f$ particles
/// (tests/sph/test_gravity.cpp) the default \f$ \theta = 0.3 \f$ with quadrupoles gives a
/// median relative force error of \f$ 1.0\times10^{-4} \f$, a 99th percentile of
/// \f$ 7\times10^{-4} \f$, and at most \f$ 3\times10^{-3} \f$ wherever the force is at
/// least a tenth of the median one.  The largest error of all, 0.7 %, belongs to the
/// particle nearest the centre, where the pulls of all sides cancel (see below).  At
/// \f$ \theta = 0.5 \f$ the median is still \f$ 5\times10^{-4} \f$, but the 99th
/// percentile is \f$ 4\times10^{-3} \f$ and the worst particles are off by 2 to 5 %.  This
/// criterion is stricter than the cell-size one at the same theta (\f$ r_\mathrm{max} \f$ is
/// up to \f$ \sqrt3/2 \f$ of a side), and the walk below is stricter still.
///
/// **Walking the tree.**  Neighbouring particles open nearly the same nodes, so the walk goes
/// down the tree of targets and the tree of sources together (after the interaction lists of
/// Warren & Salmon 1993 and Dehnen 2002).  A target node T -- the sphere of radius
/// \f$ r_\mathrm{max}(T) \f$ about its centre of mass, which holds all its particles -- tests
/// each candidate source node S with the criterion at the sphere's nearest point (d minus T's
/// radius in place of d, T's largest smoothing length in place of \f$ h_i \f$).  S is accepted
/// for all of T's particles at once; or, if S is larger than T, opened here; or else left to T's
/// children, whose smaller spheres may accept it.  So a distant node is tested once for a large
/// target, not once for every particle inside it.  At the bottom, a group -- a few neighbouring
/// leaves, at most `group_size` particles -- opens what is left down to single leaves, whose
/// particles form its particle list.  A node accepted for a target is one that each of its
/// particles would have accepted on its own, so the error can only be smaller than that of a
/// walk particle by particle.  Then every particle of the group sums the two lists -- the nodes
/// accepted by the group and by all its ancestors, and the particles -- in a tight loop that the
/// compiler runs several entries at a time in SIMD registers.  The particles are stored in tree
/// order (each node's particles side by side in memory), and the results go back to the
/// particles' own indices.
///
/// **Single precision.**  The Newtonian terms -- the multipoles, and the pairs beyond both
/// kernels' support -- are summed in single precision, measured from the group's centre and in
/// units near the size and the mass of the system (powers of two, so exact): a node's pull is
/// only good to the tree's error, and seven digits of a pair's are far below it, while a SIMD
/// register holds twice as many floats as doubles.  The softened pairs are summed in double
/// precision, and so are the pairs nearer than \f$ 10^{-12} \f$ of the size of the system
/// (no node that near is accepted), below the range of single precision.
///
/// **Where it fails.**  The error of each node is relative to that node's pull, not to the total
/// force.  Where the pulls of all sides nearly cancel -- near the centre of a uniform sphere, or
/// anywhere in a nearly uniform medium -- the net force is small and the tree's absolute error
/// is not, so the relative error of that small force is large.  And the tree is not
/// antisymmetric: particle i may see particle j through a node while j sees i directly, so the
/// forces of a pair are not exactly equal and opposite, and the total momentum is conserved
/// only to about the force error, not to round-off as with direct summation
/// (gravity/direct.hpp).
///
/// **Building.**  The tree is rebuilt at every evaluation from the current positions.  A node's
/// particles are split into the eight octants about the centre of their bounding box, and each
/// non-empty octant becomes a child, until a node holds at most `leaf_size` particles.  The box
/// is the tight box of the node's own particles, so a particle thrown far out costs one level,
/// not one level per factor of two in distance.  A node whose particles cannot be split (they
/// sit at one point, or their distances are lost to round-off) or that lies deeper than
/// `max_depth` stays a leaf, with more particles.  The top levels are built by one thread and
/// the subtrees below them by all threads, but the tree's shape depends on the particles only,
/// and every sum runs in a fixed order: the result is the same to the bit for any number of
/// threads.
///
/// The potential \f$ \Phi_i \f$ includes, as in gravity/direct.hpp, a particle's own softened
/// self-potential \f$ -\tfrac75 Gm_i/h_i \f$ (the particle is on its own group's particle list, at
/// r = 0), so that the two modules' potential energies agree to the tree's error.

#include "sph/box.hpp"
#include "sph/error.hpp"
#include "sph/gravity/direct.hpp"
#include "sph/gravity/softening.hpp"
#include "sph/integration/active_set.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace sph {

/// Self-gravity from a Barnes-Hut octree with monopole or quadrupole nodes.
struct TreeGravity {
  static constexpr const char* name = "Barnes-Hut tree";
  static constexpr bool active = true;

  /// How many terms of a node's multipole expansion the far field keeps.
  enum class Order { monopole, quadrupole };

  /// What the last evaluation did, for the course's tables and the benchmark.
  struct Statistics {
    std::size_t particles = 0;
    std::size_t nodes = 0;   ///< nodes of the tree, leaves included
    std::size_t leaves = 0;  ///< nodes without children
    std::size_t groups = 0;  ///< groups of particles that shared their lists
    int depth = 0;           ///< the deepest level (the root is level 0)
    /// Mean particle-particle interactions per particle (itself included).
    double particle_interactions = 0;
    /// Mean particle-node interactions per particle (multipoles).
    double node_interactions = 0;
    bool relative = false;  ///< whether the walk used the relative criterion
    /// Sorting the particles into the tree, the nodes' moments, the particles' values in the
    /// tree's units.
    double build_seconds = 0;
    double walk_seconds = 0;  ///< the walks and the sums over their lists
  };

  /// theta: on a uniform sphere the 99th percentile of the relative force error is 7e-4 (above).
  static constexpr double default_opening_angle = 0.3;
  /// Which opening criterion the walk uses (see the file comment).
  enum class Criterion { geometric, relative };
  /// alpha of the relative criterion: on a random uniform sphere of 10^4 particles a largest
  /// error two fifths of the geometric default's, on a 1/r sphere the same, with 14 % and 20 %
  /// fewer interactions (tests/sph/test_gravity.cpp).
  static constexpr double default_relative_accuracy = 1e-3;
  /// Leaves of at most 16 particles and groups of at most 32.  Larger groups walk the tree
  /// fewer times and sum more pairs each, and wider SIMD makes the pairs cheaper: with AVX-512
  /// these took the tree on the collapse's states 2-9 % below leaves of 12 and groups of 16
  /// (the choice on an AVX2 machine, where the two were within a few per cent); larger ones
  /// (24 and 48, 32 and 64) are slower again at 22000 particles (docs/design.md).
  static constexpr int default_leaf_size = 16;
  static constexpr int default_group_size = 32;
  /// Nodes deeper than this are leaves, however many particles they hold.
  static constexpr int max_depth = 64;

  double G = 1.0;                                ///< gravitational constant
  double opening_angle = default_opening_angle;  ///< theta of the criterion
  Order order = Order::quadrupole;               ///< monopole or quadrupole far field
  int leaf_size = default_leaf_size;             ///< a node of at most this many is a leaf
  int group_size = default_group_size;           ///< particles that share their lists, at most
  /// A softening length for every particle; 0 (the default): each particle's smoothing length.
  double fixed_softening = 0.0;
  Criterion criterion = Criterion::geometric;            ///< geometric (theta) or relative (alpha)
  double relative_accuracy = default_relative_accuracy;  ///< alpha of the relative criterion

  TreeGravity() = default;
  explicit TreeGravity(double theta, Order far_field = Order::quadrupole,
                       int leaf = default_leaf_size, double g = 1.0)
      : G(g), opening_angle(theta), order(far_field), leaf_size(leaf) {
    validate();
  }

  /// Checks the settings (the constructor does, and every evaluation, since they are public).
  void validate() const {
    require(std::isfinite(G) && G > 0,
            "tree gravity: G must be positive and finite (got " + show(G) + ")");
    require(opening_angle > 0 && opening_angle <= 1.5,
            "tree gravity: the opening angle theta must lie in (0, 1.5] (got " +
                show(opening_angle) + ")");
    require(leaf_size >= 1,
            "tree gravity: the leaf size must be at least 1 (got " + show(leaf_size) + ")");
    require(group_size >= 1,
            "tree gravity: the group size must be at least 1 (got " + show(group_size) + ")");
    require(std::isfinite(fixed_softening) && fixed_softening >= 0,
            "tree gravity: the fixed softening length must be finite and >= 0 (got " +
                show(fixed_softening) + ")");
    require(std::isfinite(relative_accuracy) && relative_accuracy > 0,
            "tree gravity: the relative criterion's alpha must be positive and finite (got " +
                show(relative_accuracy) + ")");
  }

  /// Adds \f$ -\nabla\Phi_i \f$ to the acceleration of every particle of \p active (all by
  /// default) and keeps their \f$ \Phi_i \f$ for the energy.  The tree is built from all
  /// particles; the walk visits only the groups that hold an active particle and sums only for
  /// those, with the same lists as for all: an active particle's result is the same to the bit.
  template <int D>
  void add_accelerations(Particles<D>& p, const Box<D>& box, ActiveSet active = {}) {
    require_gravity_input(p, box, "tree gravity");
    if constexpr (D == 3) evaluate(p, active);
  }

  /// \f$ \tfrac12\sum_i m_i\Phi_i \f$ at the last evaluation.
  template <int D>
  double potential_energy(const Particles<D>& p, const Box<D>&) const {
    require(potential_.size() == p.size(),
            "tree gravity: no potential yet (the accelerations were never evaluated)");
    double e = 0;
    for (std::size_t i = 0; i < p.size(); ++i) e += 0.5 * p.mass[i] * potential_[i];
    return e;
  }

  /// Makes the next evaluation use the geometric criterion, as the first does: the relative
  /// criterion reads each particle's |a| of the last evaluation, which belongs to other
  /// particles once the tree is handed a different set (a tree cannot tell such a set from
  /// the same particles moved on, when the count is the same).
  void forget_accelerations() { last_acceleration_.clear(); }

  /// \f$ \Phi_i \f$ at the last evaluation, in the particles' order.
  const std::vector<double>& potential() const { return potential_; }
  /// What the last evaluation did.
  const Statistics& statistics() const { return statistics_; }

 private:
  // --- the tree -----------------------------------------------------------------------------
  // What the walk reads of a node (one cache line).  A node's particles are [begin, end) of the
  // tree order; its children follow it in the node array (depth first), and `skip` is the index
  // just past its subtree: the next node to test when this one is accepted or is a leaf.  The
  // walk then needs no stack.
  struct Node {
    double com[3];  // centre of mass
    double r_max;   // largest distance from com to a particle of the node
    double h_max;   // largest smoothing length of the node's particles
    double reach;   // max(r_max / theta, r_max + 2 h_max): see accepts()
    std::uint32_t begin, end, skip;
    std::uint16_t depth;
    bool leaf;
  };
  // What the far field needs of a node once it is accepted, and the relative criterion.
  struct Multipole {
    double com[3];  // centre of mass
    float mass;     // in the tree's units (see units())
    float quad[6];  // traceless quadrupole about com, xx, xy, xz, yy, yz, zz, in the same units
    float error;    // the relative criterion's M r_max^(p+1) (p: the order kept), in the same units
    float a_min;    // the least |a| of its particles' last evaluation (0: none), likewise
  };
  // Nodes built by one thread, numbered from 0.
  struct Subtree {
    std::vector<Node> nodes;
    std::vector<Multipole> multipoles;
  };
  // The top of the tree in depth-first order: its nodes and, in their places, the subtrees
  // below them that are left to the threads.
  struct TopEntry {
    bool subtree;          // a subtree to build (or a node of the top)
    std::uint32_t begin;   // subtree: its particles [begin, end)
    std::uint32_t end;     // subtree: as above; node: the entry just past its subtree
    std::uint16_t depth;   // the level of the node, or of the subtree's root
    std::uint32_t number;  // subtree: its number; node: its index in top_
  };

  // Entries summed side by side, in double and in single precision: each of W (or V) running
  // sums takes every W-th entry of a list, so the order of the additions is fixed whatever the
  // compiler makes of the loop.
  static constexpr int W = 8;
  static constexpr int V = 16;

  // The lists of one thread, structures of arrays that only grow.  The node list is a stack: a
  // node accepted for a large target stays on it while the target's children and groups are
  // walked, and comes off when the walk leaves the target.
  struct Lists {
    std::size_t nodes = 0, particles = 0;     // list lengths
    std::vector<std::uint32_t> node_index;    // the accepted nodes
    std::vector<double> nx, ny, nz;           // their centres of mass
    std::vector<float> nm, nq[6];             // their moments
    std::vector<float> fx, fy, fz;            // their centres from the group's, see far_from
    std::vector<float> px, py, pz, pm, p4h2;  // the particles (from the group's centre); 4 h^2
    std::vector<std::uint32_t> pt;            // their places in the tree order
    std::vector<std::uint32_t> opened;        // the opened leaves' particles: begin, end
    std::vector<std::uint32_t> softened;      // one particle's pairs within a kernel's support
    std::vector<double> bx, by, bz, bm, bh;   // and their data side by side (bh: 1/h)
    std::vector<std::vector<std::uint32_t>> queue, next;  // candidates, per level of the descent
    std::uint64_t particle_pairs = 0, node_pairs = 0, groups = 0;  // for the statistics

    Lists() : queue(max_depth + 2), next(max_depth + 2) {}
    void push_node(std::uint32_t k, const Multipole& pole) {
      if (nodes == node_index.size()) {
        const std::size_t size = std::max<std::size_t>(256, 2 * nodes);
        node_index.resize(size);
        for (auto* v : {&nx, &ny, &nz}) v->resize(size);
        for (auto* v : {&nm, &nq[0], &nq[1], &nq[2], &nq[3], &nq[4], &nq[5], &fx, &fy, &fz})
          v->resize(size);
      }
      node_index[nodes] = k;
      nx[nodes] = pole.com[0], ny[nodes] = pole.com[1], nz[nodes] = pole.com[2];
      nm[nodes] = pole.mass;
      for (int c = 0; c < 6; ++c) nq[c][nodes] = pole.quad[c];
      ++nodes;
    }
    // The accepted nodes' centres from the group's centre c, in the tree's unit of length.
    void far_from(const double* c, double length_scale) {
      for (std::size_t k = 0; k < nodes; ++k) {
        fx[k] = static_cast<float>((nx[k] - c[0]) * length_scale);
        fy[k] = static_cast<float>((ny[k] - c[1]) * length_scale);
        fz[k] = static_cast<float>((nz[k] - c[2]) * length_scale);
      }
    }
    void size_particles(std::size_t n) {
      particles = n;
      if (px.size() >= n + W) return;
      for (auto* v : {&px, &py, &pz, &pm, &p4h2}) v->resize(2 * n + W);
      for (auto* v : {&bx, &by, &bz, &bm, &bh}) v->resize(2 * n + W);
      pt.resize(2 * n + W), softened.resize(2 * n + W);
    }
  };

  void evaluate(Particles<3>& p, ActiveSet active) {
    validate();
    const std::size_t n = p.size();
    require(n < std::numeric_limits<std::uint32_t>::max(),
            "tree gravity: too many particles for 32-bit node ranges");
    for (std::size_t i = 0; i < n; ++i) {
      if (!(std::isfinite(p.mass[i]) && p.mass[i] > 0))
        throw Error("tree gravity: particle " + show(i) + " has mass " + show(p.mass[i]) +
                    " (a node's centre of mass needs positive masses)");
    }
    if (active.all() || potential_.size() != n) potential_.assign(n, 0.0);
    statistics_ = Statistics{};
    if (n == 0) return;
    const auto start = std::chrono::steady_clock::now();
    build(p);
    mark_active(active);
    // (kept only for the relative criterion; a later switch to it starts with theta)
    if (criterion != Criterion::relative) {
      last_acceleration_.clear();
    } else if (last_acceleration_.size() != n) {
      last_acceleration_.assign(n, 0.0);
    }
    // (1/h in tree order: a softened pair then costs one division, 1/r; see softening.hpp)
    inv_h_.resize(n), mass_units_.resize(n), four_h2_units_.resize(n);
    for (std::size_t t = 0; t < n; ++t) {
      inv_h_[t] = 1.0 / h_[t];
      // (in the tree's units, for the single-precision pass; pairs nearer than closest_ go to
      // the second pass, in double precision)
      mass_units_[t] = static_cast<float>(m_[t] * mass_scale_);
      const double two_h = std::max(2.0 * h_[t] * length_scale_, closest_);
      four_h2_units_[t] = static_cast<float>(two_h * two_h);
    }
    const auto built = std::chrono::steady_clock::now();
    walk();
    // Back to the particles' own order.
    for (std::size_t t = 0; t < n; ++t) {
      if (!active_at(t)) continue;
      const std::size_t i = index_[t];
      p.acceleration[i] += G * Vec<3>(ax_[t], ay_[t], az_[t]);
      potential_[i] = G * phi_[t];
      if (!last_acceleration_.empty())
        last_acceleration_[i] = G * std::sqrt(ax_[t] * ax_[t] + ay_[t] * ay_[t] + az_[t] * az_[t]);
    }
    const auto done = std::chrono::steady_clock::now();
    statistics_.build_seconds = std::chrono::duration<double>(built - start).count();
    statistics_.walk_seconds = std::chrono::duration<double>(done - built).count();
  }

  // Which tree positions are active: none_active_ empty when all are; otherwise
  // active_before_[t] counts the active particles at tree positions below t, so that a range
  // of the tree order holds an active particle when the two counts at its ends differ.
  void mark_active(ActiveSet active) {
    const std::size_t n = x_.size();
    if (active.all()) {
      active_before_.clear();
      active_count_ = n;
      return;
    }
    flag_.assign(n, 0);
    active_count_ = active.size(n);
    for (std::size_t k = 0; k < active_count_; ++k) flag_[active[k]] = 1;
    active_before_.resize(n + 1);
    active_before_[0] = 0;
    for (std::size_t t = 0; t < n; ++t)
      active_before_[t + 1] = active_before_[t] + flag_[index_[t]];
  }
  bool active_at(std::size_t t) const {
    return active_before_.empty() || active_before_[t + 1] > active_before_[t];
  }
  bool any_active(std::uint32_t begin, std::uint32_t end) const {
    return active_before_.empty() || active_before_[end] > active_before_[begin];
  }
  std::size_t active_in(std::uint32_t begin, std::uint32_t end) const {
    return active_before_.empty() ? end - begin : active_before_[end] - active_before_[begin];
  }

  // --- building -----------------------------------------------------------------------------
  // Nodes with fewer particles than this are built as whole subtrees by one thread.
  static constexpr std::uint32_t subtree_grain = 2048;

  void build(const Particles<3>& p) {
    const std::size_t n = p.size();
    // The particles' data, one array per quantity, sorted into tree order as the tree is built
    // (each node's particles side by side).
    for (auto* v : {&x_, &y_, &z_, &m_, &h_, &a_, &sx_, &sy_, &sz_, &sm_, &sh_, &sa_}) v->resize(n);
    index_.resize(n), sindex_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      x_[i] = p.position[i][0], y_[i] = p.position[i][1], z_[i] = p.position[i][2];
      m_[i] = p.mass[i], h_[i] = fixed_softening > 0 ? fixed_softening : p.smoothing_length[i];
      index_[i] = static_cast<std::uint32_t>(i);
    }
    units();
    // The relative criterion needs every particle's last |a| (in the tree's units, without G).
    relative_ = criterion == Criterion::relative && last_acceleration_.size() == n;
    const double to_units = mass_scale_ / (length_scale_ * length_scale_ * G);
    for (std::size_t i = 0; i < n; ++i) {
      const double a = relative_ ? last_acceleration_[i] * to_units : 0.0;
      a_[i] = std::isfinite(a) ? a : 0.0;
    }
    statistics_.relative = relative_;
    // The top, by one thread; then the subtrees below it, each by one thread into its own
    // arrays; then all joined in depth-first order.
    top_entries_.clear();
    top_.nodes.clear(), top_.multipoles.clear();
    subtree_count_ = 0;
    build_top(0, static_cast<std::uint32_t>(n), 0);
    if (subtrees_.size() < subtree_count_) subtrees_.resize(subtree_count_);
#pragma omp parallel for schedule(dynamic, 1) if (n >= parallel_threshold)
    for (std::size_t e = 0; e < top_entries_.size(); ++e) {
      const TopEntry& entry = top_entries_[e];
      if (!entry.subtree) continue;
      Subtree& s = subtrees_[entry.number];
      s.nodes.clear(), s.multipoles.clear();
      build_subtree(entry.begin, entry.end, entry.depth, s);
    }
    // Where each entry starts in the joined array, and the join.
    first_.resize(top_entries_.size() + 1);
    first_[0] = 0;
    for (std::size_t e = 0; e < top_entries_.size(); ++e) {
      const TopEntry& entry = top_entries_[e];
      first_[e + 1] = first_[e] + static_cast<std::uint32_t>(
                                      entry.subtree ? subtrees_[entry.number].nodes.size() : 1);
    }
    nodes_.resize(first_.back()), multipoles_.resize(first_.back());
    for (std::size_t e = 0; e < top_entries_.size(); ++e) {
      const TopEntry& entry = top_entries_[e];
      const std::uint32_t offset = first_[e];
      if (entry.subtree) {
        const Subtree& s = subtrees_[entry.number];
        for (std::size_t k = 0; k < s.nodes.size(); ++k) {
          nodes_[offset + k] = s.nodes[k];
          nodes_[offset + k].skip += offset;
          multipoles_[offset + k] = s.multipoles[k];
        }
      } else {
        nodes_[offset] = top_.nodes[entry.number];
        nodes_[offset].skip = first_[entry.end];
        multipoles_[offset] = top_.multipoles[entry.number];
      }
    }
    statistics_.particles = n;
    statistics_.nodes = nodes_.size();
    for (const Node& node : nodes_) {
      statistics_.leaves += node.leaf;
      statistics_.depth = std::max<int>(statistics_.depth, node.depth);
    }
  }

  // The tree's units: powers of two near the size of the system and near its mass.  Single
  // precision reaches only from 1e-38 to 3e38, and a cloud measured in centimetres is 1e18
  // across; in these units every distance and mass of the single-precision sums is near 1.
  // Multiplying by a power of two is exact.  Pairs and nodes nearer than closest_ (1e-12 of the
  // size of the system) are left to double precision.
  void units() {
    const std::size_t n = x_.size();
    double lower[3] = {x_[0], y_[0], z_[0]}, upper[3] = {x_[0], y_[0], z_[0]}, mass = 0;
    for (std::size_t i = 0; i < n; ++i) {
      lower[0] = std::min(lower[0], x_[i]), upper[0] = std::max(upper[0], x_[i]);
      lower[1] = std::min(lower[1], y_[i]), upper[1] = std::max(upper[1], y_[i]);
      lower[2] = std::min(lower[2], z_[i]), upper[2] = std::max(upper[2], z_[i]);
      mass += m_[i];
    }
    const double size = std::max({upper[0] - lower[0], upper[1] - lower[1], upper[2] - lower[2]});
    length_scale_ = size > 0 ? std::ldexp(1.0, -std::ilogb(size)) : 1.0;
    mass_scale_ = std::ldexp(1.0, -std::ilogb(mass));
  }

  // The top of the tree: nodes of at least subtree_grain particles, split by one thread.
  void build_top(std::uint32_t begin, std::uint32_t end, int depth) {
    const auto level = static_cast<std::uint16_t>(depth);
    if (end - begin < subtree_grain) {
      top_entries_.push_back({true, begin, end, level, subtree_count_++});
      return;
    }
    const std::size_t self = top_entries_.size();
    top_entries_.push_back(
        {false, begin, end, level, static_cast<std::uint32_t>(top_.nodes.size())});
    std::array<std::uint32_t, 9> bounds{};
    if (add_node(begin, end, depth, top_, bounds)) {
      for (int c = 0; c < 8; ++c) {
        if (bounds[c] != bounds[c + 1]) build_top(bounds[c], bounds[c + 1], depth + 1);
      }
    }
    top_entries_[self].end = static_cast<std::uint32_t>(top_entries_.size());
  }

  // A whole subtree below the top, depth first into `out` (skip counted from out's start).
  void build_subtree(std::uint32_t begin, std::uint32_t end, int depth, Subtree& out) {
    const std::size_t self = out.nodes.size();
    std::array<std::uint32_t, 9> bounds{};
    if (add_node(begin, end, depth, out, bounds)) {
      for (int c = 0; c < 8; ++c) {
        if (bounds[c] != bounds[c + 1]) build_subtree(bounds[c], bounds[c + 1], depth + 1, out);
      }
    }
    out.nodes[self].skip = static_cast<std::uint32_t>(out.nodes.size());
  }

  // Appends the node of the particles [begin, end) to `out`: its moments, r_max, h_max.  Then,
  // unless it is a leaf, sorts its particles by octant about the centre of their bounding box
  // and returns true with the octants' ranges in `bounds`.
  bool add_node(std::uint32_t begin, std::uint32_t end, int depth, Subtree& out,
                std::array<std::uint32_t, 9>& bounds) {
    Node node{};
    Multipole pole{};
    node.begin = begin, node.end = end;
    node.depth = static_cast<std::uint16_t>(depth);
    double mass = 0, mx = 0, my = 0, mz = 0, a_min = a_[begin];
    double lower[3] = {x_[begin], y_[begin], z_[begin]};
    double upper[3] = {x_[begin], y_[begin], z_[begin]};
    for (std::uint32_t t = begin; t < end; ++t) {
      mass += m_[t];
      a_min = std::min(a_min, a_[t]);
      mx += m_[t] * x_[t], my += m_[t] * y_[t], mz += m_[t] * z_[t];
      node.h_max = std::max(node.h_max, h_[t]);
      lower[0] = std::min(lower[0], x_[t]), upper[0] = std::max(upper[0], x_[t]);
      lower[1] = std::min(lower[1], y_[t]), upper[1] = std::max(upper[1], y_[t]);
      lower[2] = std::min(lower[2], z_[t]), upper[2] = std::max(upper[2], z_[t]);
    }
    node.com[0] = mx / mass, node.com[1] = my / mass, node.com[2] = mz / mass;
    // (round-off may put the centre of mass a hair outside the box of coincident particles)
    for (int a = 0; a < 3; ++a) {
      node.com[a] = std::clamp(node.com[a], lower[a], upper[a]);
      pole.com[a] = node.com[a];
    }
    double r2_max = 0, quad[6] = {};
    for (std::uint32_t t = begin; t < end; ++t) {
      const double dx = x_[t] - node.com[0], dy = y_[t] - node.com[1], dz = z_[t] - node.com[2];
      const double r2 = dx * dx + dy * dy + dz * dz, m = m_[t];
      r2_max = std::max(r2_max, r2);
      quad[0] += m * (3 * dx * dx - r2);
      quad[1] += m * 3 * dx * dy;
      quad[2] += m * 3 * dx * dz;
      quad[3] += m * (3 * dy * dy - r2);
      quad[4] += m * 3 * dy * dz;
      quad[5] += m * (3 * dz * dz - r2);
    }
    pole.mass = static_cast<float>(mass * mass_scale_);
    for (int c = 0; c < 6; ++c)
      pole.quad[c] = static_cast<float>(quad[c] * mass_scale_ * length_scale_ * length_scale_);
    node.r_max = std::sqrt(r2_max);
    const double size = node.r_max * length_scale_;
    pole.error =
        static_cast<float>(pole.mass * size * size * (order == Order::quadrupole ? size : 1));
    // (rounded down: a target's least |a| must not exceed any of its particles')
    pole.a_min = static_cast<float>(a_min);
    if (static_cast<double>(pole.a_min) > a_min) pole.a_min = std::nextafter(pole.a_min, 0.0f);
    // (the last term keeps every accepted node farther than closest_: see units())
    node.reach = std::max(
        {node.r_max / opening_angle, node.r_max + 2.0 * node.h_max, closest_ / length_scale_});
    const bool split = end - begin > static_cast<std::uint32_t>(leaf_size) && depth < max_depth &&
                       split_octants(begin, end, lower, upper, bounds);
    node.leaf = !split;
    out.nodes.push_back(node);
    out.multipoles.push_back(pole);
    return split;
  }

  // Sorts the particles [begin, end) by octant about the centre of the box [lower, upper]
  // (stable: octant 0 first, the order inside an octant kept).  False when the particles cannot
  // be split: all in one octant (they coincide, or their distances are lost to round-off).
  bool split_octants(std::uint32_t begin, std::uint32_t end, const double* lower,
                     const double* upper, std::array<std::uint32_t, 9>& bounds) {
    const double cx = 0.5 * (lower[0] + upper[0]), cy = 0.5 * (lower[1] + upper[1]),
                 cz = 0.5 * (lower[2] + upper[2]);
    const auto octant = [&](std::uint32_t t) {
      return (x_[t] >= cx ? 1 : 0) | (y_[t] >= cy ? 2 : 0) | (z_[t] >= cz ? 4 : 0);
    };
    std::array<std::uint32_t, 8> count{};
    for (std::uint32_t t = begin; t < end; ++t) ++count[octant(t)];
    if (*std::max_element(count.begin(), count.end()) == end - begin) return false;
    bounds[0] = begin;
    for (int c = 0; c < 8; ++c) bounds[c + 1] = bounds[c] + count[c];
    std::array<std::uint32_t, 8> next{};
    std::copy(bounds.begin(), bounds.begin() + 8, next.begin());
    for (std::uint32_t t = begin; t < end; ++t) {
      const std::uint32_t s = next[octant(t)]++;
      sx_[s] = x_[t], sy_[s] = y_[t], sz_[s] = z_[t], sm_[s] = m_[t], sh_[s] = h_[t];
      sindex_[s] = index_[t];
      if (relative_) sa_[s] = a_[t];
    }
    for (std::uint32_t t = begin; t < end; ++t) {
      x_[t] = sx_[t], y_[t] = sy_[t], z_[t] = sz_[t], m_[t] = sm_[t], h_[t] = sh_[t];
      index_[t] = sindex_[t];
    }
    if (relative_) std::copy(sa_.begin() + begin, sa_.begin() + end, a_.begin() + begin);
    return true;
  }

  // --- walking ------------------------------------------------------------------------------
  // Whether every particle inside the sphere (centre c, radius r, largest smoothing length
  // h_s, least last acceleration a_s in the tree's units) may use node k as a multipole.  With d
  // the distance between the centres, both conditions of the geometric criterion at the
  // sphere's nearest point, d - r, read \f$ d - r > \max(r_\mathrm{max}/\theta,\;
  // r_\mathrm{max} + 2h_\mathrm{max},\; r_\mathrm{max} + 2h_s) \f$; the first two terms do not
  // depend on the sphere and are kept in Node::reach.  The relative criterion (where a_s > 0)
  // keeps the softening range, and the nearest point beyond the node's sphere, and asks
  // \f$ M r_\mathrm{max}^{p+1} \le \alpha\, a_s\, (d - r)^{p+3} \f$.
  bool accepts(std::uint32_t k, const double* c, double r, double two_h_s, double a_s) const {
    const Node& node = nodes_[k];
    const double dx = node.com[0] - c[0], dy = node.com[1] - c[1], dz = node.com[2] - c[2];
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (!(relative_ && a_s > 0)) {
      const double needed = r + std::max(node.reach, node.r_max + two_h_s);
      return d2 > needed * needed;
    }
    const double needed =
        r + std::max(node.r_max + std::max(2.0 * node.h_max, two_h_s), closest_ / length_scale_);
    if (!(d2 > needed * needed)) return false;
    const double s = (std::sqrt(d2) - r) * length_scale_, s2 = s * s;
    const double reach = s2 * s2 * (order == Order::quadrupole ? s : 1.0);
    return multipoles_[k].error <= relative_accuracy * a_s * reach;
  }

  // A piece of the walk left to one thread: a target node, or a group, with its candidates
  // and the nodes its ancestors accepted.
  struct Task {
    std::uint32_t target, begin, end;  // a target node, or no_node for the group [begin, end)
    std::vector<std::uint32_t> candidates, accepted;
  };
  static constexpr std::uint32_t no_node = std::numeric_limits<std::uint32_t>::max();
  // Targets of at most this many particles are left to the threads whole.
  static constexpr std::uint32_t task_grain = 512;

  void walk() {
    const std::size_t n = x_.size();
    ax_.resize(n), ay_.resize(n), az_.resize(n), phi_.resize(n);
    const auto threads = static_cast<std::size_t>(omp_get_max_threads());
    if (lists_.size() < threads) lists_.resize(threads);
    for (Lists& lists : lists_) {
      lists.nodes = 0;
      lists.particle_pairs = lists.node_pairs = lists.groups = 0;
    }
    // The top of the walk by one thread, down to targets of task_grain particles; then the
    // tasks, each by one thread.  A task's lists are the same whichever thread runs it.
    tasks_.clear();
    const std::uint32_t root = 0;
    visit(nodes_[root].begin, nodes_[root].end, root, &root, 1, 0, lists_[0], true);
#pragma omp parallel for schedule(dynamic, 1) if (n >= parallel_threshold)
    for (std::size_t k = 0; k < tasks_.size(); ++k) {
      Lists& lists = lists_[static_cast<std::size_t>(omp_get_thread_num())];
      const Task& task = tasks_[k];
      lists.nodes = 0;
      for (const std::uint32_t s : task.accepted) lists.push_node(s, multipoles_[s]);
      visit(task.begin, task.end, task.target, task.candidates.data(), task.candidates.size(), 0,
            lists, false);
    }
    std::uint64_t particle_pairs = 0, node_pairs = 0;
    for (const Lists& lists : lists_) {
      particle_pairs += lists.particle_pairs;
      node_pairs += lists.node_pairs;
      statistics_.groups += lists.groups;
    }
    const auto summed = static_cast<double>(std::max<std::size_t>(active_count_, 1));
    statistics_.particle_interactions = static_cast<double>(particle_pairs) / summed;
    statistics_.node_interactions = static_cast<double>(node_pairs) / summed;
  }

  // The targets [begin, end): the target node `target`, or a group when they are few (or one
  // leaf).  When `planning`, targets of at most task_grain active particles become tasks instead
  // (the work of a target is that of its active particles).
  void visit(std::uint32_t begin, std::uint32_t end, std::uint32_t target,
             const std::uint32_t* candidates, std::size_t count, int level, Lists& lists,
             bool planning) {
    if (!any_active(begin, end)) return;  // (no particle here needs its sums)
    const bool group = target == no_node || nodes_[target].leaf ||
                       end - begin <= static_cast<std::uint32_t>(group_size);
    if (planning && (group || active_in(begin, end) <= task_grain)) {
      tasks_.push_back({target,
                        begin,
                        end,
                        {candidates, candidates + count},
                        {lists.node_index.begin(), lists.node_index.begin() + lists.nodes}});
    } else if (group) {
      sum_group(begin, end, candidates, count, lists);
    } else {
      descend(target, candidates, count, level, lists, planning);
    }
  }

  // Target node `target`: sorts the candidates into accepted, opened here and left to the
  // children, then visits the children, gathering small neighbouring ones into groups.
  void descend(std::uint32_t target, const std::uint32_t* candidates, std::size_t count, int level,
               Lists& lists, bool planning) {
    const Node& t = nodes_[target];
    const std::size_t inherited = lists.nodes;
    std::vector<std::uint32_t>& queue = lists.queue[static_cast<std::size_t>(level)];
    std::vector<std::uint32_t>& next = lists.next[static_cast<std::size_t>(level)];
    queue.assign(candidates, candidates + count);
    next.clear();
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::uint32_t s = queue[q];
      const Node& source = nodes_[s];
      if (accepts(s, t.com, t.r_max, 2.0 * t.h_max, multipoles_[target].a_min)) {
        lists.push_node(s, multipoles_[s]);
      } else if (source.leaf || source.r_max < t.r_max) {
        next.push_back(s);
      } else {
        for (std::uint32_t c = s + 1; c < source.skip; c = nodes_[c].skip) queue.push_back(c);
      }
    }
    const auto limit = static_cast<std::uint32_t>(group_size);
    std::uint32_t begin = 0, end = 0;  // small children gathered into one group so far
    const auto flush = [&] {
      if (end > begin)
        visit(begin, end, no_node, next.data(), next.size(), level + 1, lists, planning);
      begin = end = 0;
    };
    for (std::uint32_t c = target + 1; c < t.skip; c = nodes_[c].skip) {
      const Node& child = nodes_[c];
      const std::uint32_t size = child.end - child.begin;
      if (size > limit) {
        flush();
        visit(child.begin, child.end, c, next.data(), next.size(), level + 1, lists, planning);
      } else if (end > begin && end - begin + size <= limit) {
        end = child.end;
      } else {
        flush();
        begin = child.begin, end = child.end;
      }
    }
    flush();
    lists.nodes = inherited;
  }

  // A group, the particles [begin, end): opens the candidates down to the nodes every particle
  // of the group accepts, or to single leaves, then sums both lists for each particle.
  void sum_group(std::uint32_t begin, std::uint32_t end, const std::uint32_t* candidates,
                 std::size_t count, Lists& lists) {
    // The group's sphere: centre of mass, radius about it, largest smoothing length.
    double mass = 0, mx = 0, my = 0, mz = 0, h_g = 0, a_g = a_[begin];
    for (std::uint32_t t = begin; t < end; ++t) {
      mass += m_[t], mx += m_[t] * x_[t], my += m_[t] * y_[t], mz += m_[t] * z_[t];
      h_g = std::max(h_g, h_[t]);
      a_g = std::min(a_g, a_[t]);
    }
    const double centre[3] = {mx / mass, my / mass, mz / mass};
    double r2_max = 0;
    for (std::uint32_t t = begin; t < end; ++t) {
      const double dx = x_[t] - centre[0], dy = y_[t] - centre[1], dz = z_[t] - centre[2];
      r2_max = std::max(r2_max, dx * dx + dy * dy + dz * dz);
    }
    const double r_g = std::sqrt(r2_max), two_h_g = 2.0 * h_g;
    // The walk below the candidates.
    const std::size_t inherited = lists.nodes;
    lists.opened.clear();
    std::size_t particles = 0;
    for (std::size_t c = 0; c < count; ++c) {
      const std::uint32_t last = nodes_[candidates[c]].skip;
      for (std::uint32_t k = candidates[c]; k < last;) {
        const Node& node = nodes_[k];
        if (accepts(k, centre, r_g, two_h_g, a_g)) {
          lists.push_node(k, multipoles_[k]);
          k = node.skip;
        } else if (node.leaf) {
          // (a leaf that follows the previous one in memory extends its range)
          if (!lists.opened.empty() && lists.opened.back() == node.begin) {
            lists.opened.back() = node.end;
          } else {
            lists.opened.push_back(node.begin), lists.opened.push_back(node.end);
          }
          particles += node.end - node.begin;
          k = node.skip;
        } else {
          ++k;
        }
      }
    }
    // Both lists side by side, in single precision from the group's centre.
    lists.size_particles(particles);
    std::size_t j = 0;
    const double cx = centre[0], cy = centre[1], cz = centre[2], scale = length_scale_;
    for (std::size_t r = 0; r < lists.opened.size(); r += 2) {
      const std::uint32_t first = lists.opened[r], count = lists.opened[r + 1] - first;
      const double *x = x_.data() + first, *y = y_.data() + first, *z = z_.data() + first;
      const float *m = mass_units_.data() + first, *four_h2 = four_h2_units_.data() + first;
      float *px = lists.px.data() + j, *py = lists.py.data() + j, *pz = lists.pz.data() + j,
            *pm = lists.pm.data() + j, *p4h2 = lists.p4h2.data() + j;
      std::uint32_t* pt = lists.pt.data() + j;
#pragma omp simd
      for (std::uint32_t e = 0; e < count; ++e) {
        px[e] = static_cast<float>((x[e] - cx) * scale);
        py[e] = static_cast<float>((y[e] - cy) * scale);
        pz[e] = static_cast<float>((z[e] - cz) * scale);
        pm[e] = m[e], p4h2[e] = four_h2[e];
        pt[e] = first + e;
      }
      j += count;
    }
    lists.far_from(centre, length_scale_);
    const std::size_t summed = active_in(begin, end);
    lists.particle_pairs += summed * lists.particles;
    lists.node_pairs += summed * lists.nodes;
    ++lists.groups;
    for (std::uint32_t t = begin; t < end; ++t) {
      if (!active_at(t)) continue;
      if (order == Order::quadrupole) {
        sum_lists<true>(lists, t, centre);
      } else {
        sum_lists<false>(lists, t, centre);
      }
    }
    lists.nodes = inherited;
  }

  // Particle t's sums over both lists, in three phases: the far field (the accepted nodes),
  // the near field's Newtonian pairs, and the near field's softened pairs.  The first two sum
  // in single precision, in the tree's units, a block of entries at a time into one running sum
  // per entry of the block (`#pragma omp simd` asks the compiler to compute the entries of a
  // block together in SIMD registers; each goes to its own sum, so the arithmetic is exactly
  // that of one entry at a time); the third in double precision.  The sums are added up at the
  // end in a fixed order.  The two near-field phases are inlined here (`always_inline`): called
  // as functions of their own they made the tree's evaluation 1-2 % slower.
  template <bool quadrupole>
  void sum_lists(Lists& lists, std::uint32_t t, const double* centre) {
    const float xi = static_cast<float>((x_[t] - centre[0]) * length_scale_),
                yi = static_cast<float>((y_[t] - centre[1]) * length_scale_),
                zi = static_cast<float>((z_[t] - centre[2]) * length_scale_);
    BlockSums<float, V> near_far;  // in the tree's units
    sum_far_field<quadrupole>(lists, xi, yi, zi, near_far);
    const std::size_t n_softened = sum_newtonian_pairs(lists, t, xi, yi, zi, near_far);
    BlockSums<double, W> softened;
    sum_softened_pairs(lists, t, n_softened, softened);

    // The single-precision sums back from the tree's units (acceleration: mass / length^2,
    // potential: mass / length), then the double-precision ones.
    double sum_x = 0, sum_y = 0, sum_z = 0, sum_phi = 0;
    for (int l = 0; l < V; ++l) {
      sum_x += near_far.x[l], sum_y += near_far.y[l], sum_z += near_far.z[l];
      sum_phi += near_far.phi[l];
    }
    const double to_acceleration = length_scale_ * length_scale_ / mass_scale_;
    sum_x *= to_acceleration, sum_y *= to_acceleration, sum_z *= to_acceleration;
    sum_phi *= length_scale_ / mass_scale_;
    for (int l = 0; l < W; ++l) {
      sum_x += softened.x[l], sum_y += softened.y[l], sum_z += softened.z[l];
      sum_phi += softened.phi[l];
    }
    ax_[t] = sum_x, ay_[t] = sum_y, az_[t] = sum_z, phi_[t] = sum_phi;
  }

  // One running sum per SIMD lane of the acceleration's components and the potential.
  template <class Real, int Lanes>
  struct BlockSums {
    Real x[Lanes] = {}, y[Lanes] = {}, z[Lanes] = {}, phi[Lanes] = {};
  };

  // Far field: the accepted nodes (formula in the file's comment), at the particle's position
  // (xi, yi, zi) in the tree's units.
  template <bool quadrupole>
  void sum_far_field(const Lists& lists, float xi, float yi, float zi,
                     BlockSums<float, V>& sums) const {
    float *fx = sums.x, *fy = sums.y, *fz = sums.z, *fphi = sums.phi;
    const float *nx = lists.fx.data(), *ny = lists.fy.data(), *nz = lists.fz.data(),
                *nm = lists.nm.data();
    const float *q0 = lists.nq[0].data(), *q1 = lists.nq[1].data(), *q2 = lists.nq[2].data(),
                *q3 = lists.nq[3].data(), *q4 = lists.nq[4].data(), *q5 = lists.nq[5].data();
    const auto node = [&](std::size_t k, int l) {
      const float dx = xi - nx[k], dy = yi - ny[k], dz = zi - nz[k];
      const float inv_r = 1.0f / std::sqrt(dx * dx + dy * dy + dz * dz);
      const float inv_r2 = inv_r * inv_r, m_r = nm[k] * inv_r;
      float f = m_r * inv_r2, pot = -m_r;
      float ex = 0, ey = 0, ez = 0;  // (Q r) / r^5
      if constexpr (quadrupole) {
        const float qx = q0[k] * dx + q1[k] * dy + q2[k] * dz;
        const float qy = q1[k] * dx + q3[k] * dy + q4[k] * dz;
        const float qz = q2[k] * dx + q4[k] * dy + q5[k] * dz;
        const float inv_r5 = inv_r2 * inv_r2 * inv_r;
        const float rqr_r5 = (dx * qx + dy * qy + dz * qz) * inv_r5;
        f += 2.5f * rqr_r5 * inv_r2;
        pot -= 0.5f * rqr_r5;
        ex = qx * inv_r5, ey = qy * inv_r5, ez = qz * inv_r5;
      }
      fx[l] += ex - f * dx, fy[l] += ey - f * dy, fz[l] += ez - f * dz;
      fphi[l] += pot;
    };
    const std::size_t nodes = lists.nodes, full_nodes = nodes - nodes % V;
    for (std::size_t k = 0; k < full_nodes; k += V) {
#pragma omp simd
      for (int l = 0; l < V; ++l) node(k + l, l);
    }
    for (std::size_t k = full_nodes; k < nodes; ++k) node(k, static_cast<int>(k - full_nodes));
  }

  // Near field, first pass: Newton's force from the particles of the opened leaves farther
  // than both kernels' support; the others -- itself among them -- are noted in
  // lists.softened for the second pass.  Returns how many were noted.
  [[gnu::always_inline]] std::size_t sum_newtonian_pairs(Lists& lists, std::uint32_t t, float xi,
                                                         float yi, float zi,
                                                         BlockSums<float, V>& sums) const {
    float *fx = sums.x, *fy = sums.y, *fz = sums.z, *fphi = sums.phi;
    const float *px = lists.px.data(), *py = lists.py.data(), *pz = lists.pz.data(),
                *pm = lists.pm.data(), *p4h2 = lists.p4h2.data();
    const float four_h2 = four_h2_units_[t];
    const std::size_t pairs = lists.particles, full_pairs = pairs - pairs % V;
    std::uint32_t* softened = lists.softened.data();
    std::size_t n_softened = 0;
    for (std::size_t k = 0; k < full_pairs; k += V) {
      int inside[V], any_inside = 0;
#pragma omp simd reduction(| : any_inside)
      for (int l = 0; l < V; ++l) {
        const float dx = xi - px[k + l], dy = yi - py[k + l], dz = zi - pz[k + l];
        const float r2 = dx * dx + dy * dy + dz * dz, support2 = std::max(four_h2, p4h2[k + l]);
        const float outside = r2 >= support2 ? 1.0f : 0.0f;
        // (inside the support: 1/r at the support, finite, and multiplied by 0)
        const float inv_r = 1.0f / std::sqrt(std::max(r2, support2));
        const float m_r = outside * pm[k + l] * inv_r, f = m_r * inv_r * inv_r;
        fx[l] -= f * dx, fy[l] -= f * dy, fz[l] -= f * dz;
        fphi[l] -= m_r;
        inside[l] = r2 < support2;
        any_inside |= inside[l];
      }
      // (most blocks hold no such pair: the opened leaves' particles lie in tree order, and the
      // ones within a kernel's reach sit together in a few blocks.  The OR is reduced in the SIMD
      // loop, in registers, not lane by lane after it)
      if (any_inside == 0) continue;
      for (int l = 0; l < V; ++l) {
        softened[n_softened] = static_cast<std::uint32_t>(k + l);
        n_softened += static_cast<std::size_t>(inside[l]);
      }
    }
    for (std::size_t k = full_pairs; k < pairs; ++k)
      softened[n_softened++] = static_cast<std::uint32_t>(k);
    return n_softened;
  }

  // Near field, second pass: the n_softened pairs within a kernel's support, in double
  // precision through softening.hpp (at r = 0, itself: no force, and the self-potential
  // -7/5 m/h).  The list is never empty (the particle itself is on it); its pairs are copied
  // side by side and padded to whole blocks with copies of the first, which count with mass 0.
  [[gnu::always_inline]] void sum_softened_pairs(Lists& lists, std::uint32_t t,
                                                 std::size_t n_softened,
                                                 BlockSums<double, W>& sums) const {
    const std::uint32_t* softened = lists.softened.data();
    const std::size_t blocks = (n_softened + W - 1) / W * W;
    double *bx = lists.bx.data(), *by = lists.by.data(), *bz = lists.bz.data(),
           *bm = lists.bm.data(), *bh = lists.bh.data();
    for (std::size_t s = 0; s < blocks; ++s) {
      const std::uint32_t j = lists.pt[softened[s < n_softened ? s : 0]];
      bx[s] = x_[j], by[s] = y_[j], bz[s] = z_[j], bm[s] = s < n_softened ? m_[j] : 0.0;
      bh[s] = inv_h_[j];
    }
    const double x = x_[t], y = y_[t], z = z_[t], inv_h = inv_h_[t];
    double *ax = sums.x, *ay = sums.y, *az = sums.z, *phi = sums.phi;
    for (std::size_t s = 0; s < blocks; s += W) {
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        const double dx = x - bx[s + l], dy = y - by[s + l], dz = z - bz[s + l];
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        const gravity::Softened pair = gravity::pair_softened(r, inv_h, bh[s + l]);
        const double f = bm[s + l] * pair.force_over_r;
        ax[l] -= f * dx, ay[l] -= f * dy, az[l] -= f * dz;
        phi[l] += bm[s + l] * pair.potential;
      }
    }
  }

  // The tree of the last evaluation.
  std::vector<Node> nodes_;
  std::vector<Multipole> multipoles_;
  // The particles in tree order, and the particle index of each tree position.
  std::vector<double> x_, y_, z_, m_, h_;
  std::vector<double> a_;  // the last |a| in the tree's units (0: none), for the relative criterion
  std::vector<std::uint32_t> index_;
  std::vector<double> inv_h_;                      // 1/h, in tree order
  std::vector<float> mass_units_, four_h2_units_;  // m, max(2h, closest_)^2; tree order, units
  // The active particles (see mark_active).
  std::vector<std::uint32_t> active_before_;
  std::vector<std::uint8_t> flag_;
  std::size_t active_count_ = 0;
  // The tree's units (see units()): lengths and masses are multiplied by these powers of two
  // before they are rounded to single precision.
  double length_scale_ = 1, mass_scale_ = 1;
  static constexpr double closest_ = 0x1p-40;
  // Room for sorting (the same quantities), and the build's bookkeeping.
  std::vector<double> sx_, sy_, sz_, sm_, sh_, sa_;
  std::vector<std::uint32_t> sindex_;
  Subtree top_;
  std::vector<TopEntry> top_entries_;
  std::vector<Subtree> subtrees_;  // kept from one evaluation to the next, with their room
  std::uint32_t subtree_count_ = 0;
  std::vector<std::uint32_t> first_;
  // The walk's lists (one per thread, kept from one evaluation to the next) and tasks.
  std::vector<Lists> lists_;
  std::vector<Task> tasks_;
  // Results in tree order (without G), and Phi_i in the particles' order.
  std::vector<double> ax_, ay_, az_, phi_;
  std::vector<double> potential_;
  // |a_i| of each particle's last evaluation (0: never), in the particles' order, and whether
  // this evaluation uses the relative criterion.
  std::vector<double> last_acceleration_;
  bool relative_ = false;
  Statistics statistics_;
};

}  // namespace sph
