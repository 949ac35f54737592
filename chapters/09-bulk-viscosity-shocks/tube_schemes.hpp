#pragma once
/// \file
/// \brief The five ways of holding a shock that chapter 9 compares, as scenes of the tube
/// runner, and what one run of each is measured by.
///
/// Every scene is chapter 5's gas -- the pressure force that heats each particle by its own
/// work, the M4 kernel, the leapfrog, an ideal gas -- with one viscosity in its list of terms.
/// A scene that does not name a term compiles none of it: the standard viscosity's scene has no
/// gradient pass, Watkins' has no pair bracket unless the \f$ \beta \f$ term is asked for.

#include "app/shock_tube_run.hpp"
#include "app/tube_measures.hpp"
#include "sph/measures/norms.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/morris_monaghan_1997.hpp"
#include "sph/terms/pressure.hpp"
#include "sph/terms/selhammar_1997.hpp"
#include "sph/terms/watkins_1996.hpp"

#include <string>
#include <vector>

namespace app::bulk {

/// Watkins et al.'s bulk viscosity: their two passes with \f$ \mu_b = \alpha\rho a h/8 \f$ and
/// no shear (sph::ArtificialBulk), in D dimensions (in 1D the two passes need no curl).
template <int D>
using Bulk = sph::WatkinsViscosity<D, sph::Kernel<D>, sph::ArtificialBulk>;

template <int D>
struct BulkAlone : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureOwnWork, Bulk<D>>;
};
/// The bulk viscosity with the \f$ \beta \f$ term of the standard viscosity (its
/// \f$ \alpha \f$ set to 0), which the paper keeps.
template <int D>
struct BulkWithBeta : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureOwnWork, Bulk<D>, sph::MonaghanGingold1983>;
};
template <int D>
struct Standard : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureOwnWork, sph::MonaghanGingold1983>;
};
template <int D>
struct Modified : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureOwnWork, sph::RestrictedVonNeumannRichtmyer,
                           sph::SelhammarCollective<D>>;
};
template <int D>
struct Switch : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureOwnWork, sph::MorrisMonaghan1997>;
};

/// The schemes of the chapter, and their names in its tables.
enum class Scheme { bulk_beta, bulk_alone, standard, modified, switch_av };
inline const char* name(Scheme s) {
  switch (s) {
    case Scheme::bulk_beta:
      return "bulk viscosity + beta";  // (22 characters at most)
    case Scheme::bulk_alone:
      return "bulk viscosity alone";
    case Scheme::standard:
      return "standard AV";
    case Scheme::modified:
      return "Selhammar modified";
    case Scheme::switch_av:
      return "switch";
  }
  return "?";
}

/// The coefficients every scheme runs with: the papers'.  The bulk viscosity's \f$ \alpha \f$
/// and \f$ \beta \f$ and its reading of \f$ a_0 \f$ are the chapter's options; the standard
/// viscosity is chapter 4's (\f$ \alpha = 1 \f$, \f$ \beta = 2 \f$), Selhammar's terms and the
/// switch chapter 5's, the collective term's \f$ N_n \f$ the scene's neighbour number.
struct SchemeCoefficients {
  sph::ArtificialBulk bulk{1.0, {}};
  double beta = 2.0;
  double neighbours = 50;  ///< \f$ N_n \f$ of the collective term
};

/// The terms of `Scheme` s, in a call of \p run with the scene type and its terms: one place
/// that knows how each scheme is made, for the tubes and the streams alike.
template <int D, class Run>
auto with_scheme(Scheme s, const SchemeCoefficients& k, Run&& run) {
  switch (s) {
    case Scheme::bulk_beta:
      return run.template operator()<BulkWithBeta<D>>(
          {{}, Bulk<D>(k.bulk), sph::MonaghanGingold1983(0.0, k.beta)});
    case Scheme::bulk_alone:
      return run.template operator()<BulkAlone<D>>({{}, Bulk<D>(k.bulk)});
    case Scheme::standard:
      return run.template operator()<Standard<D>>({{}, sph::MonaghanGingold1983()});
    case Scheme::modified:
      return run.template operator()<Modified<D>>({{},
                                                   sph::RestrictedVonNeumannRichtmyer(2.0, 1e-4),
                                                   sph::SelhammarCollective<D>(1.0, k.neighbours)});
    case Scheme::switch_av:
      return run.template operator()<Switch<D>>({{}, sph::MorrisMonaghan1997(0.1, 1.0, 0.1, 1e-4)});
  }
  throw sph::Error("unknown scheme");
}

/// What one run is measured by: the \f$ L_1 \f$ errors in the window \f$ |x| \le 0.5 \f$, the
/// two velocity scatters of chapter 4, the widths of the fronts, the gases' overlap, and what
/// the run conserved.
struct TubeScore {
  std::string scheme;
  std::size_t particles = 0;
  long steps = 0;
  double seconds = 0;
  double l1_rho = 0, l1_v = 0, l1_u = 0;
  double scatter_shocked = 0;    ///< between contact and shock, 2 h-bar clear of each
  double scatter_disturbed = 0;  ///< from the rarefaction's head to 2 h-bar past the shock
  FrontWidths widths;
  GasOverlap overlap;
  double energy_change = 0, momentum_drift = 0;
};

template <int D>
TubeScore score(const std::string& scheme, const TubeRun<D>& run, double t) {
  TubeScore s;
  s.scheme = scheme;
  s.particles = run.particles.size();
  s.steps = run.steps;
  s.seconds = run.seconds;
  const auto e = sph::shock_tube_errors(run.particles, run.exact, t);
  s.l1_rho = e[0].L1;
  s.l1_v = e[1].L1;
  s.l1_u = sph::error_norms<D>(
               "u", run.particles.position, run.particles.internal_energy,
               [&](const sph::Vec<D>& x) { return run.exact.internal_energy(x[0], t); },
               sph::shock_tube_window())
               .L1;
  double h_mean = 0;
  for (double h : run.particles.smoothing_length) h_mean += h / run.particles.size();
  const double contact = run.exact.contact_position(t), shock = run.exact.shock_position(t);
  s.scatter_shocked = velocity_scatter(run, t, contact + 2 * h_mean, shock - 2 * h_mean);
  s.scatter_disturbed =
      velocity_scatter(run, t, run.exact.rarefaction_head_position(t), shock + 2 * h_mean);
  s.widths = front_widths(run, t);
  s.overlap = gas_overlap(run, s.widths.h_star);
  s.energy_change = run.energy_change;
  s.momentum_drift = run.momentum_drift;
  return s;
}

}  // namespace app::bulk
