#pragma once
/// \file
/// \brief What a pair function sees: the geometry and kinematics of one interacting pair.
///
/// Sign conventions (Selhammar eq 4 read with the sign of his eq 6):
/// \f$ \mathbf r_{ij} = \mathbf r_i - \mathbf r_j \f$,
/// \f$ \mathbf v_{ij} = \mathbf v_i - \mathbf v_j \f$; the pair approaches when
/// \f$ \mathbf r_{ij}\cdot\mathbf v_{ij} < 0 \f$.  The kernel is evaluated at the mean smoothing
/// length \f$ \bar h_{ij} = (h_i + h_j)/2 \f$ (Selhammar eq 1, Watkins eq A4), so
/// \f$ \nabla_i W_{ij} = -\nabla_j W_{ji} \f$ exactly and the forces are equal and opposite.

#include "sph/dimension.hpp"

#include <cstddef>

namespace sph {

/// One interacting pair (i, j) as a term's pair function sees it: separation, relative
/// velocity, kernel gradient and the two particles' state.
template <int D>
struct Pair {
  std::size_t i = 0, j = 0;
  Vec<D> r_ij;          ///< r_i - r_j (periodic image taken into account)
  Vec<D> v_ij;          ///< v_i - v_j
  double r2 = 0;        ///< |r_ij|^2
  double r = 0;         ///< |r_ij|
  double rv = 0;        ///< r_ij . v_ij  (negative when approaching)
  double h_bar = 0;     ///< (h_i + h_j) / 2
  double support2 = 0;  ///< (support * h_bar)^2: the pair is inside the kernel when r2 < support2
  double gradient_factor = 0;  ///< g with grad_i W(r_ij, h_bar) = g r_ij
};

}  // namespace sph
