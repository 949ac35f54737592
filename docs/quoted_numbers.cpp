// The numbers a chapter's text quotes from a run, checked against the run.
//
// A chapter's text (the `///` lines of its program and of its helper files, and its results.md)
// quotes what its program printed: errors, energies, step counts, fractions, percentages.  When
// the program changes, those numbers go stale unless something compares them.  This tool does,
// for every number the text writes with a decimal point or a percent sign: in scientific
// notation (`1.234e-3`, or `1.234\cdot 10^{-3}` or `1.234\times10^{-3}` in a formula), a plain
// decimal (`0.62`, `3.93`), a percentage (`0.62 %`, `18 %`), and a count of steps
// (`1393 steps`).  Such a number passes if the program's recorded output
// (figures/<chapter>/output.txt, written by the figures command) or the chapter's own code
// (where numbers quoted from other codes and papers live) holds a number that rounds to it, to
// the digits the text gives (a percentage may also be printed as a fraction).
//
// A number the text does not read off a run -- derived from others in a line of algebra, taken
// from a paper, from another chapter, or from an earlier recording that the text says is
// earlier -- is listed with where it comes from in the chapter's numbers_not_from_runs.txt
// (`<number as the text writes it>  <where it comes from>`, one a line, `#` for comments), so
// that every such number is accounted for and a number that merely went stale is not.
//
// The "What to try" section quotes runs with other options.  Each of its items names its runs
// as options in bold code, <b>`--courant 0.15`</b>; the figures command runs every item that
// quotes a number in scientific notation or a count of steps and keeps its output in
// figures/<chapter>/try/<slug>.txt, and the item's numbers are checked against those outputs
// (and the default run's, which an item may quote for comparison, and the runs of the other
// items that it names in code font, as in "compare with the `--neighbours-1d 4.8` run above").
// The rest of the text may quote such a run too, where it names it in code font: its numbers
// are then checked against the default run's output and those of the runs it names.
//
//   sph_quoted_numbers tries <chapter source dir>   the runs to make: "<slug>\t<options>" lines
//   sph_quoted_numbers check <project root>         check every chapter; exit 1 on a stale number
//
// Integers other than step counts and percentages (neighbour numbers, particle counts, years,
// equation numbers) are not checked: they are set, not measured.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// One line of a chapter's text, with where it comes from.
struct Line {
  std::string text, file;
  int number;
};

// The text of a chapter: the `///` lines of its program and helper files, then its results.md.
// The code lines of those files go into `code`.
std::vector<Line> chapter_text(const fs::path& dir, std::string& code) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const auto ext = entry.path().extension();
    if (ext == ".cpp" || ext == ".hpp") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  std::vector<Line> lines;
  for (const fs::path& file : files) {
    std::ifstream in(file);
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      const auto slashes = line.find("///");
      if (slashes == std::string::npos) {
        code += line + "\n";
      } else {
        lines.push_back({line.substr(slashes + 3), file.filename().string(), n});
      }
    }
  }
  if (fs::exists(dir / "results.md")) {
    std::ifstream in(dir / "results.md");
    std::string line;
    int n = 0;
    while (std::getline(in, line)) lines.push_back({line, "results.md", ++n});
  }
  return lines;
}

// A quoted number: its value, the size of a unit in its last digit, and whether it is a
// percentage (which a run may print as a fraction).
struct Quoted {
  double value, unit;
  std::string text;
  bool percent = false;
};

