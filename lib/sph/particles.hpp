#pragma once
/// \file
/// \brief The particle set: a structure of arrays.
///
/// Each field says which pass writes it.  The fields here are the ones every hydrodynamic
/// scene uses; a term that needs more (a smoothed velocity, a curl) keeps its own arrays in its
/// own state, so a scene that does not choose it does not allocate them.
///
/// Passes, in order (after SWIFT's `hydro.h`):
///   smoothing lengths + neighbour list -> density -> equation of state -> force -> kick/drift.

#include "sph/dimension.hpp"
#include "sph/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sph {

/// What the integrator does with a particle.  A fluid particle moves; a fixed boundary particle
/// takes part in the density and force sums like any other (it is a neighbour, it has a
/// density and a pressure) but is never kicked or drifted, and does not limit the time step
/// (Watkins et al. 1996, sect. 4.1).  Only a scene whose boundaries allow it (boundaries/)
/// may have fixed particles.
enum class ParticleKind : std::uint8_t { fluid = 0, fixed = 1 };

/// The particle set of a D-dimensional scene as a structure of arrays: positions,
/// velocities, masses, internal energies, smoothing lengths and the fields each pass writes.
template <int D>
struct Particles {
  // --- set by the initial conditions, advanced by the integrator ---------------------------
  std::vector<Vec<D>> position;  ///< r_i; drifted by the integrator
  std::vector<Vec<D>> velocity;  ///< v_i; kicked by the integrator
  std::vector<double> mass;      ///< m_i; constant
  std::vector<double>
      internal_energy;             ///< u_i, thermal energy per unit mass; kicked by the integrator
  std::vector<ParticleKind> kind;  ///< fluid (moves) or fixed boundary; constant

  // --- written by the smoothing-length pass ------------------------------------------------
  std::vector<double> smoothing_length;  ///< h_i; kernel support is 2 h_i
  std::vector<int> neighbour_count;      ///< number of j != i with r_ij < 2 h_i

  // --- written by the density pass -----------------------------------------------------------
  std::vector<double> density;  ///< rho_i

  // --- written by the equation-of-state pass ----------------------------------------------
  std::vector<double> pressure;     ///< P_i
  std::vector<double> sound_speed;  ///< c_i

  // --- written by the force pass ------------------------------------------------------------
  std::vector<Vec<D>> acceleration;  ///< dv_i/dt
  std::vector<double> energy_rate;   ///< du_i/dt (gases that evolve their energy)

  std::size_t size() const { return position.size(); }

  /// Resize every field to n (new entries zero).
  void resize(std::size_t n) {
    position.resize(n, Vec<D>::Zero());
    velocity.resize(n, Vec<D>::Zero());
    mass.resize(n, 0.0);
    internal_energy.resize(n, 0.0);
    kind.resize(n, ParticleKind::fluid);
    smoothing_length.resize(n, 0.0);
    neighbour_count.resize(n, 0);
    density.resize(n, 0.0);
    pressure.resize(n, 0.0);
    sound_speed.resize(n, 0.0);
    acceleration.resize(n, Vec<D>::Zero());
    energy_rate.resize(n, 0.0);
  }

  /// Append one particle.
  void add(const Vec<D>& x, const Vec<D>& v, double m, double u = 0.0, double h = 0.0,
           ParticleKind k = ParticleKind::fluid) {
    const std::size_t n = size();
    resize(n + 1);
    kind[n] = k;
    position[n] = x;
    velocity[n] = v;
    mass[n] = m;
    internal_energy[n] = u;
    smoothing_length[n] = h;
  }

  /// Check the initial conditions: finite positions and velocities, positive finite masses,
  /// non-negative finite internal energy.  Throws sph::Error naming the first bad particle.
  void validate() const {
    require(size() > 0, "particles: the set is empty");
    require(kind.size() == size(), "particles: the kind array has " + show(kind.size()) +
                                       " entries for " + show(size()) +
                                       " particles (use resize() or add())");
    for (std::size_t i = 0; i < size(); ++i) {
      const bool good = position[i].allFinite() && velocity[i].allFinite() &&
                        std::isfinite(mass[i]) && mass[i] > 0 &&
                        std::isfinite(internal_energy[i]) && internal_energy[i] >= 0;
      if (good) continue;
      const std::string who = "particle " + show(i);
      require(position[i].allFinite(),
              who + " has a non-finite position " + to_string<D>(position[i]));
      require(velocity[i].allFinite(),
              who + " has a non-finite velocity " + to_string<D>(velocity[i]));
      require(std::isfinite(mass[i]) && mass[i] > 0,
              who + " has mass " + show(mass[i]) + " (must be positive and finite)");
      throw Error(who + " has internal energy " + show(internal_energy[i]) +
                  " (must be non-negative and finite)");
    }
  }
};

}  // namespace sph
