// The numbers a chapter's text quotes from a run, checked against the run.
//
// A chapter's text (the `///` lines of its program and its results.md) quotes what its program
// printed: errors, energies, step counts.  When the program changes, those numbers go stale
// unless something compares them.  This tool does, for the numbers that can only have come from
// a run: a number in scientific notation (`1.234e-3`, or `1.234\cdot 10^{-3}` or
// `1.234\times10^{-3}` in a formula) and a count of steps (`1393 steps`).  Such a number
// passes if the program's recorded output
// (figures/<chapter>/output.txt, written by the figures command) or the program's own code
// (where numbers quoted from other codes live) holds a number that rounds to it, to the digits
// the text gives.
//
// The "What to try" section quotes runs with other options.  Each of its items names its runs
// as options in bold code, <b>`--courant 0.15`</b>; the figures command runs every item that
// quotes a number of this kind and keeps its output in figures/<chapter>/try/<slug>.txt, and the
// item's numbers are checked against those outputs (and the default run's, which an item may
// quote for comparison, and the runs of the other items that it names in code font, as in "compare
// with the `--neighbours-1d 4.8` run above").  The rest of the text may quote such a run too, where
// it names it in code font: its numbers are then checked against the default run's output and
// those of the runs it names.
//
//   sph_quoted_numbers tries <chapter source dir>   the runs to make: "<slug>\t<options>" lines
//   sph_quoted_numbers check <project root>         check every chapter; exit 1 on a stale number
//
// Numbers of fewer digits (0.41, 3.2 %) are not checked: they are as often derived, rounded or
// quoted from a paper as read off a run.

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

// The text of a chapter: the `///` lines of its programs, then its results.md.  The code lines
// of the programs go into `code`.
std::vector<Line> chapter_text(const fs::path& dir, std::string& code) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".cpp") files.push_back(entry.path());
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

// A quoted number: its value and the size of a unit in its last digit.
struct Quoted {
  double value, unit;
  std::string text;
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
bool matches(const Quoted& q, const std::vector<double>& pool) {
  const double half = 0.5 * q.unit * (1 + 1e-9) + 1e-12 * std::abs(q.value);
  const auto from = std::lower_bound(pool.begin(), pool.end(), std::abs(q.value) - half);
  return from != pool.end() && *from <= std::abs(q.value) + half;
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

// Reports the numbers of `lines` that no number of `pool` rounds to; returns how many.
int report_stale(const std::vector<Line>& lines, const std::vector<double>& pool,
                 const std::string& against) {
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
        "the output of the default run" + (body_names.empty() ? "" : " or of " + body_names));
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
                                          : "the output of " + names);
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
