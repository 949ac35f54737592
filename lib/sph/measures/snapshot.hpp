#pragma once
/// \file
/// \brief Snapshots: one ASCII file per output, in the format SPLASH reads without options.
///
/// SPLASH (Price 2007, PASA 24, 159) reads a whitespace-separated table and guesses everything
/// else from the header.  Its ASCII reader (`read_data_ascii.f90`, `asciiutils.f90`) does so:
///  - **header lines** are the lines before the first two consecutive lines with the same number
///    of numeric columns; ours all start with `#`;
///  - **time**: the first header line whose text after the `#` starts with a real number
///    containing a decimal point; **gamma**: the next header line that starts with a number in
///    (1, 2] (so a line `# time = 0.2` would *not* be read — the number must come first);
///  - **column labels**: a header line of the form `# [01           x]   [02           y] ...`,
///    which is Phantom's and SPLASH's own layout, Fortran `('#',N(1x,'[',i2.2,1x,a11,']',2x))`:
///    a two-digit column number, then the label right-aligned in 11 characters;
///  - **roles** from the labels: `x y z` positions (hence the dimension), `vx vy vz` velocity,
///    `mass`, `h`, `density`, `u` (thermal energy), `pressure`.
///
/// So a file looks like
/// \verbatim
/// # SPH snapshot (SPLASH ascii format; time and gamma are the numbers below)
/// # 450  npart
/// # 1  dimensions
/// # 2.0000000000000001e-01  time
/// # 1.3999999999999999e+00  gamma
/// # [01           x]   [02          vx]   [03        mass]   [04           h]   ...
///   -4.9888888888888888e-01  ...
/// \endverbatim
/// `npart` and `dimensions` come before the time on purpose: they have no decimal point, so
/// SPLASH can take neither for the time, nor (being before it) for gamma.
///
/// Values are written with 17 significant digits, which reproduces every double exactly: the
/// reader below gives back the same numbers, so a snapshot can also serve as a restart.  A file
/// is written to `path.tmp` and renamed, so a reader never sees half a snapshot.  Numbers are
/// formatted and parsed with std::to_chars / std::from_chars, independent of the C locale.

#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <locale>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

/// A snapshot read back: the time, gamma and the particles.
template <int D>
struct Snapshot {
  double time = 0;
  double gamma = 0;
  Particles<D> particles;  ///< position, velocity, mass, h, density, u, pressure; other fields zero
};

namespace splash_ascii {

/// A double with 17 significant digits ("-1.2345678901234567e+00"), independent of the locale.
inline std::string format_number(double x) {
  char text[40];
  const auto result = std::to_chars(text, text + sizeof text, x, std::chars_format::scientific, 16);
  return std::string(text, result.ptr);
}

/// Parse a whole token as a double; false if it is not one.
inline bool parse_number(std::string_view token, double& x) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto result = std::from_chars(token.data(), token.data() + token.size(), x);
  return result.ec == std::errc() && result.ptr == token.data() + token.size();
}

/// One label in SPLASH's column layout: " [07    pressure]" (Fortran 1x,'[',i2.2,1x,a11,']').
inline std::string column_label(int column, const std::string& label) {
  char text[40];
  std::snprintf(text, sizeof text, " [%02d %11.11s]", column, label.c_str());
  return text;
}

/// The label line: "#" then each column_label, two spaces apart.
inline std::string column_label_line(const std::vector<std::string>& labels) {
  std::string line = "#";
  for (std::size_t c = 0; c < labels.size(); ++c) {
    if (c) line += "  ";
    line += column_label(static_cast<int>(c) + 1, labels[c]);
  }
  return line;
}

/// The labels of a label line, in order ("x", "vx", ...); empty if the line is not one.
inline std::vector<std::string> parse_column_labels(const std::string& line) {
  std::vector<std::string> labels;
  std::size_t open = line.find('[');
  while (open != std::string::npos) {
    const std::size_t close = line.find(']', open);
    if (close == std::string::npos) return {};
    // "[07    pressure]": skip the column number, trim the blanks.
    std::string inside = line.substr(open + 1, close - open - 1);
    const std::size_t start = inside.find_first_not_of("0123456789 ");
    const std::size_t end = inside.find_last_not_of(' ');
    labels.push_back(start == std::string::npos ? "" : inside.substr(start, end - start + 1));
    open = line.find('[', close);
  }
  return labels;
}

