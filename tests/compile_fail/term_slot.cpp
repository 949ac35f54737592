// A term with a member named like a slot but with the wrong signature must not compile: without
// the check the step would never call the member, and the term's physics would silently be
// missing from every run.  tests/CMakeLists.txt compiles this file once as it is (it must
// compile: the check must not refuse a correct term) and once for each misspelt slot below
// (each must fail, with a message that names the slot and the signature it expects).
#include "sph/simulation.hpp"
#include "sph/terms/pressure.hpp"

namespace {

struct Drag {
  double rate = 1.0;

  // A valid bracket, so that the term is recognised by the step whatever else it has.
  template <int D>
  sph::Bracket bracket(const sph::Pair<D>&, const sph::ParticleView<D>&) const {
    return {};
  }

#if defined(SPH_WRONG_AFTER_FORCE)
  // The heating left out: the step's call has four arguments.
  template <int D>
  void after_force(std::size_t, const sph::ParticleView<D>&, sph::Vec<D>& a) {
    a *= 1 - rate;
  }
#elif defined(SPH_BY_VALUE_AFTER_FORCE)
  // The acceleration taken by value: the step's call would compile and change only a copy.
  template <int D>
  void after_force(std::size_t, const sph::ParticleView<D>&, sph::Vec<D> a, double&) {
    a *= 1 - rate;
  }
#elif defined(SPH_WRONG_TIMESTEP)
  // A time-step limit without the name the step reports it by.
  template <int D>
  double timestep(std::size_t, const sph::ParticleView<D>&) const {
    return 1 / rate;
  }
#elif defined(SPH_WRONG_GRADIENT_PASS)
  // A gradient pass whose sum type is missing.
  template <int D>
  void gradient_pair(double& sum, const sph::Pair<D>&, const sph::ParticleView<D>&) const {
    sum += 1;
  }
#else
  // The correct per-particle hook.
  template <int D>
  void after_force(std::size_t, const sph::ParticleView<D>&, sph::Vec<D>& a, double&) {
    a *= 1 - rate;
  }
#endif
};

struct DragScene : sph::Scene<1> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, Drag>;
};

}  // namespace

// Completing the step's type is what checks its terms.
static_assert(sizeof(sph::Simulation<DragScene>) > 0);
