#pragma once
/// \file
/// \brief The shock-tube figure every chapter draws: rho, v_x, P and u against x, particles as
/// dots and the exact Riemann solution as a line (the SPLASH convention).
///
/// Several runs can share one figure (e.g. without and with viscosity): each is a Profile with
/// its own label and colour.  In 2D and 3D every particle is drawn at its x, so the scatter of
/// a column of particles about the exact line is visible as it is in the papers' figures.

#include "plot/figure.hpp"
#include "sph/reference/riemann.hpp"
#include "sph/setups/shock_tube.hpp"

#include <string>
#include <vector>

namespace app {

/// One run's particles, reduced to what the figure draws.
struct Profile {
  std::string label;  ///< legend text (markup)
  std::vector<double> x, density, velocity, pressure, internal_energy;
  plot::Color color = plot::black;
  double size = 3.0;  ///< marker diameter in pixels
};

/// Collect the profile of a particle set (only particles within [x_min, x_max]).
template <int D>
Profile make_profile(const sph::Particles<D>& p, std::string label, double x_min = -0.5,
                     double x_max = 0.5, plot::Color color = plot::black) {
  Profile prof{std::move(label), {}, {}, {}, {}, {}, color};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.position[i][0];
    if (x < x_min || x > x_max) continue;
    prof.x.push_back(x);
    prof.density.push_back(p.density[i]);
    prof.velocity.push_back(p.velocity[i][0]);
    prof.pressure.push_back(p.pressure[i]);
    prof.internal_energy.push_back(p.internal_energy[i]);
  }
  // Fewer, larger dots for a few hundred particles; small ones for tens of thousands.
  prof.size = prof.x.size() > 20000 ? 1.5 : (prof.x.size() > 2000 ? 2.2 : 3.5);
  return prof;
}

/// How a shock-tube figure is drawn.
struct ShockTubeFigureOptions {
  double x_min = -0.5, x_max = 0.5;   ///< the window drawn
  std::string exact_label = "exact";  ///< names the line (e.g. the solution of another gas)
  plot::Dash exact_style = plot::Dash::solid;
  bool pressure = true;  ///< false: rho, v, u in one column (Watkins et al. 1996, Fig. 7)
};

/// Draw rho, v, P, u (2 x 2 panels; without P, 3 x 1) of the profiles against the exact
/// solution at time t.
inline plot::Figure shock_tube_figure(const std::vector<Profile>& profiles,
                                      const sph::RiemannSolution& exact, double t,
                                      const std::string& title, const plot::Stamp& stamp,
                                      const ShockTubeFigureOptions& options = {}) {
  sph::require(!profiles.empty(), "shock tube figure: no profiles to draw");
  // The exact solution on a fine grid (it has jumps: 4000 points resolve them to 0.03 % of the
  // window).
  const int samples = 4000;
  std::vector<double> xs(samples), rho(samples), v(samples), P(samples), u(samples);
  for (int k = 0; k < samples; ++k) {
    xs[k] = options.x_min + (options.x_max - options.x_min) * k / (samples - 1);
    const sph::GasState w = exact.sample(xs[k], t);
    rho[k] = w.density;
    v[k] = w.velocity;
    P[k] = w.pressure;
    u[k] = exact.internal_energy(xs[k], t);
  }
  struct Panel {
    const char* label;
    const std::vector<double>* exact_values;
    std::vector<double> Profile::*values;
  };
  std::vector<Panel> panels = {{"\\rho  [code units]", &rho, &Profile::density},
                               {"v_x  [code units]", &v, &Profile::velocity},
                               {"P  [code units]", &P, &Profile::pressure},
                               {"u  [code units]", &u, &Profile::internal_energy}};
  if (!options.pressure) panels.erase(panels.begin() + 2);
  plot::Figure figure = options.pressure ? plot::Figure(2, 2, {.width = 1500, .height = 1100})
                                         : plot::Figure(3, 1, {.width = 1000, .height = 1350});
  figure.title(title);
  figure.stamp(stamp);
  for (std::size_t k = 0; k < panels.size(); ++k) {
    plot::Axes& ax = figure.panel(static_cast<int>(k));
    ax.xlabel("x  [code units]").ylabel(panels[k].label).xlim(options.x_min, options.x_max);
    for (const Profile& prof : profiles) {
      ax.scatter(prof.x, prof.*(panels[k].values),
                 {.label = prof.label, .color = prof.color, .size = prof.size});
    }
    ax.line(xs, *panels[k].exact_values,
            {.label = options.exact_label,
             .color = plot::red,
             .style = options.exact_style,
             .width = 1.6});
    if (k == 0) ax.legend(plot::Corner::upper_right);
  }
  return figure;
}

}  // namespace app
