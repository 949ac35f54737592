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
  template <int D>
  Bracket bracket(const Pair<D>& pair, const ParticleView<D>& in) const {
    return {in.p_over_rho2[pair.i] + in.p_over_rho2[pair.j], 0.0};
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