/// The whitespace-separated tokens of a line.
inline std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

/// Call `write(stream)` on path.tmp, then rename it to path; sph::Error naming the path on
/// failure (the temporary file is removed).
template <class Writer>
void write_file_atomically(const std::string& path, Writer&& write) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    require(static_cast<bool>(out), "cannot write " + path + ": cannot open " + temporary + " (" +
                                        std::strerror(errno) + ")");
    out.imbue(
        std::locale::classic());  // no digit grouping in the integers, whatever the user's locale
    write(out);
    out.close();
    if (!out) {
      std::remove(temporary.c_str());
      throw Error("cannot write " + path + ": writing " + temporary + " failed");
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temporary.c_str());
    throw Error("cannot write " + path + ": renaming " + temporary + " failed (" + reason + ")");
  }
}

/// Write one table row: each number right-aligned in 24 characters.
inline void write_row(std::ostream& out, const double* values, std::size_t count) {
  for (std::size_t c = 0; c < count; ++c) {
    const std::string number = format_number(values[c]);
    out << std::string(number.size() < 24 ? 24 - number.size() : 1, ' ') << number;
  }
  out << '\n';
}

}  // namespace splash_ascii

/// The column labels of a D-dimensional snapshot: x [y z] vx [vy vz] mass h density u pressure.
template <int D>
std::vector<std::string> snapshot_labels() {
  std::vector<std::string> labels;
  for (int a = 0; a < D; ++a) labels.push_back(axis_name(a));
  for (int a = 0; a < D; ++a) labels.push_back(std::string("v") + axis_name(a));
  for (const char* name : {"mass", "h", "density", "u", "pressure"}) labels.push_back(name);
  return labels;
}

/// "dir/stem_00012.dat": the conventional name of output number `index`.
inline std::string snapshot_path(const std::string& directory, const std::string& stem, int index) {
  char number[16];
  std::snprintf(number, sizeof number, "_%05d.dat", index);
  return (directory.empty() ? "" : directory + "/") + stem + number;
}

/// Write one snapshot that SPLASH opens with `splash file` and no options (see the file
/// comment for the layout).  Throws sph::Error naming the path if it cannot be written, or if
/// a field has the wrong number of entries.
template <int D>
void write_snapshot(const std::string& path, const Particles<D>& p, double time, double gamma) {
  using splash_ascii::format_number;
  const std::size_t n = p.size();
  // Every written field must cover every particle.
  for (const auto* field :
       {&p.mass, &p.smoothing_length, &p.density, &p.internal_energy, &p.pressure}) {
    require(field->size() == n, "snapshot " + path + ": a field has " + show(field->size()) +
                                    " entries for " + show(n) + " particles");
  }
  require(p.velocity.size() == n, "snapshot " + path + ": velocity has the wrong size");
  splash_ascii::write_file_atomically(path, [&](std::ostream& out) {
    // Header: npart and dimensions first, then time and gamma (SPLASH takes the first two reals).
    out << "# SPH snapshot (SPLASH ascii format; time and gamma are the numbers below)\n"
        << "# " << n << "  npart\n"
        << "# " << D << "  dimensions\n"
        << "# " << format_number(time) << "  time\n"
        << "# " << format_number(gamma) << "  gamma\n"
        << splash_ascii::column_label_line(snapshot_labels<D>()) << "\n";
    // One row per particle.
    double row[2 * D + 5];
    for (std::size_t i = 0; i < n; ++i) {
      for (int a = 0; a < D; ++a) {
        row[a] = p.position[i][a];
        row[D + a] = p.velocity[i][a];
      }
      const double scalars[5] = {p.mass[i], p.smoothing_length[i], p.density[i],
                                 p.internal_energy[i], p.pressure[i]};
      std::copy(scalars, scalars + 5, row + 2 * D);
      splash_ascii::write_row(out, row, 2 * D + 5);
    }
  });
}