// The checkable numbers in a piece of text.
std::vector<Quoted> quoted_numbers(const std::string& text) {
  std::vector<Quoted> found;
  static const std::regex scientific(
      R"((^|[^\w.])(\d+)\.(\d+)\s*(?:[eE]([-+]?\d+)|\\(?:cdot|times)\s*10\^\{?([-+]?\d+)\}?))");
  for (std::sregex_iterator it(text.begin(), text.end(), scientific), end; it != end; ++it) {
    const std::smatch& m = *it;
    const int exponent = std::stoi(m[4].matched ? m[4].str() : m[5].str());
    const std::string mantissa = m[2].str() + "." + m[3].str();
    const double value = std::stod(mantissa) * std::pow(10.0, exponent);
    const double unit = std::pow(10.0, exponent - static_cast<int>(m[3].length()));
    found.push_back({value, unit, m.str().substr(m[1].length())});
  }
  static const std::regex steps(R"((^|[^\w.])(\d{3,})\s+steps)");
  for (std::sregex_iterator it(text.begin(), text.end(), steps), end; it != end; ++it) {
    const std::smatch& m = *it;
    found.push_back({std::stod(m[2].str()), 1.0, m[2].str() + " steps"});
  }
  // Plain decimals and percentages: not part of a longer number or of a version (3.25.1), not
  // a mantissa (taken above), not an exponent (10^{1.5}).
  static const std::regex plain(R"((^|[^\w.^])(\d+)(?:\.(\d+))?)"
                                R"((?!\d|\.\d|\s*(?:[eE][-+]?\d|\\cdot|\\times))(\s*(?:%|\\%))?)");
  for (std::sregex_iterator it(text.begin(), text.end(), plain), end; it != end; ++it) {
    const std::smatch& m = *it;
    const bool decimal = m[3].matched, percent = m[4].matched;
    if (!decimal && !percent) continue;  // an integer: set, not measured
    std::string digits = m[2].str();
    if (decimal) digits += '.' + m[3].str();
    const double unit = decimal ? std::pow(10.0, -static_cast<int>(m[3].length())) : 1.0;
    found.push_back({std::stod(digits), unit, m.str().substr(m[1].length()), percent});
  }
  return found;
}

// Every number written in a program's output or code.
std::vector<double> numbers_in(const std::string& text) {
  std::vector<double> numbers;
  static const std::regex number(R"((\d+\.?\d*(?:[eE][-+]?\d+)?))");
  for (std::sregex_iterator it(text.begin(), text.end(), number), end; it != end; ++it) {
    numbers.push_back(std::stod(it->str()));
  }
  std::sort(numbers.begin(), numbers.end());
  return numbers;
}

// Whether a number of `pool` rounds to the quoted one: lies within half a unit of its last digit.
// A percentage matches a number printed as a percentage or as a fraction.
bool matches(const Quoted& q, const std::vector<double>& pool) {
  const auto rounds_to = [&](double value, double unit) {
    const double half = 0.5 * unit * (1 + 1e-9) + 1e-12 * std::abs(value);
    const auto from = std::lower_bound(pool.begin(), pool.end(), std::abs(value) - half);
    return from != pool.end() && *from <= std::abs(value) + half;
  };
  return rounds_to(q.value, q.unit) || (q.percent && rounds_to(q.value / 100, q.unit / 100));
}

// An item of a "What to try" section: its lines and the option sets it names.
struct TryItem {
  std::vector<Line> lines;
  std::vector<std::string> options;
};

std::string slug(const std::string& options) {
  std::string s;
  for (char c : options) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.') {
      s += c;
    } else if (!s.empty() && s.back() != '_') {
      s += '_';
    }
  }
  while (!s.empty() && s.back() == '_') s.pop_back();
  return s;
}

// Splits a chapter's text into the lines outside "What to try" and the items inside it.
void split(const std::vector<Line>& lines, std::vector<Line>& body, std::vector<TryItem>& items) {
  static const std::regex try_heading(R"(^\s*(## What to try|\\section \w+_try\b))");
  static const std::regex other_heading(R"(^\s*(## |\\section ))");
  static const std::regex item_start(R"(^\s*- )");
  static const std::regex bold_options(R"(<b>`([^`]+)`</b>)");
  bool in_try = false;
  for (const Line& line : lines) {
    if (std::regex_search(line.text, try_heading)) {
      in_try = true;
      continue;
    }
    if (in_try && std::regex_search(line.text, other_heading)) in_try = false;
    if (!in_try) {
      body.push_back(line);
      continue;
    }
    if (std::regex_search(line.text, item_start) || items.empty()) items.emplace_back();
    items.back().lines.push_back(line);
    for (std::sregex_iterator it(line.text.begin(), line.text.end(), bold_options), end; it != end;
         ++it) {
      items.back().options.push_back((*it)[1].str());
    }
  }
}

