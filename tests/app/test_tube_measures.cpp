// The measures of a shock tube's run that the papers quote without defining them: the front
// widths, the velocity scatter and the gases' overlap, on made-up profiles whose answers are
// known.
#include "app/tube_measures.hpp"
#include "sph/terms/watkins_1996.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace {

// A 1D "run" of the Monaghan & Gingold tube at t = 0.2: particles every h/20 from -0.6 to 0.6
// carrying the exact solution, except that the shock is a linear ramp of length `shock_ramp`
// and the contact a linear ramp of density of length `contact_ramp`, with alternate particles'
// velocities off by +-noise v*; the left gas is every particle left of the contact.
app::TubeRun<1> made_up_run(double h, double shock_ramp, double contact_ramp, double noise = 0) {
  const sph::ShockTubeSetup mg = sph::ShockTubeSetup::monaghan_gingold();
  app::TubeRun<1> run;
  run.exact = sph::RiemannSolution(mg.left, mg.right, mg.gamma);
  const double t = 0.2, v_star = run.exact.star_velocity();
  const double xs = run.exact.shock_position(t), xc = run.exact.contact_position(t);
  const double rl = run.exact.star_density_left(), rr = run.exact.star_density_right();
  const double dx = h / 20;
  int k = 0;
  for (double x = -0.6; x < 0.6; x += dx, ++k) {
    const sph::GasState s = run.exact.sample(x, t);
    double v = s.velocity, rho = s.density;
    if (std::abs(x - xs) < shock_ramp / 2) v = v_star * (0.5 - (x - xs) / shock_ramp);
    if (std::abs(x - xc) < contact_ramp / 2) rho = rl + (rr - rl) * (0.5 + (x - xc) / contact_ramp);
    v += noise * v_star * (k % 2 == 0 ? 1 : -1);
    run.particles.add(sph::Vec<1>(x), sph::Vec<1>(v), 1.0, 1.0, h);
    run.particles.density.back() = rho;
    if (x < xc) ++run.left_count;
  }
  return run;
}

}  // namespace

TEST_CASE("Tube measures: a linear ramp's 10-90 width is 0.8 of its length", "[tube]") {
  const double h = 0.02;
  const app::TubeRun<1> run = made_up_run(h, 3 * h, 5 * h);
  const app::FrontWidths w = app::front_widths(run, 0.2);
  CHECK(w.h_star == Approx(h));
  CHECK(w.shock == Approx(0.8 * 3).margin(0.05));
  CHECK(w.contact == Approx(0.8 * 5).margin(0.05));
  // A sharp front measures less than two bins (h/2 each): the bin that holds the jump is
  // averaged across it, and the measure does not invent more.
  const app::FrontWidths sharp = app::front_widths(made_up_run(h, 1e-9, 1e-9), 0.2);
  CHECK(sharp.shock < 1.0);
  CHECK(sharp.contact < 1.0);
}

TEST_CASE("Tube measures: oscillations behind a front do not widen it", "[tube]") {
  const double h = 0.02;
  // +-15 % of v* on alternate particles averages out in a bin of ten particles: the width holds.
  const app::FrontWidths w = app::front_widths(made_up_run(h, 3 * h, 5 * h, 0.15), 0.2);
  CHECK(w.shock == Approx(2.4).margin(0.1));
}

TEST_CASE("Tube measures: the scatter is the RMS of the velocity error over v*", "[tube]") {
  const double h = 0.02;
  const app::TubeRun<1> exact = made_up_run(h, 1e-9, 1e-9);
  const app::TubeRun<1> noisy = made_up_run(h, 1e-9, 1e-9, 0.1);
  const double xc = exact.exact.contact_position(0.2), xs = exact.exact.shock_position(0.2);
  CHECK(app::velocity_scatter(exact, 0.2, xc + 0.01, xs - 0.01) == Approx(0).margin(1e-12));
  CHECK(app::velocity_scatter(noisy, 0.2, xc + 0.01, xs - 0.01) == Approx(0.1).epsilon(1e-9));
  CHECK(app::velocity_scatter(noisy, 0.2, 5, 6) == 0);  // (no particles there)
}

TEST_CASE("Tube measures: the gases' overlap counts the particles that crossed", "[tube]") {
  const double h = 0.02, dx = h / 20;
  app::TubeRun<1> run = made_up_run(h, h, h);
  CHECK(app::gas_overlap(run, h).crossed == 0);
  // The left gas's front particle moved 3.5 spacings on: it has passed the right gas's first
  // three (or four) particles, and they it.
  const std::size_t front = run.left_count - 1, rear = run.left_count;
  run.particles.position[front][0] += 3.5 * dx;
  const app::GasOverlap o = app::gas_overlap(run, h);
  const double depth = run.particles.position[front][0] - run.particles.position[rear][0];
  CHECK(o.depth == Approx(depth / h));
  CHECK(o.crossed == 1 + static_cast<std::size_t>(std::floor(depth / dx)) + 1);
}

TEST_CASE("Bulk viscosity of Watkins' shock tube: mu_b = alpha rho a h / 8", "[tube]") {
  const double rho[] = {2.0}, c[] = {3.0}, h[] = {0.5};
  sph::ParticleView<3> in;
  in.rho = rho;
  in.c = c;
  in.h = h;
  const sph::ArtificialBulk local{1.0, {}};
  CHECK(local.bulk_at(0, in) == Approx(2.0 * 3.0 * 0.5 / 8));
  CHECK(local.shear_at(0, in) == 0);
  const sph::ArtificialBulk fixed{2.0, {5.0}};
  CHECK(fixed.bulk_at(0, in) == Approx(2.0 * 2.0 * 5.0 * 0.5 / 8));
}
