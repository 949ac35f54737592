#pragma once
/// \file
/// \brief Totals over the particle set, a check that a pass wrote only finite numbers, and the
/// energy history of a run.
///
/// The totals are the conserved quantities a scene watches:
/// \f[ E_\mathrm{kin} = \sum_i \tfrac12 m_i |\mathbf v_i|^2, \qquad
///     E_\mathrm{th} = \sum_i m_i u_i, \qquad
///     \mathbf P = \sum_i m_i \mathbf v_i, \qquad
///     \mathbf R = \frac{\sum_i m_i \mathbf r_i}{\sum_i m_i} . \f]
/// With the symmetric pair forces of the papers (Selhammar 1997 eq 4) \f$ \mathbf P \f$ is
/// conserved to round-off and \f$ E_\mathrm{kin} + E_\mathrm{th} (+ E_\mathrm{pot}) \f$ to the
/// accuracy of the time integration; Selhammar's Fig 3 and Fig 5 plot these energies over time,
/// which EnergyHistory records.

#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/measures/snapshot.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace sph {

/// \f$ \sum_i m_i \f$.
template <int D>
double total_mass(const Particles<D>& p) {
  double sum = 0;
  for (double m : p.mass) sum += m;
  return sum;
}

/// \f$ E_\mathrm{kin} = \sum_i \tfrac12 m_i |\mathbf v_i|^2 \f$.
template <int D>
double kinetic_energy(const Particles<D>& p) {
  double sum = 0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += 0.5 * p.mass[i] * p.velocity[i].squaredNorm();
  return sum;
}

/// \f$ E_\mathrm{th} = \sum_i m_i u_i \f$.
template <int D>
double thermal_energy(const Particles<D>& p) {
  double sum = 0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += p.mass[i] * p.internal_energy[i];
  return sum;
}

/// \f$ \mathbf P = \sum_i m_i \mathbf v_i \f$.
template <int D>
Vec<D> total_momentum(const Particles<D>& p) {
  Vec<D> sum = Vec<D>::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) sum += p.mass[i] * p.velocity[i];
  return sum;
}

/// \f$ \sum_i m_i |\mathbf v_i| \f$: the scale against which a change of the total momentum is
/// judged.  In a shock tube at rest the total momentum starts at zero and should stay there, so
/// no relative change can be formed; what round-off allows is a fraction \f$ \sim 10^{-16} \f$
/// of the momenta that are being added up, and this is their sum.
template <int D>
double momentum_scale(const Particles<D>& p) {
  double sum = 0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += p.mass[i] * p.velocity[i].norm();
  return sum;
}

/// \f$ \mathbf R = \sum_i m_i \mathbf r_i / \sum_i m_i \f$; an error for zero total mass.
template <int D>
Vec<D> centre_of_mass(const Particles<D>& p) {
  Vec<D> sum = Vec<D>::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) sum += p.mass[i] * p.position[i];
  const double mass = total_mass(p);
  require(mass > 0, "centre of mass: total mass is " + std::to_string(mass));
  return sum / mass;
}

/// All the totals at once.
template <int D>
struct Totals {
  double mass = 0;
  double kinetic = 0;
  double thermal = 0;
  Vec<D> momentum = Vec<D>::Zero();
  Vec<D> centre_of_mass = Vec<D>::Zero();
};

template <int D>
Totals<D> totals(const Particles<D>& p) {
  return {total_mass(p), kinetic_energy(p), thermal_energy(p), total_momentum(p),
          centre_of_mass(p)};
}

// ---------------------------------------------------------------------------------------------
// Finite-value checks

/// The fields of Particles<D>, by name, for check_finite.
enum class Field {
  position,
  velocity,
  mass,
  internal_energy,
  smoothing_length,
  density,
  pressure,
  sound_speed,
  acceleration,
  energy_rate
};

/// The member name of a field ("smoothing_length").
inline const char* field_name(Field f) {
  switch (f) {
    case Field::position:
      return "position";
    case Field::velocity:
      return "velocity";
    case Field::mass:
      return "mass";
    case Field::internal_energy:
      return "internal_energy";
    case Field::smoothing_length:
      return "smoothing_length";
    case Field::density:
      return "density";
    case Field::pressure:
      return "pressure";
    case Field::sound_speed:
      return "sound_speed";
    case Field::acceleration:
      return "acceleration";
    case Field::energy_rate:
      return "energy_rate";
  }
  return "?";
}

namespace diagnostics_detail {

/// "density pass: particle 12 at (0.1, 0.2) has density = nan".
template <int D>
[[noreturn]] void report_non_finite(const Particles<D>& p, std::size_t i, Field f,
                                    const std::string& value, const std::string& pass) {
  throw Error(pass + ": particle " + std::to_string(i) + " at " + to_string<D>(p.position[i]) +
              " has " + field_name(f) + " = " + value + " (not finite)");
}

/// Check one scalar field: the right size and every entry finite.
template <int D>
void check_scalar(const Particles<D>& p, const std::vector<double>& values, Field f,
                  const std::string& pass) {
  require(values.size() == p.size(), pass + ": field " + field_name(f) + " has " +
                                         std::to_string(values.size()) + " entries for " +
                                         std::to_string(p.size()) + " particles");
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) report_non_finite(p, i, f, std::to_string(values[i]), pass);
  }
}

/// Check one vector field the same way.
template <int D>
void check_vector(const Particles<D>& p, const std::vector<Vec<D>>& values, Field f,
                  const std::string& pass) {
  require(values.size() == p.size(), pass + ": field " + field_name(f) + " has " +
                                         std::to_string(values.size()) + " entries for " +
                                         std::to_string(p.size()) + " particles");
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!values[i].allFinite()) report_non_finite(p, i, f, to_string<D>(values[i]), pass);
  }
}

}  // namespace diagnostics_detail