/// Read a snapshot written by write_snapshot back into particles of dimension D.  Throws
/// sph::Error naming the path (and the line) if the file is missing, its dimension is not D, a
/// column is missing, or a row does not parse.
template <int D>
Snapshot<D> read_snapshot(const std::string& path) {
  std::ifstream in(path);
  require(static_cast<bool>(in),
          "cannot read snapshot " + path + " (" + std::strerror(errno) + ")");
  Snapshot<D> snapshot;
  std::map<std::string, double> header;  // "# <number>  <name>" lines
  std::vector<std::string> labels;
  std::vector<std::vector<double>> rows;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    const std::string where = path + " line " + show(line_number);
    const auto tokens = splash_ascii::split(line);
    if (tokens.empty()) continue;
    // A header line: either the labels or "# <number> <name>".
    if (tokens.front().front() == '#') {
      if (line.find('[') != std::string::npos) labels = splash_ascii::parse_column_labels(line);
      double value = 0;
      if (tokens.size() == 3 && tokens[0] == "#" && splash_ascii::parse_number(tokens[1], value)) {
        header[std::string(tokens[2])] = value;
      }
      continue;
    }
    // A data row: as many numbers as labels.
    require(!labels.empty(), where + ": data before the column-label line");
    require(tokens.size() == labels.size(), where + ": " + show(tokens.size()) + " numbers for " +
                                                show(labels.size()) + " columns");
    std::vector<double>& row = rows.emplace_back(tokens.size());
    for (std::size_t c = 0; c < tokens.size(); ++c) {
      require(
          splash_ascii::parse_number(tokens[c], row[c]),
          where + ": column " + show(c + 1) + " '" + std::string(tokens[c]) + "' is not a number");
    }
  }
  // Header values.
  require(header.count("time") && header.count("gamma"),
          "snapshot " + path + ": no time or gamma header line");
  snapshot.time = header["time"];
  snapshot.gamma = header["gamma"];
  if (header.count("dimensions")) {
    require(header["dimensions"] == D, "snapshot " + path + " is " +
                                           show(static_cast<int>(header["dimensions"])) +
                                           "-dimensional, read as " + show(D) + "D");
  }
  if (header.count("npart")) {
    require(header["npart"] == static_cast<double>(rows.size()),
            "snapshot " + path + ": header says " + show(static_cast<long>(header["npart"])) +
                " particles, found " + show(rows.size()) + " rows");
  }
  // Which column holds what.
  const auto column = [&](const std::string& label) {
    for (std::size_t c = 0; c < labels.size(); ++c) {
      if (labels[c] == label) return c;
    }
    throw Error("snapshot " + path + ": no column labelled '" + label + "'");
  };
  if (D < 3) {
    require(
        std::find(labels.begin(), labels.end(), axis_name(D)) == labels.end(),
        "snapshot " + path + " has a column '" + axis_name(D) + "': it is not " + show(D) + "D");
  }
  std::size_t x[D], v[D];
  for (int a = 0; a < D; ++a) {
    x[a] = column(axis_name(a));
    v[a] = column(std::string("v") + axis_name(a));
  }
  const std::size_t m = column("mass"), h = column("h"), rho = column("density"), u = column("u"),
                    P = column("pressure");
  // Fill the particles.
  Particles<D>& p = snapshot.particles;
  p.resize(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::vector<double>& r = rows[i];
    for (int a = 0; a < D; ++a) {
      p.position[i][a] = r[x[a]];
      p.velocity[i][a] = r[v[a]];
    }
    p.mass[i] = r[m];
    p.smoothing_length[i] = r[h];
    p.density[i] = r[rho];
    p.internal_energy[i] = r[u];
    p.pressure[i] = r[P];
  }
  return snapshot;
}

}  // namespace sph
