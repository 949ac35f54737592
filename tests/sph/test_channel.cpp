// The pieces of Watkins et al.'s channel (chapter 8): the lattice and its rest density, the
// weakly compressible fluid, fluid confined to one axis, and the one-pass viscosity of Morris,
// Fox & Zhu (1997) and Monaghan's linear viscosity on all pairs, with the walls'
// pseudo-velocity.
#include "sph/boundaries/fixed_particles.hpp"
#include "sph/boundaries/parabolic_walls.hpp"
#include "sph/eos.hpp"
#include "sph/error.hpp"
#include "sph/potential/uniform_field.hpp"
#include "sph/scene.hpp"
#include "sph/setups/poiseuille_channel.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_shear_viscosity.hpp"
#include "sph/terms/morris_fox_zhu_1997.hpp"
#include "sph/terms/pressure.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

namespace {

sph::Settings channel_settings() {
  sph::Settings s;
  s.smoothing = sph::SmoothingLengthRule::fixed();
  s.density = sph::DensityForm::watkins();
  s.fixed_timestep = 2e-4;
  return s;
}

// The channel's particles, the fluid moving on eq 15's parabola (a, g, mu), the walls at rest.
sph::Particles<2> on_parabola(const sph::setups::PoiseuilleChannel& channel, double a, double g,
                              double mu) {
  sph::Particles<2> p = channel.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double y = p.position[i][1];
    if (p.kind[i] == sph::ParticleKind::fluid) p.velocity[i][0] = g * (a * a - y * y) / (2 * mu);
  }
  return p;
}

using Walls = sph::ParabolicWalls<2>;
using OnePass = sph::MorrisFoxZhu1997<2, Walls>;

struct PressureScene : sph::Scene<2> {
  using Eos = sph::WeaklyCompressible;
  using Terms = sph::Terms<sph::PressureHernquistKatz>;
  using Boundaries = sph::FixedParticles;
};
using AllPairs = sph::MonaghanShearViscosity<2, Walls>;
// A weakly compressible fluid with fixed walls and one viscosity term.
template <class Term>
struct ViscousScene : sph::Scene<2> {
  using Eos = sph::WeaklyCompressible;
  using Terms = sph::Terms<Term>;
  using Boundaries = sph::FixedParticles;
};
struct FreeScene : sph::Scene<2> {
  using Eos = sph::Isothermal;
  using Terms = sph::Terms<sph::PressureHernquistKatz>;
  using External = sph::UniformField<2>;
  using Boundaries = sph::FixedParticles;
  using Integrator = sph::PredictorCorrector<2>;
};
struct ConfinedScene : FreeScene {
  using Boundaries = sph::FixedParticlesMovingAlong;
};

}  // namespace

TEST_CASE("Channel: Watkins' lattice, its walls and its rest density", "[channel]") {
  const sph::setups::PoiseuilleChannel channel;
  const sph::Particles<2> p = channel.particles();
  REQUIRE(p.size() == 4900);
  const auto fluid = std::count(p.kind.begin(), p.kind.end(), sph::ParticleKind::fluid);
  CHECK(fluid == 56 * 70);  // 56 rows between the plates, 7 wall rows on each side
  CHECK(channel.smoothing_length() == Approx(1.545 / 70).epsilon(1e-3));
  // The gather sum of the running simulation, far from the walls, is the lattice's rho_0.
  const double rho0 = channel.lattice_density<sph::Kernel<2>>();
  const sph::Simulation<PressureScene> sim(p, channel.box(), sph::WeaklyCompressible(1, rho0),
                                           channel_settings());
  double worst = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (std::abs(p.position[i][1]) < 0.3)
      worst = std::max(worst, std::abs(sim.particles().density[i] / rho0 - 1));
  }
  CHECK(worst < 1e-12);
  CHECK(rho0 == Approx(1.0034).epsilon(1e-4));
  // ... so that the weakly compressible fluid at rest has no pressure and no force.
  double largest = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.kind[i] == sph::ParticleKind::fluid)
      largest = std::max(largest, sim.particles().acceleration[i].norm());
  CHECK(largest < 1e-9);
}

TEST_CASE("Channel: impossible channels are refused by name", "[channel]") {
  sph::setups::PoiseuilleChannel c;
  c.side = 20;  // 2h = 0.154 reaches beyond the walls' 0.1
  CHECK_THROWS_WITH(c.particles(), Catch::Contains("do not reach"));
  c = {};
  c.half_width = 0.6;
  CHECK_THROWS_WITH(c.particles(), Catch::Contains("half-width"));
  c = {};
  c.neighbours = NAN;
  CHECK_THROWS_WITH(c.particles(), Catch::Contains("neighbour number"));
  CHECK_THROWS_WITH(sph::WeaklyCompressible(-1, 1), Catch::Contains("sound speed"));
  CHECK_THROWS_WITH(sph::WeaklyCompressible(1, 0), Catch::Contains("rest density"));
  CHECK(sph::WeaklyCompressible(2, 1.5).pressure(1.5, 0) == 0.0);
}