/// Check that the fields a pass wrote are finite for every particle; sph::Error naming the
/// pass, the particle, its position and the field otherwise.
///
/// \code
/// compute_density(p, list);
/// sph::check_finite(p, {sph::Field::density}, "density pass");
/// \endcode
template <int D>
void check_finite(const Particles<D>& p, std::initializer_list<Field> fields,
                  const std::string& pass) {
  using namespace diagnostics_detail;
  for (Field f : fields) {
    switch (f) {
      case Field::position:
        check_vector(p, p.position, f, pass);
        break;
      case Field::velocity:
        check_vector(p, p.velocity, f, pass);
        break;
      case Field::acceleration:
        check_vector(p, p.acceleration, f, pass);
        break;
      case Field::mass:
        check_scalar(p, p.mass, f, pass);
        break;
      case Field::internal_energy:
        check_scalar(p, p.internal_energy, f, pass);
        break;
      case Field::smoothing_length:
        check_scalar(p, p.smoothing_length, f, pass);
        break;
      case Field::density:
        check_scalar(p, p.density, f, pass);
        break;
      case Field::pressure:
        check_scalar(p, p.pressure, f, pass);
        break;
      case Field::sound_speed:
        check_scalar(p, p.sound_speed, f, pass);
        break;
      case Field::energy_rate:
        check_scalar(p, p.energy_rate, f, pass);
        break;
    }
  }
}

/// Check every field of Particles<D>.
template <int D>
void check_all_finite(const Particles<D>& p, const std::string& pass) {
  check_finite(p,
               {Field::position, Field::velocity, Field::mass, Field::internal_energy,
                Field::smoothing_length, Field::density, Field::pressure, Field::sound_speed,
                Field::acceleration, Field::energy_rate},
               pass);
}

// ---------------------------------------------------------------------------------------------
// Energy history

/// Energies against time: E_kin, E_th, optionally E_pot, and their sum.
///
/// \code
/// sph::EnergyHistory energies;
/// energies.record(t, particles);              // no potential energy
/// energies.record(t, particles, potential);   // with self-gravity
/// energies.write(output + "/energies.ev");    // SPLASH reads it like a Phantom .ev file
/// \endcode
class EnergyHistory {
 public:
  std::vector<double> time;
  std::vector<double> kinetic;
  std::vector<double> thermal;
  std::vector<double> potential;  ///< zeros when the scene has no potential energy
  std::vector<double> total;

  /// Append one entry.  A history either always has a potential energy or never.
  void record(double t, double kinetic_energy, double thermal_energy,
              std::optional<double> potential_energy = std::nullopt) {
    require(time.empty() || potential_energy.has_value() == has_potential_,
            "energy history: record " + std::to_string(time.size()) +
                (has_potential_ ? " lacks the potential energy the earlier records have"
                                : " has a potential energy the earlier records lack"));
    require(std::isfinite(t) && std::isfinite(kinetic_energy) && std::isfinite(thermal_energy) &&
                std::isfinite(potential_energy.value_or(0.0)),
            "energy history: non-finite energy at t = " + std::to_string(t) + " (E_kin = " +
                std::to_string(kinetic_energy) + ", E_th = " + std::to_string(thermal_energy) +
                ", E_pot = " + std::to_string(potential_energy.value_or(0.0)) + ")");
    has_potential_ = potential_energy.has_value();
    const double pot = potential_energy.value_or(0.0);
    time.push_back(t);
    kinetic.push_back(kinetic_energy);
    thermal.push_back(thermal_energy);
    potential.push_back(pot);
    total.push_back(kinetic_energy + thermal_energy + pot);
  }

  /// Append the energies of the particles at time t.
  template <int D>
  void record(double t, const Particles<D>& p,
              std::optional<double> potential_energy = std::nullopt) {
    record(t, kinetic_energy(p), thermal_energy(p), potential_energy);
  }

  std::size_t size() const { return time.size(); }
  bool has_potential() const { return has_potential_; }

  /// \f$ \max_t |E_\mathrm{tot}(t) - E_\mathrm{tot}(0)| / |E_\mathrm{tot}(0)| \f$, or the
  /// absolute deviation when \f$ E_\mathrm{tot}(0) = 0 \f$.
  double relative_drift() const {
    require(!total.empty(), "energy history: empty");
    double worst = 0;
    for (double e : total) worst = std::max(worst, std::abs(e - total.front()));
    return total.front() != 0.0 ? worst / std::abs(total.front()) : worst;
  }

  /// Write the history as a SPLASH-readable table (columns time, ekin, etherm, [epot,] etot,
  /// the labels of Phantom's .ev files).
  void write(const std::string& path) const {
    std::vector<std::string> labels = {"time", "ekin", "etherm"};
    if (has_potential_) labels.push_back("epot");
    labels.push_back("etot");
    splash_ascii::write_file_atomically(path, [&](std::ostream& out) {
      out << "# energy history\n" << splash_ascii::column_label_line(labels) << "\n";
      for (std::size_t k = 0; k < size(); ++k) {
        std::vector<double> row = {time[k], kinetic[k], thermal[k]};
        if (has_potential_) row.push_back(potential[k]);
        row.push_back(total[k]);
        splash_ascii::write_row(out, row.data(), row.size());
      }
    });
  }

 private:
  bool has_potential_ = false;
};

}  // namespace sph
