#pragma once
/// \file
/// \brief The one-dimensional references of the Evrard collapse: app::read_reference_table
/// reads a whitespace-separated table shipped with the chapter, and app::load_evrard_reference
/// reads the two tables of independent codes and runs a third reference with lib/sph's own
/// Lagrangian code.
///
/// The collapse of a sphere is spherically symmetric, so a fine one-dimensional calculation is
/// its exact answer.  The chapter's reference/ directory holds two, each with its provenance:
///
///  - `energies_t0-3_lagrangian_1d.txt`: t, E_kin, E_th, W, E_tot of a Lagrangian code with
///    4000 shells;
///  - `profile_t0.8_finite_volume_1d.txt`: r, rho, v, P (and a fifth column) at t = 0.8 of a
///    finite-volume code with 8000 cells.
///
/// The third, sph::Lagrangian1D with self-gravity (app::run_evrard_lagrangian, in the library
/// because chapter 9 draws it too), is run from the same initial state.
///
/// Header-only, like the chapter's other helper files.

#include "app/evrard_run.hpp"
#include "sph/error.hpp"

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace app {

/// A table of numbers read by columns.
struct ReferenceTable {
  std::vector<std::vector<double>> columns;
};

/// Reads the first \p columns numbers of every row of the file \p path; empty lines and lines
/// starting with `#` are skipped.  Throws sph::Error, naming the file, if it cannot be read, a
/// row is short, or it holds fewer than 10 rows.
inline ReferenceTable read_reference_table(const std::filesystem::path& path, std::size_t columns) {
  std::ifstream in(path);
  if (!in)
    throw sph::Error("cannot read the reference file " + path.string() +
                     " (the chapter reads it from its reference/ directory in the source tree;"
                     " give --reference-dir if it has moved)");
  ReferenceTable table;
  table.columns.resize(columns);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    for (std::size_t c = 0; c < columns; ++c) {
      double value;
      if (!(row >> value))
        throw sph::Error("reference file " + path.string() + ": a row with fewer than " +
                         std::to_string(columns) + " numbers: " + line);
      table.columns[c].push_back(value);
    }
  }
  if (table.columns[0].size() < 10)
    throw sph::Error("reference file " + path.string() + " holds almost no rows");
  return table;
}

/// The references of the Evrard collapse.
struct EvrardReference {
  /// energies: t, E_kin, E_th, W (independent Lagrangian code, 4000 shells)
  std::vector<double> t, kinetic, thermal, potential;
  /// profile at t = 0.8: r, rho, v, P (finite-volume code, 8000 cells)
  std::vector<double> r, rho, v, pressure;
  /// lib/sph's own Lagrangian code: its energies, its profiles at t = 0.8 and at the end
  EvrardLagrangian own;
};

/// Reads the two reference tables from the directory \p dir, and runs lib/sph's Lagrangian code
/// with \p own_zones shells to \p t_end.
inline EvrardReference load_evrard_reference(const std::filesystem::path& dir, int own_zones,
                                             double t_end) {
  EvrardReference ref;
  const ReferenceTable e = read_reference_table(dir / "energies_t0-3_lagrangian_1d.txt", 5);
  ref.t = e.columns[0];
  ref.kinetic = e.columns[1];
  ref.thermal = e.columns[2];
  ref.potential = e.columns[3];
  const ReferenceTable p = read_reference_table(dir / "profile_t0.8_finite_volume_1d.txt", 5);
  ref.r = p.columns[0];
  ref.rho = p.columns[1];
  ref.v = p.columns[2];
  ref.pressure = p.columns[3];
  ref.own = run_evrard_lagrangian(own_zones, t_end);
  return ref;
}

}  // namespace app
