#pragma once
/// \file
/// \brief The two figures of the homologous compression, in the layout of Selhammar's Figs 3
/// and 4: the energies against time, and the density against radius at maximum compression.
///
/// The program's step4_homologous_sphere(), just above, draws both.  The energy figure has two
/// panels, the whole run and a magnified bounce; the reference is drawn first, wide and light,
/// so that the runs show on top of it.  The density figure has one panel per run (up to four).
/// The panels of the runs that come within a factor ten of the zeroth-order density (eq 26)
/// share one scale, as in the paper, and show that estimate and the reference at the run's own
/// time of maximum compression; a run that stalls far short of it gets its own scale and a note
/// saying so.
///
/// Header-only: a chapter that includes it links sph_plot.

#include "app/homologous_sphere_run.hpp"
#include "plot/figure.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace app {

/// The energies of \p runs (up to four) and of the reference \p ref against time: kinetic
/// solid, thermal dashed, total dotted; written to \p path.
inline void save_sphere_energy_figure(const std::vector<SphereRun>& runs,
                                      const SphereReference& ref,
                                      const sph::HomologousSphereSetup& setup,
                                      const std::string& path, const std::string& title) {
  plot::Figure figure(1, 2, {.width = 1600, .height = 720});
  figure.title(title);
  figure.stamp(plot::Stamp{.kernel = "M4",
                           .neighbours = 64,
                           .particles = setup.particles,
                           .extra = "R = M = 1, v = -2r, u = 0.001, \\gamma = 5/3; E_{kin} falls, "
                                    "E_{th} rises, E_{tot} dotted"});
  const plot::Color colors[] = {plot::black, plot::blue, plot::red, plot::green};
  for (int panel = 0; panel < 2; ++panel) {
    plot::Axes& ax = figure.panel(panel);
    ax.xlabel("t  [code units]").ylabel("energy  [code units]");
    if (panel == 0) {
      ax.xlim(0, 0.7).ylim(-0.02, 1.75).title("the whole run");
    } else {
      ax.xlim(0.44, 0.56).ylim(-0.02, 1.75).title("around maximum compression");
    }
    // The reference first, wide and light, so that the runs show on top of it.
    const plot::Color light{0.7, 0.7, 0.7};
    ax.line(ref.t, ref.kinetic, {.label = "1D Lagrangian reference", .color = light, .width = 5});
    ax.line(ref.t, ref.thermal, {.color = light, .style = plot::Dash::dashed, .width = 5});
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const SphereRun& run = runs[k];
      std::vector<double> total(run.t.size());
      for (std::size_t i = 0; i < total.size(); ++i) total[i] = run.kinetic[i] + run.thermal[i];
      ax.line(run.t, run.kinetic, {.label = run.name, .color = colors[k], .width = 1.8});
      ax.line(run.t, run.thermal, {.color = colors[k], .style = plot::Dash::dashed, .width = 1.8});
      ax.line(run.t, total, {.color = colors[k], .style = plot::Dash::dotted, .width = 1.4});
    }
    ax.text(panel == 0 ? 0.02 : 0.443, 1.62, "solid: E_{kin};  dashed: E_{th};  dotted: E_{tot}");
    if (panel == 0) ax.legend(plot::Corner::upper_right);
  }
  figure.save_png(path);
}

/// The density against the distance from the centre of mass at maximum compression, one panel
/// per run of \p runs (up to four), with the zeroth-order estimate and the reference (\p zones
/// shells) where the run comes near them; written to \p path.
inline void save_sphere_density_figure(const std::vector<SphereRun>& runs,
                                       const sph::HomologousSphereSetup& setup, int zones,
                                       const std::string& path, const std::string& title) {
  plot::Figure figure(2, 2, {.width = 1500, .height = 1100});
  figure.title(title);
  figure.stamp(plot::Stamp{.kernel = "M4",
                           .neighbours = 64,
                           .particles = setup.particles,
                           .extra = "maximum compression = largest density"});
  const double rho_estimate = setup.zeroth_order_density(),
               r_estimate = setup.zeroth_order_radius();
  /// First the common scale.  A run counts as reaching the estimate when its largest density
  /// is within a factor ten of \f$ \rho' \f$.  For each such run the Lagrangian sphere is run
  /// once more, to that run's own time of maximum compression, and the scale is the largest of
  /// the estimate, the runs' peaks and the references' densities, so that no panel on it
  /// clips a peak.
  // The panels whose gas reaches the estimate share one scale, as in the paper.
  const auto compact = [&](const SphereRun& run) { return run.peak_density > 0.1 * rho_estimate; };
  double common = rho_estimate;
  std::vector<sph::LagrangianProfile> refs(runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (!compact(runs[k])) continue;
    refs[k] = homologous_sphere_profile(setup, zones, runs[k].t_maximum);
    common = std::max({common, runs[k].peak_density,
                       *std::max_element(refs[k].density.begin(), refs[k].density.end())});
  }
  /// Then one panel per run: the density of every particle against its distance from the centre
  /// of mass, at the run's maximum compression, with the run's name and that time as heading.
  for (std::size_t k = 0; k < runs.size(); ++k) {
    // The particles' density against their distance from the centre of mass.
    const SphereRun& run = runs[k];
    const sph::Vec<3> centre = sph::centre_of_mass(run.at_maximum);
    std::vector<double> r, rho;
    for (std::size_t i = 0; i < run.at_maximum.size(); ++i) {
      r.push_back((run.at_maximum.position[i] - centre).norm());
      rho.push_back(run.at_maximum.density[i]);
    }
    plot::Axes& ax = figure.panel(static_cast<int>(k));
    char heading[96];
    std::snprintf(heading, sizeof heading, "%s, t = %.4f%s", run.name.c_str(), run.t_maximum,
                  compact(run) ? "" : " (note the scale)");
    ax.title(heading).xlabel("r  [code units]").ylabel("\\rho  [code units]");
    if (compact(run)) ax.xlim(0, 3 * r_estimate).ylim(0, 1.05 * common);
    ax.scatter(r, rho, {.label = "SPH particles", .color = plot::black, .size = 2.0});
    /// On the common scale the estimate is drawn as what eq 26 assumes, a uniform sphere of
    /// radius \f$ R' \f$ -- a step in \f$ \rho(r) \f$ -- beside the reference; a panel on its
    /// own scale gets a note giving the estimate's density instead.
    if (compact(run)) {
      // The estimate as a uniform sphere, and the reference at the same time.
      ax.line(std::vector<double>{0, r_estimate, r_estimate, 3 * r_estimate},
              std::vector<double>{rho_estimate, rho_estimate, 0, 0},
              {.label = "zeroth-order estimate (eq 26)", .color = plot::blue, .width = 1.6});
      ax.line(refs[k].radius, refs[k].density,
              {.label = "1D Lagrangian reference, same t",
               .color = plot::red,
               .style = plot::Dash::dashed,
               .width = 1.6});
    } else {
      char note[96];
      std::snprintf(note, sizeof note, "(the estimate, \\rho' = %.0f, is far off this scale)",
                    rho_estimate);
      // (low on the left, where the profile is high: clear of the particles)
      ax.text(0.03 * *std::max_element(r.begin(), r.end()),
              0.15 * *std::max_element(rho.begin(), rho.end()), note);
    }
    ax.legend(plot::Corner::upper_right);
  }
  figure.save_png(path);
}

}  // namespace app
