// literate: turns the chapter programs into Doxygen pages.
//
// A chapter is a directory chapters/NN-name/ holding one program name.cpp (and perhaps helper
// .cpp/.hpp files) and optionally results.md.  In the program, a line whose first non-blank
// characters are "///" (but not "////" or "///<") is prose: Markdown, Doxygen commands and
// LaTeX maths (\f$ ... \f$, \f[ ... \f]).  Every other line is code.  The first prose lines are
//
//     /// \page chNN Chapter NN: Title
//     /// \builds_on chMM            (zero or more; one or more page names per line)
//
// For each chapter this program writes WORK/pages/chNN.md:
//   - the title as a Markdown heading "# Title {#chNN}", then "Builds on: \ref chMM, ..." and
//     where the program lives;
//   - the prose with "/// " stripped, verbatim, and each maximal run of code lines (without
//     leading and trailing blank lines) as a \code{.cpp} ... \endcode block;
//   - the chapter's helper files (the other .cpp/.hpp files of its directory: what only this
//     chapter uses), rendered like the program -- prose verbatim, code in blocks -- each where
//     a prose line "/// \show_file name.hpp" of the program (or of another helper) places it,
//     so that the page shows every line of the chapter's code in the order the text uses it; a
//     helper's `#pragma once` and `\file` lines are left out and its `\brief` becomes a plain
//     sentence.  A helper no \show_file line places is shown at the end, with a warning;
//   - a Results section: the program's console output FIGURES/NN-name/output.txt as a
//     \verbatim block, then results.md (its \image html lines pointed at copies of the figures),
//     or, without results.md, every PNG in FIGURES/NN-name/;
//   - a closing line: previous and next chapter, and the chapters that build on this one.
// Figures are copied to WORK/images/chNN-<file> (Doxygen's IMAGE_PATH) so that equal file
// names in different chapters cannot collide.  A figure that does not exist yet becomes a note
// saying how to make it.
//
// It also writes WORK/pages/chapters.md, the page "The chapters": the chapter map, whose
// \subpage links make the chapters its children in the navigation tree; and
// WORK/pages/mainpage.md from the template given with --mainpage, replacing the line
// @CHAPTER_MAP@ with the same map and @GALLERY@ with one thumbnail per chapter (its first
// figure, copied to WORK/html/gallery/) and lib/plot's demo figure.
//
// Beside each page it writes WORK/origins/chNN.md.txt: for every line of the page, the file and
// line it came from.  `literate --work DIR --explain LOG` prints a Doxygen warning log with the
// locations in generated pages replaced by those in the chapters' own files.
//
// Usage: literate --chapters DIR --figures DIR --mainpage FILE --work DIR [--strict]
// With --strict, any warning (a chapter without a \page line, \builds_on naming an unknown
// page, a figure named in results.md missing after the chapter has run, a prose line ending in
// a backslash, a helper file placed by no \show_file line or twice) makes the exit status 2;
// the pages are written all the same.  An error (an unreadable file, bad arguments) makes
// it 1.

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// ---- Small text helpers -----------------------------------------------------------------------

int warnings = 0;

void warn(const std::string& message) {
  std::cerr << "literate: warning: " << message << "\n";
  ++warnings;
}

