#pragma once
/// \file
/// \brief The pressure force: the symmetric bracket of Hernquist & Katz (1989), and the
/// bracket as Selhammar (1997) eq 4 prints it (for comparison only).
///
/// Both are bracket terms (terms.hpp): the force pass multiplies the bracket by
/// \f$ m_j \nabla_i W(r_{ij}, \bar h_{ij}) \f$, so momentum and energy are conserved by
/// construction, and the loop stays a SIMD loop.

#include "sph/fields.hpp"
#include "sph/pair.hpp"
#include "sph/terms.hpp"

namespace sph {

/// The symmetric pressure bracket of Hernquist & Katz (1989), Selhammar eq 4 as it must be
/// read: \f$ P_i/\rho_i^2 + P_j/\rho_j^2 \f$.
struct PressureHernquistKatz {
  static constexpr const char* name = "Hernquist & Katz (1989)";
  /// What the step adds to its message when a particle's internal energy goes negative.
  static constexpr const char* cooling_hint =
      "if the particle sits beside a much hotter one, this energy equation (the pair's work "
      "shared equally) cools it at its neighbour's rate, which no step follows: the form in "
      "which each particle does the work of its own pressure, sph::PressureOwnWork, does not";
  template <int D>
  Bracket bracket(const Pair<D>& pair, const ParticleView<D>& in) const {
    return {in.p_over_rho2[pair.i] + in.p_over_rho2[pair.j], 0.0};
  }
};

/// The same pressure force, with each particle heated by the work of its own pressure:
/// \f[ \frac{du_i}{dt} = \frac{P_i}{\rho_i^2} \sum_j m_j\, \mathbf v_{ij}\cdot\nabla_i W_{ij}, \f]
/// the SPH form of \f$ du/dt = (P/\rho^2)\, d\rho/dt \f$ (Monaghan 1992), instead of the
/// symmetric \f$ \tfrac12 (P_i/\rho_i^2 + P_j/\rho_j^2) \f$ of Hernquist & Katz.  The momentum
/// equation is the same, and total energy is conserved just as exactly (the two heating factors
/// of a pair add up to the bracket).  The difference shows where a cold particle meets a hot
/// one: in the symmetric form the cold particle is heated or cooled at a rate set by its hot
/// neighbour's pressure, which can remove all its small energy in one step; here its rate is
/// set by its own pressure, a fraction \f$ (\gamma - 1)\nabla\cdot\mathbf v \f$ of its own
/// energy per unit time.
struct PressureOwnWork {
  static constexpr const char* name = "Hernquist & Katz force, own-pressure work";
  template <int D>
  Bracket bracket(const Pair<D>& pair, const ParticleView<D>& in) const {
    return {in.p_over_rho2[pair.i] + in.p_over_rho2[pair.j], 0.0};
  }
  template <int D>
  double heating(const Pair<D>& pair, const ParticleView<D>& in) const {
    return in.p_over_rho2[pair.i];
  }
};

/// Selhammar's eq 4 as printed: \f$ \bar P_{ij}/\bar\rho_{ij}^2 \f$.  Offered only to show what
/// the misprint does (for two equal particles it is half the Hernquist & Katz bracket, so
/// pressure forces are halved); never the default.
struct PressureAsPrinted {
  static constexpr const char* name = "Selhammar eq 4 as printed";
  template <int D>
  Bracket bracket(const Pair<D>& pair, const ParticleView<D>& in) const {
    const double rho_bar = 0.5 * (in.rho[pair.i] + in.rho[pair.j]);
    return {0.5 * (in.pressure[pair.i] + in.pressure[pair.j]) / (rho_bar * rho_bar), 0.0};
  }
};

}  // namespace sph
