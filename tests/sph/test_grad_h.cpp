// The grad-h correction: on a uniform 1D lattice Omega is the ratio of the lattice's gradient
// sum to its density sum, so a linear pressure is pushed with exactly -grad P / rho at any
// h/dx, where the plain Hernquist & Katz bracket is off by the gradient sum's bias.
#include "sph/simulation.hpp"
#include "sph/terms/grad_h.hpp"
#include "sph/terms/pressure.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace {

template <class Pressure>
struct Gas : sph::Scene<1> {
  using Terms = sph::Terms<Pressure>;
};

// A lattice of spacing 0.01 on [-1, 1], open ends, rho = 1 nominal, u = (1 + g x)/(gamma - 1)
// with g = 0.5.
// Returns the simulation after its first evaluation.
template <class Pressure>
sph::Simulation<Gas<Pressure>> linear_pressure(double eta) {
  const double dx = 0.01, g = 0.5, gamma = 1.4;
  sph::Particles<1> p;
  for (int k = -100; k < 100; ++k) {
    const double x = (k + 0.5) * dx;
    p.add(sph::Vec<1>(x), sph::Vec<1>(0.0), dx, (1.0 + g * x) / (gamma - 1.0));
  }
  sph::Settings settings;
  settings.smoothing = sph::SmoothingLengthRule::from_density(4.0 * eta);
  return sph::Simulation<Gas<Pressure>>(p, sph::Box<1>::open(), sph::IdealGas(gamma), settings);
}

// The M4 lattice sums at h/dx = eta (as chapter 4 computes them).
std::pair<double, double> lattice_sums(double eta) {
  double density = sph::Kernel<1>::value(0.0, eta), gradient = 0;
  for (int k = 1; k <= 2 * static_cast<int>(eta) + 2; ++k) {
    density += 2.0 * sph::Kernel<1>::value(k, eta);
    gradient -= 2.0 * k * sph::Kernel<1>::derivative(k, eta);
  }
  return {density, gradient};
}

}  // namespace

TEST_CASE("grad-h: Omega on a lattice is the gradient sum over the density sum", "[grad_h]") {
  for (double eta : {1.0, 1.2, 1.5}) {
    const auto sim = linear_pressure<sph::PressureGradH>(eta);
    const std::size_t middle = 100;
    const double h_over_dx = sim.particles().smoothing_length[middle] / 0.01;
    const auto [density, gradient] = lattice_sums(h_over_dx);
    INFO("h/dx = " << h_over_dx);
    CHECK(sim.term<sph::PressureGradH>().omega[middle] == Approx(gradient / density).epsilon(1e-9));
    if (eta == 1.0) CHECK(sim.term<sph::PressureGradH>().omega[middle] == Approx(1.0));
  }
}

TEST_CASE("grad-h: a linear pressure is pushed with -grad P / rho at h = 1.2 dx", "[grad_h]") {
  const std::size_t middle = 100;
  // u is linear, so P = (gamma - 1) rho u = rho (1 + g x) with the lattice's uniform SPH rho:
  // -dP/dx / rho = -g, whatever the density sum's bias.
  const double exact = -0.5;
  const auto grad_h = linear_pressure<sph::PressureGradH>(1.2);
  const auto plain = linear_pressure<sph::PressureHernquistKatz>(1.2);
  const double a_grad_h = grad_h.particles().acceleration[middle][0];
  const double a_plain = plain.particles().acceleration[middle][0];
  CHECK(a_grad_h == Approx(exact).epsilon(1e-9));
  // The plain bracket pushes with the gradient sum over the density sum: 2 % too hard.
  CHECK(a_plain / exact > 1.015);
  CHECK(a_plain / exact < 1.025);
}