std::string read_file(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw std::runtime_error("cannot read " + path.string());
  }
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream stream(text);
  while (std::getline(stream, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

void write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream file(path, std::ios::binary);
  file << text;
  if (!file) {
    throw std::runtime_error("cannot write " + path.string());
  }
}

bool is_blank(const std::string& line) {
  return std::all_of(line.begin(), line.end(),
                     [](unsigned char c) { return std::isspace(c) != 0; });
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream stream(text);
  for (std::string word; stream >> word;) result.push_back(word);
  return result;
}

/// A page being written, line by line, with where each line came from ("file:line", or empty),
/// so that Doxygen's warnings about the page can be traced back to the chapter's own files.
/// A Markdown table row with the bars inside its formulas (\f$ ... \f$) made `\vert` (and
/// `\|` made `\Vert`): Markdown splits a row at every bar, and a formula such as
/// \f$ \sum m|v| \f$ would cut the row into more cells than its header has.
std::string protect_formula_bars(const std::string& row) {
  std::string out;
  bool formula = false;
  for (std::size_t k = 0; k < row.size(); ++k) {
    if (row.compare(k, 3, "\\f$") == 0) {
      formula = !formula;
      out += "\\f$";
      k += 2;
    } else if (formula && row.compare(k, 2, "\\|") == 0) {
      out += "\\Vert ";
      k += 1;
    } else if (formula && row[k] == '|') {
      out += "\\vert ";
    } else {
      out += row[k];
    }
  }
  return out;
}

/// The cells of a Markdown table row: bars outside code spans and formulas, less the outer two.
int table_cells(const std::string& row) {
  int bars = 0;
  bool code = false, formula = false;
  for (std::size_t k = 0; k < row.size(); ++k) {
    if (!formula && row[k] == '`') code = !code;
    if (!code && row.compare(k, 3, "\\f$") == 0) formula = !formula;
    if (row[k] == '\\' && k + 1 < row.size() && row[k + 1] == '|') {
      ++k;  // an escaped bar is text
      continue;
    }
    if (!code && !formula && row[k] == '|') ++bars;
  }
  const std::string t = trim(row);
  return bars - (t.size() > 1 && t.back() == '|' ? 1 : 0);  // "| a | b |": three bars, two cells
}

class Page {
 public:
  /// Appends \p text (one or more lines, without the final newline) taken from \p origin.  Outside
  /// code and verbatim blocks, a table row's formulas lose their bars (protect_formula_bars).
  void add(const std::string& text, const std::string& origin = "") {
    if (text.empty()) {
      lines_.emplace_back();
      origins_.push_back(origin);
      table_row_.push_back(false);
      return;
    }
    for (const std::string& line : split_lines(text)) {
      const std::string t = trim(line);
      if (t == "\\code{.cpp}" || t == "\\verbatim") block_ = true;
      const bool row = !block_ && !t.empty() && t.front() == '|';
      if (t == "\\endcode" || t == "\\endverbatim") block_ = false;
      lines_.push_back(row ? protect_formula_bars(line) : line);
      origins_.push_back(origin);
      table_row_.push_back(row);
    }
  }
  /// Every table row whose number of cells differs from its header's, as "origin: message".
  [[nodiscard]] std::vector<std::string> table_problems() const {
    std::vector<std::string> problems;
    int header = -1;  // the header's cells, -1 outside a table
    for (std::size_t k = 0; k < lines_.size(); ++k) {
      if (!table_row_[k]) {
        header = -1;
        continue;
      }
      const int cells = table_cells(lines_[k]);
      if (header < 0) {
        header = cells;
      } else if (cells != header) {
        problems.push_back(
            (origins_[k].empty() ? "page line " + std::to_string(k + 1) : origins_[k]) +
            ": a table row has " + std::to_string(cells) + " cells, its header " +
            std::to_string(header) + " (a bar in the text? write it \\| or in a formula)");
      }
    }
    return problems;
  }
  /// The page's text.
  [[nodiscard]] std::string text() const {
    std::string out;
    for (const std::string& line : lines_) out += line + "\n";
    return out;
  }
  /// One line per page line: where it came from, or nothing.
  [[nodiscard]] std::string origins() const {
    std::string out;
    for (const std::string& origin : origins_) out += origin + "\n";
    return out;
  }

 private:
  std::vector<std::string> lines_;
  std::vector<std::string> origins_;
  std::vector<bool> table_row_;  ///< per line: a table row (outside code and verbatim blocks)
  bool block_ = false;           ///< the last line added is inside a code or verbatim block
};

/// "file:line" for messages and for the origin of page lines.
std::string at(const fs::path& file, std::size_t line) {
  return file.string() + ":" + std::to_string(line);
}

// ---- Prose and code ---------------------------------------------------------------------------

/// If \p line is prose, its text with the "///" prefix (and one following space) removed.
std::optional<std::string> prose_text(const std::string& line) {
  const auto start = line.find_first_not_of(" \t");
  if (start == std::string::npos || line.compare(start, 3, "///") != 0) return std::nullopt;
  if (start + 3 < line.size() && (line[start + 3] == '/' || line[start + 3] == '<')) {
    return std::nullopt;  // "////..." rules and "///<" member comments are code
  }
  std::string text = line.substr(start + 3);
  if (!text.empty() && text.front() == ' ') text.erase(0, 1);
  return text;
}

/// A line of code and where it came from.
struct CodeLine {
  std::string text;
  std::string origin;
};

/// Appends \p code as a fenced block, without leading and trailing blank lines; nothing if
/// the run is empty.
void emit_code(Page& page, std::vector<CodeLine>& code) {
  auto filled = [](const CodeLine& line) { return !is_blank(line.text); };
  auto first = std::find_if(code.begin(), code.end(), filled);
  auto last = std::find_if(code.rbegin(), code.rend(), filled);
  if (first != code.end()) {
    page.add("");
    page.add("\\code{.cpp}");
    for (auto line = first; line != last.base(); ++line) page.add(line->text, line->origin);
    page.add("\\endcode");
    page.add("");
  }
  code.clear();
}

// ---- Chapters ---------------------------------------------------------------------------------

struct Chapter {
  std::string dir;                     ///< "01-kernel"
  fs::path program;                    ///< chapters/01-kernel/kernel.cpp (full path)
  std::string shown;                   ///< "chapters/01-kernel/kernel.cpp", for messages
  std::vector<fs::path> helpers;       ///< the other .cpp/.hpp/.h files of the chapter
  std::string page;                    ///< "ch01"
  std::string title;                   ///< "Chapter 01: The smoothing kernel"
  std::vector<std::string> builds_on;  ///< page names
  std::string gallery_image;           ///< the first figure shown on the page (copied name)
  fs::path gallery_source;             ///< ... and where it came from
  std::map<std::string, int> figures;  ///< figure file -> its number k in "Fig. N.k"
  std::set<std::string> uses;          ///< library headers the chapter uses ("sph/kernel.hpp")
};

struct Settings {
  fs::path chapters;
  fs::path figures;
  fs::path mainpage;
  fs::path work;
  fs::path explain;  ///< a Doxygen warning log to trace back to the chapters' files
  bool strict = false;
};

/// The name of an executable target for a chapter directory: 01-kernel -> ch01_kernel.
std::string target_name(const std::string& dir) {
  std::string name = "ch" + dir;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

/// Finds a figure called \p file for chapter \p dir: in its own figures directory first, then
/// in the other chapters' directories, then in the figures directory itself.
std::optional<fs::path> find_figure(const Settings& settings, const std::string& dir,
                                    const std::string& file) {
  const fs::path own = settings.figures / dir / file;
  if (fs::is_regular_file(own)) return own;
  if (fs::is_directory(settings.figures)) {
    std::vector<fs::path> others;
    for (const auto& entry : fs::directory_iterator(settings.figures)) {
      if (entry.is_directory()) others.push_back(entry.path());
    }
    std::sort(others.begin(), others.end());
    for (const fs::path& other : others) {
      if (fs::is_regular_file(other / file)) return other / file;
    }
  }
  if (fs::is_regular_file(settings.figures / file)) return settings.figures / file;
  return std::nullopt;
}

/// Copies a figure into WORK/images under a name unique to the chapter page; returns it.
std::string copy_figure(const Settings& settings, Chapter& chapter, const fs::path& source) {
  std::string name = chapter.page + "-" + source.filename().string();
  fs::copy_file(source, settings.work / "images" / name, fs::copy_options::overwrite_existing);
  if (chapter.gallery_image.empty()) {
    chapter.gallery_image = name;
    chapter.gallery_source = source;
  }
  return name;
}

/// The chapter's number N in "Fig. N.k": page "ch04" -> "4".
std::string chapter_number(const Chapter& chapter) {
  std::size_t i = 2;
  while (i + 1 < chapter.page.size() && chapter.page[i] == '0') ++i;
  return chapter.page.substr(i);
}

/// The anchor of figure \p k of a chapter page: "ch04_figure_3".
std::string figure_anchor(const Chapter& chapter, int k) {
  return chapter.page + "_figure_" + std::to_string(k);
}

/// The regular expression of an "\image html file "caption"" command.
const std::regex& image_command() {
  static const std::regex pattern(
      R"re(\\image(\{[^}]*\})?[ \t]+html[ \t]+("[^"]+"|[^ \t"]+)([ \t]+"([^"]*)")?)re");
  return pattern;
}

/// Numbers the figures of a chapter in the order results.md shows them: Fig. N.1, N.2, ...
void number_figures(Chapter& chapter) {
  chapter.figures.clear();
  const fs::path results = chapter.program.parent_path() / "results.md";
  if (!fs::is_regular_file(results)) return;
  const std::string text = read_file(results);
  for (auto it = std::sregex_iterator(text.begin(), text.end(), image_command());
       it != std::sregex_iterator(); ++it) {
    std::string file = (*it)[2].str();
    if (file.front() == '"') file = file.substr(1, file.size() - 2);
    if (!chapter.figures.count(file)) {
      const int k = static_cast<int>(chapter.figures.size()) + 1;
      chapter.figures[file] = k;
    }
  }
}

/// Replaces each "\figref{file.png}" in \p line by a link "Fig. N.k" to that figure of the
/// chapter (numbered by number_figures); an unknown file is a warning.  A figure named as code,
/// "`file.png`", keeps its name and gains the link after it, when the chapter shows it.
std::string cite_figures(const Chapter& chapter, const std::string& line,
                         const std::string& where) {
  static const std::regex figref(R"re(\\figref\{([^}]+)\})re");
  std::string out;
  std::smatch match;
  std::string rest = line;
  while (std::regex_search(rest, match, figref)) {
    out += match.prefix().str();
    const auto found = chapter.figures.find(match[1].str());
    if (found == chapter.figures.end()) {
      warn(where + ": \\figref{" + match[1].str() + "}: results.md shows no such figure");
      out += match[1].str();
    } else {
      out += "\\ref " + figure_anchor(chapter, found->second) + " \"Fig. " +
             chapter_number(chapter) + "." + std::to_string(found->second) + "\"";
    }
    rest = match.suffix().str();
  }
  out += rest;

  static const std::regex named(R"re(`([A-Za-z0-9_.-]+\.png)`)re");
  std::string linked;
  rest = out;
  while (std::regex_search(rest, match, named)) {
    linked += match.prefix().str() + match.str();
    const auto found = chapter.figures.find(match[1].str());
    if (found != chapter.figures.end()) {
      linked += " (\\ref " + figure_anchor(chapter, found->second) + " \"Fig. " +
                chapter_number(chapter) + "." + std::to_string(found->second) + "\")";
    }
    rest = match.suffix().str();
  }
  return linked + rest;
}

/// Rewrites the figure references of results.md: "\image html fig.png ..." and Markdown
/// "![caption](fig.png)" point at the copies; a figure not made yet becomes a note.
std::vector<std::string> resolve_figures(const Settings& settings, Chapter& chapter,
                                         const std::string& text, bool chapter_has_run) {
  static const std::regex markdown_image(R"re(!\[([^\]]*)\]\(([^)\s]+)\))re");
  auto missing = [&](const std::string& file, const std::string& caption) {
    if (chapter_has_run) {
      warn("chapters/" + chapter.dir + "/results.md: figure " + file + " not found in " +
           (settings.figures / chapter.dir).string());
    }
    return "<em>(Figure " + file + (caption.empty() ? "" : ": " + caption) +
           " &mdash; made by running the chapter, e.g. with `scripts/figures.sh`.)</em>";
  };

  std::vector<std::string> result;
  for (const std::string& line : split_lines(text)) {
    std::string out;
    std::smatch match;
    std::string rest = line;
    while (std::regex_search(rest, match, image_command())) {
      out += match.prefix().str();
      std::string file = match[2].str();
      if (file.front() == '"') file = file.substr(1, file.size() - 2);
      const std::string caption = match[4].str();
      if (file.find("://") != std::string::npos) {
        out += match.str();
      } else if (auto source = find_figure(settings, chapter.dir, file)) {
        // Numbered, with an anchor that \figref links to; the page's HTML wraps the image in a
        // link to its full-size file (docs/build_docs.cmake).
        const int k = chapter.figures.count(file) ? chapter.figures.at(file) : 0;
        const std::string number = "Fig. " + chapter_number(chapter) + "." + std::to_string(k);
        out += "\\anchor " + figure_anchor(chapter, k) + "\n\\image" + match[1].str() + " html " +
               copy_figure(settings, chapter, *source) + " \"" + number +
               (caption.empty() ? "" : ": " + caption) + "\"";
      } else {
        out += missing(file, caption);
      }
      rest = match.suffix().str();
    }
    out += rest;

    std::string second;
    rest = out;
    while (std::regex_search(rest, match, markdown_image)) {
      second += match.prefix().str();
      const std::string file = match[2].str();
      if (file.find("://") != std::string::npos) {
        second += match.str();
      } else if (auto source = find_figure(settings, chapter.dir, file)) {
        second += "![" + match[1].str() + "](" + copy_figure(settings, chapter, *source) + ")";
      } else {
        second += missing(file, match[1].str());
      }
      rest = match.suffix().str();
    }
    second += rest;
    // The headings of results.md sit one level below the page's Results section.
    if (!second.empty() && second.front() == '#') second.insert(0, "#");
    result.push_back(cite_figures(chapter, second, "chapters/" + chapter.dir + "/results.md"));
  }
  return result;
}

/// Reads the \page line and the \builds_on lines of a chapter program.  False if it has no
/// \page line.
bool read_header(Chapter& chapter) {
  chapter.page.clear();
  chapter.builds_on.clear();
  for (const std::string& line : split_lines(read_file(chapter.program))) {
    const auto prose = prose_text(line);
    if (!prose) continue;
    const auto w = words(*prose);
    if (chapter.page.empty() && w.size() >= 2 && w[0] == "\\page") {
      chapter.page = w[1];
      const auto at = prose->find(w[1], prose->find("\\page") + 5);
      chapter.title = trim(prose->substr(at + w[1].size()));
    } else if (!w.empty() && w[0] == "\\builds_on") {
      if (w.size() == 1) warn(chapter.shown + ": \\builds_on needs a page name");
      for (std::size_t i = 1; i < w.size(); ++i) {
        std::string name = w[i];
        if (!name.empty() && name.back() == ',') name.pop_back();
        chapter.builds_on.push_back(name);
      }
    }
  }
  return !chapter.page.empty();
}

/// The closing line of a chapter page: the previous and next chapters, and those that build on
/// this one.
std::string navigation(const std::vector<Chapter>& chapters, std::size_t index) {
  std::vector<std::string> parts;
  if (index > 0) parts.push_back("Previous: \\ref " + chapters[index - 1].page);
  if (index + 1 < chapters.size()) parts.push_back("Next: \\ref " + chapters[index + 1].page);
  std::string later;
  for (const Chapter& other : chapters) {
    if (std::find(other.builds_on.begin(), other.builds_on.end(), chapters[index].page) !=
        other.builds_on.end()) {
      later += (later.empty() ? "" : ", ") + ("\\ref " + other.page);
    }
  }
  if (!later.empty()) parts.push_back("Built on by: " + later);
  std::string line;
  for (const std::string& part : parts) {
    line += (line.empty() ? "" : " &nbsp;&middot;&nbsp; ") + part;
  }
  return line.empty() ? "" : "<hr>\n" + line + "\n";
}

/// Writes the chapter's program twice into WORK/html/programs/ (linked from the head of its
/// page): whole, and as "the plain program" -- the code without the prose lines, runs of blank
/// lines left by the prose made one.  The .txt ending makes a browser show them as text.
void write_programs(const Settings& settings, const Chapter& chapter,
                    const std::vector<std::string>& lines) {
  const fs::path dir = settings.work / "html" / "programs";
  const std::string file = chapter.program.filename().string();
  fs::create_directories(dir);
  fs::copy_file(chapter.program, dir / (chapter.page + "-" + file + ".txt"),
                fs::copy_options::overwrite_existing);
  std::string plain = "// " + chapter.shown + " without its text: the plain program.\n\n";
  bool blank = true;  // no blank lines at the top
  for (const std::string& line : lines) {
    if (prose_text(line)) continue;
    if (is_blank(line)) {
      if (!blank) plain += "\n";
      blank = true;
      continue;
    }
    plain += line + "\n";
    blank = false;
  }
  write_file(dir / (chapter.page + "-plain-" + file + ".txt"), plain);
}

/// A code line as the page shows it: a member's `///<` comment becomes a plain `//` comment of
/// the same width, which Doxygen keeps in a code block (it drops documentation comments there,
/// and with them what a field means).
std::string shown_in_code(std::string line) {
  const auto at = line.find("///<");
  if (at != std::string::npos) line.replace(at, 4, "//  ");
  return line;
}

/// Renders one file of chapter \p chapter into \p page: its prose (`///` lines) verbatim, each
/// run of its code as a block.  In the program the \page and \builds_on lines are left out; in
/// a helper file, `#pragma once` and the `\file` line, and its `\brief` is shown as a plain
/// sentence under the file's name.  A prose line "\show_file name.hpp" renders that helper
/// file of the chapter in its place (each once; \p shown holds the files already placed).
void render_file(Page& page, const Chapter& chapter, const fs::path& file,
                 const std::vector<std::string>& lines, std::set<fs::path>& shown) {
  const bool program = file == chapter.program;
  const std::string shown_name = "chapters/" + chapter.dir + "/" + file.filename().string();
  shown.insert(file);
  if (!program) {
    page.add("");
    page.add("<div class=\"chapter-file\">The file <code>" + shown_name + "</code></div>");
    page.add("");
  }
  std::vector<CodeLine> code;
  bool page_seen = false;
  for (std::size_t number = 1; number <= lines.size(); ++number) {
    const std::string& line = lines[number - 1];
    const auto prose = prose_text(line);
    if (!prose) {
      if (!program && trim(line) == "#pragma once") continue;
      code.push_back({shown_in_code(line), at(file, number)});
      continue;
    }
    // A comment line ending in a backslash continues onto the next line: the compiler would
    // swallow that line into the comment (LaTeX's "\\" must not end a line).
    const auto end = line.find_last_not_of(" \t");
    if (end != std::string::npos && line[end] == '\\') {
      warn(shown_name + ":" + std::to_string(number) +
           ": a prose line ends with a backslash, so C++ continues the comment onto the next "
           "line; move the \\\\ to the start of the next line");
    }
    const auto w = words(*prose);
    std::string text = *prose;
    if (program && !page_seen && !w.empty() && w[0] == "\\page") {
      page_seen = true;
      continue;
    }
    if (program && !w.empty() && w[0] == "\\builds_on") {
      continue;  // read by read_header()
    }
    if (!program && !w.empty() && w[0] == "\\file") continue;
    if (!program && !w.empty() && w[0] == "\\brief")
      text = trim(text.substr(text.find("\\brief") + 6));
    if (!w.empty() && w[0] == "\\show_file") {
      emit_code(page, code);
      const fs::path helper = file.parent_path() / (w.size() > 1 ? w[1] : "");
      const bool known = w.size() == 2 && std::find(chapter.helpers.begin(), chapter.helpers.end(),
                                                    helper) != chapter.helpers.end();
      if (!known) {
        warn(at(file, number) + ": \\show_file names no helper file of the chapter (" +
             trim(*prose) + ")");
      } else if (shown.count(helper)) {
        warn(at(file, number) + ": " + w[1] + " is shown already");
      } else {
        render_file(page, chapter, helper, split_lines(read_file(helper)), shown);
      }
      continue;
    }
    emit_code(page, code);
    page.add(cite_figures(chapter, text, at(file, number)), at(file, number));
  }
  emit_code(page, code);
  if (!program) {
    page.add("<div class=\"chapter-file-end\">(end of <code>" + shown_name + "</code>)</div>");
    page.add("");
  }
}

/// The page for chapter number \p index.
Page convert(const Settings& settings, std::vector<Chapter>& chapters, std::size_t index) {
  Chapter& chapter = chapters[index];
  const std::vector<std::string> lines = split_lines(read_file(chapter.program));
  Page page;

  // The head: title, what it builds on, where the program is.  (A Markdown heading with an id,
  // not \page: Doxygen 1.9.4 names a .md file's page after the file and turns a \page command
  // in it into a mere anchor.)
  page.add("# " + chapter.title + " {#" + chapter.page + "}");
  page.add("");
  if (!chapter.builds_on.empty()) {
    std::string line = "Builds on: ";
    for (std::size_t i = 0; i < chapter.builds_on.size(); ++i) {
      line += (i ? ", " : "") + ("\\ref " + chapter.builds_on[i]);
    }
    page.add(line);
    page.add("");
  }
  const std::string file = chapter.program.filename().string();
  page.add("<em>This page is the program `" + chapter.shown + "`; run it as `build/chapters/" +
           target_name(chapter.dir) + "` (`--help` lists its options).  The same program as " +
           "<a href=\"programs/" + chapter.page + "-" + file + ".txt\">one source file</a>, " +
           "and as <a href=\"programs/" + chapter.page + "-plain-" + file +
           ".txt\">the plain program</a>: its code without the text.</em>");
  page.add("");
  page.add("\\tableofcontents");
  page.add("");

  // The program: prose verbatim, code in blocks; the \page and \builds_on lines are taken out,
  // and a "\show_file name.hpp" line is replaced by that helper file, rendered the same way.
  std::set<fs::path> shown;
  render_file(page, chapter, chapter.program, lines, shown);
  write_programs(settings, chapter, lines);

  // Helper files that no \show_file line placed: at the end, so that the page still shows
  // every line of the chapter's code (and a warning: the text should say where each belongs).
  for (const fs::path& helper : chapter.helpers) {
    if (shown.count(helper)) continue;
    warn("chapters/" + chapter.dir + "/" + helper.filename().string() + ": no '/// \\show_file " +
         helper.filename().string() +
         "' line in the chapter places it on the page; it is shown at the end");
    render_file(page, chapter, helper, split_lines(read_file(helper)), shown);
  }

  // Results: the real console output, then results.md or every figure.
  const fs::path figures = settings.figures / chapter.dir;
  const fs::path output = figures / "output.txt";
  const bool has_run = fs::is_regular_file(output);
  page.add("");
  page.add("\\section " + chapter.page + "_results Results");
  page.add("");
  if (has_run) {
    const std::vector<std::string> out = split_lines(read_file(output));
    constexpr std::size_t max_lines = 400;
    page.add("The program's output (`figures/" + chapter.dir + "/output.txt`):");
    page.add("");
    page.add("\\verbatim");
    for (std::size_t i = 0; i < out.size() && i < max_lines; ++i) {
      page.add(out[i], at(output, i + 1));
    }
    if (out.size() > max_lines) {
      page.add("... (" + std::to_string(out.size() - max_lines) + " more lines in output.txt)");
    }
    page.add("\\endverbatim");
    page.add("");
  } else {
    page.add(
        "<em>This chapter has not been run yet: `scripts/figures.sh` runs every chapter and "
        "puts its output and figures here.</em>");
    page.add("");
  }
  const fs::path results = chapter.program.parent_path() / "results.md";
  if (fs::is_regular_file(results)) {
    const auto resolved = resolve_figures(settings, chapter, read_file(results), has_run);
    for (std::size_t i = 0; i < resolved.size(); ++i) page.add(resolved[i], at(results, i + 1));
    page.add("");
  } else if (fs::is_directory(figures)) {
    std::vector<fs::path> pngs;
    for (const auto& entry : fs::directory_iterator(figures)) {
      if (entry.is_regular_file() && entry.path().extension() == ".png") {
        pngs.push_back(entry.path());
      }
    }
    std::sort(pngs.begin(), pngs.end());
    for (const fs::path& png : pngs) {
      std::string caption = png.stem().string();
      std::replace(caption.begin(), caption.end(), '_', ' ');
      page.add("\\image html " + copy_figure(settings, chapter, png) + " \"" + caption + "\"");
      page.add("");
    }
  }
  page.add(navigation(chapters, index));
  for (const std::string& problem : page.table_problems()) warn(problem);
  return page;
}

/// Rewrites Doxygen's warnings about generated pages ("WORK/pages/ch01.md:12: warning: ...")
/// to point at the chapter's own file and line, using the origins written beside the pages.
void explain(const fs::path& work, const fs::path& log) {
  static const std::regex location(R"re(^(.*[/\\])?([^/\\:]+\.md):([0-9]+):(.*)$)re");
  std::map<std::string, std::vector<std::string>> origins;
  for (const std::string& line : split_lines(read_file(log))) {
    std::smatch match;
    if (std::regex_match(line, match, location)) {
      const std::string page = match[2].str();
      const fs::path map = work / "origins" / (page + ".txt");
      if (!origins.count(page)) {
        origins[page] =
            fs::is_regular_file(map) ? split_lines(read_file(map)) : std::vector<std::string>{};
      }
      const std::size_t number = std::stoul(match[3].str());
      const auto& map_lines = origins[page];
      if (number >= 1 && number <= map_lines.size() && !map_lines[number - 1].empty()) {
        std::cout << map_lines[number - 1] << ":" << match[4].str() << "\n";
        continue;
      }
    }
    std::cout << line << "\n";
  }
}

/// Finds the chapters: directories NN-name holding name.cpp (or another .cpp with \page).
std::vector<Chapter> find_chapters(const Settings& settings) {
  std::vector<Chapter> chapters;
  if (!fs::is_directory(settings.chapters)) return chapters;
  static const std::regex chapter_dir(R"([0-9][0-9]-.+)");
  std::vector<fs::path> dirs;
  for (const auto& entry : fs::directory_iterator(settings.chapters)) {
    if (entry.is_directory() && std::regex_match(entry.path().filename().string(), chapter_dir)) {
      dirs.push_back(entry.path());
    }
  }
  std::sort(dirs.begin(), dirs.end());

  for (const fs::path& dir : dirs) {
    Chapter chapter;
    chapter.dir = dir.filename().string();
    std::vector<fs::path> sources;
    for (const auto& entry : fs::directory_iterator(dir)) {
      const auto ext = entry.path().extension();
      if (entry.is_regular_file() && (ext == ".cpp" || ext == ".hpp" || ext == ".h")) {
        sources.push_back(entry.path());
      }
    }
    std::sort(sources.begin(), sources.end());
    if (sources.empty()) continue;  // not a chapter yet (CMake skips it as well)

    // The program is name.cpp; failing that, the first .cpp with a \page line.
    const fs::path named = dir / (chapter.dir.substr(3) + ".cpp");
    std::vector<fs::path> candidates;
    if (fs::is_regular_file(named)) candidates.push_back(named);
    for (const fs::path& s : sources) {
      if (s.extension() == ".cpp" && s != named) candidates.push_back(s);
    }
    for (const fs::path& candidate : candidates) {
      chapter.program = candidate;
      chapter.shown = "chapters/" + chapter.dir + "/" + candidate.filename().string();
      if (read_header(chapter)) break;
      chapter.program.clear();
    }
    if (chapter.program.empty()) {
      warn("chapters/" + chapter.dir + ": no program with a '/// \\page chNN Title' line (" +
           named.filename().string() + " expected); chapter left out of the documentation");
      continue;
    }
    for (const fs::path& s : sources) {
      if (s != chapter.program) chapter.helpers.push_back(s);
    }
    chapters.push_back(std::move(chapter));
  }
  return chapters;
}

// ---- Where the library is used --------------------------------------------------------------

/// A type declared at namespace level in a library header.
struct LibraryType {
  std::string keyword;    ///< "struct" or "class"
  std::string qualified;  ///< "sph::MonaghanGingold1983"
  std::string name;       ///< "MonaghanGingold1983"
};

/// A library header, named as the chapters include it ("sph/kernel.hpp"), and its types.
struct LibraryHeader {
  std::string name;
  std::vector<LibraryType> types;
};

/// The headers under \p lib and the types each declares at namespace level (lines starting with
/// "struct X" or "class X" that are not forward declarations; "detail" namespaces left out).
std::vector<LibraryHeader> library_headers(const fs::path& lib) {
  static const std::regex declaration(
      R"re(^(struct|class)\s+([A-Za-z_]\w*)\s*(final\s*)?[:{].*)re");
  static const std::regex namespace_line(R"re(^namespace\s+([A-Za-z_][\w:]*)\s*\{.*)re");
  std::vector<LibraryHeader> headers;
  if (!fs::is_directory(lib)) return headers;
  for (const auto& entry : fs::recursive_directory_iterator(lib)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".hpp") continue;
    LibraryHeader header{fs::relative(entry.path(), lib).generic_string(), {}};
    std::string space;
    for (const std::string& line : split_lines(read_file(entry.path()))) {
      std::smatch match;
      if (std::regex_match(line, match, namespace_line)) {
        space = match[1].str();
      } else if (std::regex_match(line, match, declaration) &&
                 space.find("detail") == std::string::npos && !space.empty()) {
        header.types.push_back({match[1].str(), space + "::" + match[2].str(), match[2].str()});
      }
    }
    headers.push_back(std::move(header));
  }
  std::sort(headers.begin(), headers.end(),
            [](const LibraryHeader& a, const LibraryHeader& b) { return a.name < b.name; });
  return headers;
}

/// True if \p word occurs in \p text as a whole identifier.
bool mentions(const std::string& text, const std::string& word) {
  auto is_identifier = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  };
  for (auto at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
    const bool left = at == 0 || !is_identifier(text[at - 1]);
    const bool right = at + word.size() >= text.size() || !is_identifier(text[at + word.size()]);
    if (left && right) return true;
  }
  return false;
}

/// Writes WORK/pages/used_in.dox: for every library header and type that a chapter's code uses
/// (it includes the header, or names the type), a "Used in the chapters" paragraph that
/// Doxygen adds to the header's and the type's reference pages, so that a reader of the
/// reference can go back to the chapters that teach and use it.
void write_used_in(const Settings& settings, const std::vector<Chapter>& chapters) {
  const std::vector<LibraryHeader> headers =
      library_headers(settings.chapters.parent_path() / "lib");
  std::vector<std::string> code;  // the code lines of each chapter, prose left out
  for (const Chapter& chapter : chapters) {
    std::string text;
    std::vector<fs::path> files = chapter.helpers;
    files.push_back(chapter.program);
    for (const fs::path& file : files) {
      for (const std::string& line : split_lines(read_file(file))) {
        if (!prose_text(line)) text += line + "\n";
      }
    }
    code.push_back(std::move(text));
  }
  auto refs = [&](const std::vector<std::size_t>& users) {
    std::string line;
    for (std::size_t i : users) line += (line.empty() ? "" : ", ") + ("\\ref " + chapters[i].page);
    return line;
  };
  std::ostringstream out;
  out << "/// \\file used_in.dox\n/// \\brief Generated: where the chapters use the library.\n\n";
  for (const LibraryHeader& header : headers) {
    std::vector<std::size_t> users;
    for (std::size_t i = 0; i < chapters.size(); ++i) {
      bool used = code[i].find("#include \"" + header.name + "\"") != std::string::npos;
      for (const LibraryType& type : header.types) used = used || mentions(code[i], type.name);
      if (used) users.push_back(i);
    }
    if (users.empty()) continue;
    out << "/// \\file " << header.name << "\n/// \\par Used in the chapters\n/// " << refs(users)
        << "\n\n";
    for (const LibraryType& type : header.types) {
      std::vector<std::size_t> type_users;
      for (std::size_t i : users) {
        if (mentions(code[i], type.name)) type_users.push_back(i);
      }
      if (type_users.empty()) continue;
      out << "/// \\" << type.keyword << " " << type.qualified
          << "\n/// \\par Used in the chapters\n/// " << refs(type_users) << "\n\n";
    }
  }
  write_file(settings.work / "pages" / "used_in.dox", out.str());
}

// ---- The main page ----------------------------------------------------------------------------

std::string escape_html(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// The table of chapters and what each builds on.  \p link is "\\ref" on the main page and
/// "\\subpage" on the chapters page (which makes the chapters its children in the navigation
/// tree; Doxygen 1.9.4 does not show subpages of the main page there).
std::string chapter_map(const std::vector<Chapter>& chapters, const std::string& link) {
  if (chapters.empty()) {
    return "<em>No chapters yet.</em>\n";
  }
  std::ostringstream map;
  map << "| Chapter | Builds on |\n|:--|:--|\n";
  for (const Chapter& chapter : chapters) {
    map << "| " << link << " " << chapter.page << " | ";
    if (chapter.builds_on.empty()) {
      map << "&mdash;";
    }
    for (std::size_t i = 0; i < chapter.builds_on.size(); ++i) {
      map << (i ? ", " : "") << "\\ref " << chapter.builds_on[i];
    }
    map << " |\n";
  }
  return map.str();
}

/// The page "The chapters": the chapter map, parent of every chapter page.
std::string chapters_page(const std::vector<Chapter>& chapters) {
  return "# The chapters {#chapters}\n\n"
         "Each chapter is one program in `chapters/NN-name/` that adds one idea to the chapters "
         "it builds on.  Its page is the program itself: the text, the code, then its real "
         "output and figures.\n\n" +
         chapter_map(chapters, "\\subpage");
}

std::string gallery(const Settings& settings, const std::vector<Chapter>& chapters) {
  const fs::path dir = settings.work / "html" / "gallery";
  std::ostringstream html;
  int items = 0;
  auto item = [&](const fs::path& source, const std::string& name, const std::string& link,
                  const std::string& caption) {
    fs::copy_file(source, dir / name, fs::copy_options::overwrite_existing);
    html << "<a class=\"gallery-item\" href=\"" << link << "\"><img src=\"gallery/" << name
         << "\" alt=\"" << escape_html(caption) << "\"/><span>" << escape_html(caption)
         << "</span></a>\n";
    ++items;
  };
  html << "\\htmlonly\n<div class=\"gallery\">\n";
  for (const Chapter& chapter : chapters) {
    if (!chapter.gallery_image.empty()) {
      item(chapter.gallery_source, chapter.gallery_image, chapter.page + ".html", chapter.title);
    }
  }
  if (fs::is_regular_file(settings.figures / "plot-demo.png")) {
    item(settings.figures / "plot-demo.png", "plot-demo.png", "gallery/plot-demo.png",
         "The figure engine (lib/plot)");
  }
  html << "</div>\n\\endhtmlonly\n";
  if (items == 0) {
    return "<em>No figures yet: `scripts/figures.sh` runs every chapter and fills this "
           "gallery.</em>\n";
  }
  return html.str();
}

std::string main_page(const Settings& settings, const std::vector<Chapter>& chapters) {
  std::string result;
  for (const std::string& line : split_lines(read_file(settings.mainpage))) {
    const std::string t = trim(line);
    if (t == "@CHAPTER_MAP@") {
      result += chapter_map(chapters, "\\ref");
    } else if (t == "@GALLERY@") {
      result += gallery(settings, chapters);
    } else {
      result += line + "\n";
    }
  }
  return result;
}

// ---- main -------------------------------------------------------------------------------------

Settings read_arguments(int argc, char** argv) {
  Settings settings;
  const std::string usage =
      "usage: literate --chapters DIR --figures DIR --mainpage FILE --work DIR [--strict]\n"
      "       literate --work DIR --explain DOXYGEN_WARNING_LOG";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> fs::path {
      if (i + 1 >= argc) throw std::runtime_error(arg + " needs a value\n" + usage);
      return argv[++i];
    };
    if (arg == "--chapters")
      settings.chapters = value();
    else if (arg == "--figures")
      settings.figures = value();
    else if (arg == "--mainpage")
      settings.mainpage = value();
    else if (arg == "--work")
      settings.work = value();
    else if (arg == "--explain")
      settings.explain = value();
    else if (arg == "--strict")
      settings.strict = true;
    else
      throw std::runtime_error("unknown argument " + arg + "\n" + usage);
  }
  const bool explaining = !settings.explain.empty() && !settings.work.empty();
  if (!explaining && (settings.chapters.empty() || settings.figures.empty() ||
                      settings.mainpage.empty() || settings.work.empty())) {
    throw std::runtime_error(usage);
  }
  return settings;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Settings settings = read_arguments(argc, argv);
    if (!settings.explain.empty()) {
      explain(settings.work, settings.explain);
      return 0;
    }

    // Start from empty page, image and gallery directories: nothing stale survives.
    for (const char* sub : {"pages", "origins", "images", "html/gallery"}) {
      fs::remove_all(settings.work / sub);
      fs::create_directories(settings.work / sub);
    }

    std::vector<Chapter> chapters = find_chapters(settings);
    std::set<std::string> pages;
    for (Chapter& chapter : chapters) {
      if (!pages.insert(chapter.page).second) {
        warn("chapters/" + chapter.dir + ": page name " + chapter.page + " is used twice");
      }
    }
    for (Chapter& chapter : chapters) number_figures(chapter);
    for (std::size_t i = 0; i < chapters.size(); ++i) {
      const Page page = convert(settings, chapters, i);
      const Chapter& chapter = chapters[i];
      write_file(settings.work / "pages" / (chapter.page + ".md"), page.text());
      write_file(settings.work / "origins" / (chapter.page + ".md.txt"), page.origins());
      for (const std::string& other : chapter.builds_on) {
        if (!pages.count(other)) {
          warn(chapter.shown + ": \\builds_on " + other + ": no chapter has this page");
        }
      }
    }
    write_file(settings.work / "pages" / "mainpage.md", main_page(settings, chapters));
    write_used_in(settings, chapters);
    write_file(settings.work / "pages" / "chapters.md", chapters_page(chapters));

    std::cout << "literate: " << chapters.size() << " chapter page"
              << (chapters.size() == 1 ? "" : "s") << " in " << (settings.work / "pages").string()
              << "\n";
    return settings.strict && warnings > 0 ? 2 : 0;
  } catch (const std::exception& error) {
    std::cerr << "literate: error: " << error.what() << "\n";
    return 1;
  }
}