// Fluid confined to x: a disturbed particle feels pressure across the axis, which the constraint
// removes; it never leaves its line, and its motion along x is untouched.
TEST_CASE("Channel: fluid moving along one axis stays on its line", "[channel]") {
  const sph::setups::PoiseuilleChannel channel{.side = 40};
  sph::Particles<2> p = channel.particles();
  std::size_t moved = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] == sph::ParticleKind::fluid && std::abs(p.position[i][1]) < 0.05) {
      p.position[i] += sph::Vec<2>(0.003, 0.004);  // off the lattice: pushed both ways
      moved = i;
      break;
    }
  }
  const double y0 = p.position[moved][1];
  sph::Simulation<ConfinedScene> sim(p, channel.box(), sph::Isothermal(5),
                                     sph::UniformField<2>(sph::Vec<2>(1.0, 0.0)),
                                     sph::FixedParticlesMovingAlong(0), channel_settings());
  for (int k = 0; k < 50; ++k) sim.step();
  double worst = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    worst = std::max(worst, std::abs(sim.particles().position[i][1] - p.position[i][1]));
    worst = std::max(worst, std::abs(sim.particles().velocity[i][1]));
  }
  CHECK(worst == 0.0);
  CHECK(sim.particles().position[moved][1] == y0);
  // Along x nothing is held back: at the start the accelerations along x are those of the same
  // particles free to move both ways, and across x there are none.
  const sph::Simulation<ConfinedScene> confined(
      p, channel.box(), sph::Isothermal(5), sph::UniformField<2>(sph::Vec<2>(1.0, 0.0)),
      sph::FixedParticlesMovingAlong(0), channel_settings());
  const sph::Simulation<FreeScene> free(p, channel.box(), sph::Isothermal(5),
                                        sph::UniformField<2>(sph::Vec<2>(1.0, 0.0)),
                                        channel_settings());
  CHECK(free.particles().acceleration[moved][1] != 0.0);  // there was something to hold back
  int differ = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] != sph::ParticleKind::fluid) continue;
    if (confined.particles().acceleration[i][0] != free.particles().acceleration[i][0] ||
        confined.particles().acceleration[i][1] != 0.0)
      ++differ;
  }
  CHECK(differ == 0);
  // A particle that starts moving across the axis is refused.
  p.velocity[moved] = sph::Vec<2>(0, 1e-3);
  CHECK_THROWS_WITH(
      sph::Simulation<ConfinedScene>(p, channel.box(), sph::Isothermal(5),
                                     sph::FixedParticlesMovingAlong(0), channel_settings()),
      Catch::Contains("across the axis"));
}

// Morris et al.'s one pass on the steady parabola: mu_s v''/rho = -g at every fluid particle,
// to the lattice's accuracy, with the walls' pseudo-velocity; without it the rows next to the
// walls are wrong by order one.  And its pairs push equally and oppositely.
TEST_CASE("One-pass viscosity: the Poiseuille parabola, the walls, and momentum", "[channel]") {
  const sph::setups::PoiseuilleChannel channel;
  const double a = 0.4, g = 3.6, mu = 0.15;
  const sph::Particles<2> p = on_parabola(channel, a, g, mu);
  const double rho0 = channel.lattice_density<sph::Kernel<2>>();
  const sph::Simulation<ViscousScene<OnePass>> walled(
      p, channel.box(), sph::WeaklyCompressible(1, rho0), OnePass(mu, Walls(0.0, a, 1)),
      channel_settings());
  const sph::Simulation<ViscousScene<sph::MorrisFoxZhu1997<2>>> bare(
      p, channel.box(), sph::WeaklyCompressible(1, rho0), sph::MorrisFoxZhu1997<2>(mu),
      channel_settings());
  double with = 0, without = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] != sph::ParticleKind::fluid) continue;
    with = std::max(with, std::abs(walled.particles().acceleration[i][0] + g) / g);
    without = std::max(without, std::abs(bare.particles().acceleration[i][0] + g) / g);
  }
  INFO("one pass, |a_x + g|/g: " << with << " with the walls' pseudo-velocity, " << without
                                 << " without");
  CHECK(with < 0.05);
  CHECK(without > 1.0);
  // Momentum: the bare term's forces on all particles (walls included) sum to zero.
  sph::Vec<2> net = sph::Vec<2>::Zero();
  double scale = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    net += p.mass[i] * bare.particles().acceleration[i];
    scale += p.mass[i] * bare.particles().acceleration[i].norm();
  }
  CHECK(net.norm() < 1e-12 * scale);
  CHECK_THROWS_WITH(sph::MorrisFoxZhu1997<2>(-1.0), Catch::Contains("shear viscosity"));
}