std::string joined(const std::vector<Line>& lines) {
  std::string text;
  for (const Line& line : lines) text += line.text + "\n";
  return text;
}

int list_tries(const fs::path& dir) {
  std::string code;
  std::vector<Line> body;
  std::vector<TryItem> items;
  split(chapter_text(dir, code), body, items);
  for (const TryItem& item : items) {
    if (quoted_numbers(joined(item.lines)).empty()) continue;
    for (const std::string& options : item.options) {
      std::printf("%s\t%s\n", slug(options).c_str(), options.c_str());
    }
  }
  return 0;
}

// The numbers a chapter's text quotes that are not read off its runs, each with where it comes
// from: the lines `"<number as the text writes it>"  <source>` of numbers_not_from_runs.txt in
// its folder.  `used` counts how often each is needed.
struct NotFromRuns {
  std::vector<std::string> numbers;
  std::vector<int> used;
  std::vector<int> line;
  bool covers(const std::string& text) {
    for (std::size_t k = 0; k < numbers.size(); ++k) {
      if (numbers[k] == text) return ++used[k], true;
    }
    return false;
  }
};

// Reads numbers_not_from_runs.txt of a chapter's folder (none: an empty list); a line that is
// not a comment, blank or `"number"  source` is reported and counted in `bad`.
NotFromRuns read_not_from_runs(const fs::path& dir, int& bad) {
  NotFromRuns list;
  const fs::path file = dir / "numbers_not_from_runs.txt";
  if (!fs::exists(file)) return list;
  std::ifstream in(file);
  static const std::regex entry(R"re(^"([^"]+)"\s+\S.*$)re");
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    std::smatch m;
    if (!std::regex_match(line, m, entry)) {
      std::printf("  numbers_not_from_runs.txt:%d: expected '\"number\"  where it comes from'\n",
                  n);
      ++bad;
      continue;
    }
    list.numbers.push_back(m[1].str());
    list.used.push_back(0);
    list.line.push_back(n);
  }
  return list;
}

// Reports the numbers of `lines` that no number of `pool` rounds to and that `listed` does not
// account for; returns how many.
int report_stale(const std::vector<Line>& lines, const std::vector<double>& pool,
                 const std::string& against, NotFromRuns& listed) {
  int stale = 0;
  // A number may be split over two lines: join each line with the next for the search, and
  // take a number from the line it starts on.
  std::set<std::string> seen;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const std::string text =
        lines[k].text + (k + 1 < lines.size() ? " " + lines[k + 1].text : std::string());
    for (const Quoted& q : quoted_numbers(text)) {
      const std::string where = lines[k].file + ":" + std::to_string(lines[k].number);
      if (text.find(q.text) >= lines[k].text.size()) continue;  // starts on the next line
      if (!seen.insert(where + q.text).second || matches(q, pool)) continue;
      if (listed.covers(q.text)) continue;
      std::printf("  %s: \"%s\" is not in %s\n", where.c_str(), q.text.c_str(), against.c_str());
      ++stale;
    }
  }
  return stale;
}

