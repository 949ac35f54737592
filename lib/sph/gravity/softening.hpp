#pragma once
/// \file
/// \brief The gravity of a particle smeared out like the M4 kernel: the softened potential and
/// force of Price & Monaghan (2007).
///
/// An SPH particle is not a point: its mass is spread over its kernel, \f$ m\,W(r, h) \f$.  Its
/// gravity is then that of this mass distribution.  By Gauss's law the force at distance r is
/// \f$ G\,m(<r)/r^2 \f$ with \f$ m(<r) = m\int_0^r 4\pi r'^2 W(r', h)\,dr' \f$, the mass of the
/// kernel inside r; outside the kernel's support (r >= 2h) it is exactly Newton's.  For the M4
/// kernel, with \f$ q = r/h \f$ (Price & Monaghan 2007, appendix A),
/// \f[ \phi'(r, h) = \frac{1}{h^2}\begin{cases}
///       \tfrac43 q - \tfrac65 q^3 + \tfrac12 q^4, & 0 \le q < 1,
///       \\ \tfrac83 q - 3q^2 + \tfrac65 q^3 - \tfrac16 q^4 - \tfrac{1}{15q^2}, & 1 \le q < 2,
///       \\ 1/q^2, & q \ge 2,
///     \end{cases} \f]
/// \f[ \phi(r, h) = \frac{1}{h}\begin{cases}
///       \tfrac23 q^2 - \tfrac{3}{10} q^4 + \tfrac{1}{10} q^5 - \tfrac75, & 0 \le q < 1,
///       \\ \tfrac43 q^2 - q^3 + \tfrac{3}{10} q^4 - \tfrac{1}{30} q^5 - \tfrac85 + \tfrac{1}{15q},
///         & 1 \le q < 2,
///       \\ -1/q, & q \ge 2,
///     \end{cases} \f]
/// with the potential \f$ \Phi_i = G\sum_j m_j\,\phi(r_{ij}, h) \f$ (phi is negative) and the
/// acceleration
/// \f$ \mathbf a_i = -G\sum_j m_j\,\phi'(r_{ij}, h)\,\hat{\mathbf r}_{ij} \f$.  Both are finite
/// at r = 0: a particle's own potential is \f$ -\tfrac75 Gm/h \f$ and its own force zero.
///
/// Two particles with different h: the pair uses the mean of the two kernels,
/// \f$ \tfrac12[\phi'(r, h_i) + \phi'(r, h_j)] \f$, which keeps the force antisymmetric and
/// momentum conserved (Price & Monaghan 2007, eq 16 without its correction term, see
/// gravity/direct.hpp).  The functions below return \f$ \phi'/r \f$ rather than \f$ \phi' \f$,
/// so that the force is \f$ -Gm_j (\phi'/r)\,\mathbf r_{ij} \f$ without a division and is zero,
/// not NaN, for coincident particles.

#include <algorithm>

namespace sph::gravity {

/// The support of the softened kernel in units of h: Newtonian from r = 2h on.
inline constexpr double softening_support = 2.0;

/// \f$ \phi'(r, h)/r \f$ and \f$ \phi(r, h) \f$ of one kernel.
struct Softened {
  double force_over_r;
  double potential;
};

/// Both for the M4 kernel, from r, 1/r and 1/h (1/r may be infinite at r = 0: the inner
/// piece, the only one used there, does not read it).  The outer piece's terms in 1/q are
/// written with 1/r -- \f$ h^{-3}/(15q^3) = 1/(15r^3) \f$, \f$ h^{-1}/(15q) = 1/(15r) \f$ --
/// so that a pair costs one division, 1/r, when the 1/h of both particles are known: the
/// tree's near field and direct summation evaluate this for every pair within a kernel's
/// support, several pairs at a time (a division is the slowest operation of the pair).
inline Softened m4_softened(double r, double inv_r, double inv_h) {
  const double q = r * inv_h, q2 = q * q;
  const double inv_r3 = inv_r * inv_r * inv_r, inv_h3 = inv_h * inv_h * inv_h;
  if (q >= 2.0) return {inv_r3, -inv_r};
  if (q < 1.0) {
    return {inv_h3 * (4.0 / 3.0 - 1.2 * q2 + 0.5 * q2 * q),
            inv_h * (2.0 / 3.0 * q2 - 0.3 * q2 * q2 + 0.1 * q2 * q2 * q - 1.4)};
  }
  // (8/3 q - 3 q^2 + 6/5 q^3 - 1/6 q^4 - 1/(15 q^2)) / q and the potential's piece
  return {
      inv_h3 * (8.0 / 3.0 - 3.0 * q + 1.2 * q2 - q2 * q / 6.0) - inv_r3 / 15.0,
      inv_h * (4.0 / 3.0 * q2 - q2 * q + 0.3 * q2 * q2 - q2 * q2 * q / 30.0 - 1.6) + inv_r / 15.0};
}

/// \f$ \phi'(r, h)/r \f$ for the M4 kernel, any r >= 0: \f$ 1/r^3 \f$ beyond 2h.
inline double m4_force_over_r(double r, double h) {
  return m4_softened(r, 1.0 / r, 1.0 / h).force_over_r;
}

/// \f$ \phi(r, h) \f$ for the M4 kernel, any r >= 0: \f$ -1/r \f$ beyond 2h, \f$ -1.4/h \f$ at 0.
inline double m4_potential(double r, double h) {
  return m4_softened(r, 1.0 / r, 1.0 / h).potential;
}

/// The pair's force factor \f$ \tfrac12[\phi'(r,h_i) + \phi'(r,h_j)]/r \f$ and potential
/// \f$ \tfrac12[\phi(r,h_i) + \phi(r,h_j)] \f$, from r and both 1/h.
inline Softened pair_softened(double r, double inv_h_i, double inv_h_j) {
  const double inv_r = 1.0 / r;
  const Softened a = m4_softened(r, inv_r, inv_h_i), b = m4_softened(r, inv_r, inv_h_j);
  return {0.5 * (a.force_over_r + b.force_over_r), 0.5 * (a.potential + b.potential)};
}

/// The pair's force factor \f$ \tfrac12[\phi'(r,h_i) + \phi'(r,h_j)]/r \f$.
inline double pair_force_over_r(double r, double h_i, double h_j) {
  return pair_softened(r, 1.0 / h_i, 1.0 / h_j).force_over_r;
}
/// The pair's potential \f$ \tfrac12[\phi(r,h_i) + \phi(r,h_j)] \f$.
inline double pair_potential(double r, double h_i, double h_j) {
  return pair_softened(r, 1.0 / h_i, 1.0 / h_j).potential;
}

}  // namespace sph::gravity