TEST_CASE("Channel: a row on a plate is refused", "[channel]") {
  const sph::setups::PoiseuilleChannel odd{.side = 35};  // rows at multiples of 1/35: one at 0.4
  CHECK_THROWS_WITH(odd.particles(), Catch::Contains("lies on the plate"));
}

TEST_CASE("Artificial viscosity on all pairs: nu = alpha c h / 8, the parabola, and momentum",
          "[channel]") {
  const sph::setups::PoiseuilleChannel channel;
  sph::Particles<2> p = channel.particles();
  const double a = 0.4, g = 3.6, mu = 0.15, c = 19.2, h = channel.smoothing_length();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double y = p.position[i][1];
    if (p.kind[i] == sph::ParticleKind::fluid) {
      p.velocity[i][0] = g * (a * a - y * y) / (2 * mu);
      p.velocity[i][1] = 0.3 * std::sin(7 * p.position[i][0]);  // (for the bare term's sums)
    }
  }
  const AllPairs term = AllPairs::for_viscosity(mu, c, h, Walls(0.0, a, 1));
  CHECK(term.alpha == Approx(8 * mu / (c * h)));
  CHECK(term.viscosity() == Approx(mu));
  // The parabola's Laplacian: nu d2v/dy2 = -g, on every fluid particle, walls and all.
  const double rho0 = channel.lattice_density<sph::Kernel<2>>();
  sph::Particles<2> straight = p;
  for (auto& v : straight.velocity) v[1] = 0;
  const sph::Simulation<ViscousScene<AllPairs>> walled(
      straight, channel.box(), sph::WeaklyCompressible(1, rho0), term, channel_settings());
  // On the square lattice the directions' fourth moment is not isotropic, and the viscosity
  // seen by this shear is a few per cent off nu (the chapter measures it): every particle,
  // walls or not, sees the same ratio, and it is near 1 (a wrong 2(D+2) would be 25 % off).
  double lowest = 1e9, highest = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] != sph::ParticleKind::fluid) continue;
    const double ratio = -walled.particles().acceleration[i][0] / g;
    lowest = std::min(lowest, ratio);
    highest = std::max(highest, ratio);
  }
  INFO("all pairs with walls, -a_x/g from " << lowest << " to " << highest);
  CHECK(highest - lowest < 0.01);
  CHECK(std::abs(lowest - 1) < 0.07);
  // Without walls every pair pushes its two particles equally and oppositely.
  const sph::Simulation<ViscousScene<sph::MonaghanShearViscosity<2>>> bare(
      p, channel.box(), sph::WeaklyCompressible(1, rho0),
      sph::MonaghanShearViscosity<2>::for_viscosity(mu, c, h), channel_settings());
  sph::Vec<2> net = sph::Vec<2>::Zero();
  double scale = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const sph::Vec<2> f = p.mass[i] * bare.particles().acceleration[i];
    net += f;
    scale += f.norm();
  }
  CHECK(net.norm() < 1e-12 * scale);
  CHECK_THROWS_WITH(AllPairs(-1.0, c, h), Catch::Contains("alpha"));
  CHECK_THROWS_WITH(AllPairs(1.0, 0.0, h), Catch::Contains("sound speed"));
  CHECK_THROWS_WITH(AllPairs::for_viscosity(std::nan(""), c, h), Catch::Contains("nu"));
}

// The kinematic form, mu_i = nu rho_i: on the lattice at rest density rho0 it is the constant
// mu = nu rho0 to round-off; and it refuses a viscosity that is not positive.
TEST_CASE("One-pass viscosity, kinematic: mu = nu rho at each particle", "[channel]") {
  const sph::setups::PoiseuilleChannel channel;
  const double a = 0.4, g = 3.6, mu = 0.15;
  const sph::Particles<2> p = on_parabola(channel, a, g, mu);
  const double rho0 = channel.lattice_density<sph::Kernel<2>>();
  using Bare = sph::MorrisFoxZhu1997<2>;
  const sph::Simulation<ViscousScene<Bare>> constant(
      p, channel.box(), sph::WeaklyCompressible(1, rho0), Bare(mu), channel_settings());
  const sph::Simulation<ViscousScene<Bare>> kinematic(
      p, channel.box(), sph::WeaklyCompressible(1, rho0), Bare::kinematic(mu / rho0),
      channel_settings());
  double worst = 0, scale = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const sph::Vec<2>& x = constant.particles().acceleration[i];
    const double rho = constant.particles().density[i];
    // where the density is the lattice's, mu_i + mu_j = 2 mu; near the walls' edge it is not
    if (std::abs(rho / rho0 - 1) > 1e-12) continue;
    worst = std::max(worst, (x - kinematic.particles().acceleration[i]).norm());
    scale = std::max(scale, x.norm());
  }
  CHECK(scale > 0);
  CHECK(worst < 1e-10 * scale);
  CHECK_THROWS_WITH(Bare::kinematic(0.0), Catch::Contains("kinematic viscosity"));
}