int check(const fs::path& root) {
  int stale = 0, checked = 0;
  std::vector<fs::path> chapters;
  for (const auto& entry : fs::directory_iterator(root / "chapters")) {
    if (entry.is_directory()) chapters.push_back(entry.path());
  }
  std::sort(chapters.begin(), chapters.end());
  for (const fs::path& dir : chapters) {
    const std::string name = dir.filename().string();
    const fs::path figures = root / "figures" / name;
    std::string code;
    std::vector<Line> body;
    std::vector<TryItem> items;
    split(chapter_text(dir, code), body, items);
    const fs::path output = figures / "output.txt";
    if (!fs::exists(output)) {
      std::printf("%s: no recorded output (%s); run the figures command\n", name.c_str(),
                  output.string().c_str());
      ++stale;
      continue;
    }
    const std::string recorded = read(output) + code;
    std::printf("%s\n", name.c_str());
    NotFromRuns listed = read_not_from_runs(dir, stale);
    // Every run the section makes (the items that quote numbers), for the items that name
    // another item's run, and for the rest of the text.
    std::set<std::string> runs;
    for (const TryItem& item : items) {
      if (quoted_numbers(joined(item.lines)).empty()) continue;
      runs.insert(item.options.begin(), item.options.end());
    }
    // The outputs of the runs that `text` names in code font, and of those in `own`, appended
    // to `outputs`, their options to `names`; a named run without a recorded output is stale.
    const auto add_named_runs = [&](const std::string& text, const std::set<std::string>& own,
                                    std::string& outputs, std::string& names) {
      for (const std::string& options : runs) {
        if (own.count(options) == 0 && text.find("`" + options + "`") == std::string::npos) {
          continue;
        }
        const fs::path run = figures / "try" / (slug(options) + ".txt");
        names += (names.empty() ? "" : ", ") + options;
        if (!fs::exists(run)) {
          std::printf("  no recorded output of the run %s (%s); run the figures command\n",
                      options.c_str(), run.string().c_str());
          ++stale;
        }
        outputs += read(run);
      }
    };
    const std::string body_text = joined(body);
    std::string body_outputs = recorded, body_names;
    add_named_runs(body_text, {}, body_outputs, body_names);
    checked += static_cast<int>(quoted_numbers(body_text).size());
    stale += report_stale(
        body, numbers_in(body_outputs),
        "the output of the default run" + (body_names.empty() ? "" : " or of " + body_names),
        listed);
    for (const TryItem& item : items) {
      const std::string text = joined(item.lines);
      const auto numbers = quoted_numbers(text);
      if (numbers.empty()) continue;
      checked += static_cast<int>(numbers.size());
      std::string outputs = recorded, names;
      add_named_runs(text, std::set<std::string>(item.options.begin(), item.options.end()), outputs,
                     names);
      stale += report_stale(item.lines, numbers_in(outputs),
                            names.empty() ? "the default run (the item names no run of its own: "
                                            "write its options as <b>`--option value`</b>)"
                                          : "the output of " + names,
                            listed);
    }
    // An entry of the list that no number needs: the text changed, or the number is in a run
    // after all; either way the list must not hide a number that later goes stale.
    for (std::size_t k = 0; k < listed.numbers.size(); ++k) {
      if (listed.used[k] > 0) continue;
      std::printf(
          "  numbers_not_from_runs.txt:%d: \"%s\" is listed, but no number of the text "
          "needs it (found in a run, or no longer quoted): remove it\n",
          listed.line[k], listed.numbers[k].c_str());
      ++stale;
    }
  }
  std::printf("%d quoted numbers checked, %d not found in their runs\n", checked, stale);
  return stale == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string usage =
      "usage: sph_quoted_numbers tries <chapter source dir> | check <project root>\n";
  if (argc != 3) {
    std::fputs(usage.c_str(), stderr);
    return 2;
  }
  const std::string mode = argv[1];
  if (!fs::is_directory(argv[2])) {
    std::fprintf(stderr, "sph_quoted_numbers: %s is not a directory\n", argv[2]);
    return 2;
  }
  if (mode == "tries") return list_tries(argv[2]);
  if (mode == "check") return check(argv[2]);
  std::fputs(usage.c_str(), stderr);
  return 2;
}
