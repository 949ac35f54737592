#include "app/chapter.hpp"

#include "app/text.hpp"

#include <omp.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <system_error>

#ifndef SPH_FIGURES_DIR
#define SPH_FIGURES_DIR "figures"
#endif

namespace app {

// ---- The command line -------------------------------------------------------------------------

namespace {

/// A command-line error in the chapters' one voice, "--option: what is wrong": CLI11's own
/// words for a missing value ("1 required INT:in [2, 20000] missing"), a repeated option ("At
/// Most 1 required but received 2"), a value it cannot convert and a stray argument are
/// rewritten; every other message (the validators' own) is already in that voice.
std::string in_our_words(const CLI::Error& error) {
  const std::string what = error.what();
  const auto colon = what.find(": ");
  const std::string option = colon == std::string::npos ? "" : what.substr(0, colon);
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&error) != nullptr && !option.empty()) {
    if (what.find(" missing") != std::string::npos) {
      return option + ": needs a value (--help gives its type and range)";
    }
    const auto received = what.find("received ");
    if (what.find("At Most") != std::string::npos && received != std::string::npos) {
      return option + ": given " + what.substr(received + 9) + " times; give it once";
    }
  }
  if (dynamic_cast<const CLI::ConversionError*>(&error) != nullptr) {
    static const std::string prefix = "Could not convert: ";
    const auto equals = what.find(" = ");
    if (what.rfind(prefix, 0) == 0 && equals != std::string::npos) {
      return what.substr(prefix.size(), equals - prefix.size()) + ": cannot read '" +
             what.substr(equals + 3) + "' as a value of this option";
    }
  }
  if (dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr) {
    const auto extra = what.find("expected: ");
    const std::string args = extra == std::string::npos ? what : what.substr(extra + 10);
    return "unexpected argument " + args +
           ": every parameter is named, as --name value (--help lists them)";
  }
  return what;
}

/// Help in two columns: the option with its type, then what it is, its default and its range:
///   --gamma FLOAT              adiabatic index (default 1.4; > 1)
class HelpFormatter : public CLI::Formatter {
 public:
  using QuickNotes = std::map<const CLI::Option*, std::string>;
  explicit HelpFormatter(std::shared_ptr<const QuickNotes> quick) : quick_(std::move(quick)) {}
  std::string make_option_opts(const CLI::Option* option) const override {
    if (option->get_type_size() == 0) return "";
    const std::string type = option->get_type_name();
    return " " + type.substr(0, type.find(':'));
  }
  std::string make_option_desc(const CLI::Option* option) const override {
    std::string details;
    if (option->get_type_size() != 0 && !option->get_default_str().empty()) {
      details = "default " + option->get_default_str();
      if (auto note = quick_->find(option); note != quick_->end()) {
        details += ", with --quick " + note->second;
      }
    }
    const std::string type = option->get_type_name();
    for (auto colon = type.find(':'); colon != std::string::npos;) {
      const auto next = type.find(':', colon + 1);
      details += (details.empty() ? "" : "; ") + type.substr(colon + 1, next - colon - 1);
      colon = next;
    }
    return option->get_description() + (details.empty() ? "" : " (" + details + ")");
  }

 private:
  std::shared_ptr<const QuickNotes> quick_;
};

}  // namespace

Chapter::Chapter(std::string name, std::string title, int argc, char** argv)
    : name_(std::move(name)),
      title_(std::move(title)),
      argc_(argc),
      argv_(argv),
      cli_(title_, name_),
      output_arg_((std::filesystem::path(SPH_FIGURES_DIR) / name_).string()) {
  // Line by line, even into a file or a pipe: a run that is stopped keeps every line it printed
  // (the chapters print a few hundred lines, so the cost is nil).
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // Set up the options every chapter shares.
  cli_.add_flag("--quick", quick_, "reduced resolution that runs in seconds (used by the tests)")
      ->group("Run options");
  cli_.add_option("-o,--output", output_arg_, "directory for the figures and summary.txt")
      ->capture_default_str()
      ->type_name("DIR")
      ->group("Run options");
  // More threads than a few per core only slow a run down, and a huge count makes the OpenMP
  // runtime fail (a crash or a bare abort): the range is bounded, and --help says by what.
  cli_.add_option("--threads", threads_, "OpenMP threads; 0 uses every core")
      ->capture_default_str()
      ->transform(whole_number())
      ->check(between(0, max_threads()))
      ->group("Run options");
  cli_.get_help_ptr()->group("Run options");
  cli_.formatter(std::make_shared<HelpFormatter>(quick_notes_));

  // Errors read "ch: error: --gamma: must be greater than 1, got 0.5".
  cli_.failure_message([name = name_](const CLI::App* app, const CLI::Error& error) {
    std::string message = name + ": error: " + in_our_words(error) + "\n";
    if (app->get_help_ptr() != nullptr) {
      message += "Run with " + app->get_help_ptr()->get_name() + " for more information.\n";
    }
    return message;
  });
}

void Chapter::require_dashes(const std::string& flag) {
  // CLI11 would quietly make "gamma" a positional argument; a chapter's parameters are named.
  if (flag.empty() || flag.front() != '-') {
    throw std::invalid_argument("app::Chapter: option \"" + flag + "\" must start with -- (or -)");
  }
}

CLI::Option& Chapter::flag(const std::string& flag, bool& value, const std::string& description) {
  require_dashes(flag);
  CLI::Option* option = cli_.add_flag(flag, value, description);
  option->group("Scene parameters");
  return *option;
}

void Chapter::require(std::function<bool()> condition, std::string problem) {
  require(std::move(condition), [problem = std::move(problem)] { return problem; });
}

void Chapter::require(std::function<bool()> condition, std::function<std::string()> problem) {
  requirements_.push_back({std::move(condition), std::move(problem)});
}

int Chapter::parse() {
  // Read the options; CLI11 reports --help, unknown options and rejected values itself.
  try {
    cli_.parse(argc_, argv_);
  } catch (const CLI::ParseError& error) {
    return cli_.exit(error, *out_, *err_);
  }

  // Apply the quick defaults of the options not given.
  if (quick_) {
    for (const QuickDefault& quick : quick_defaults_) {
      if (quick.option->count() == 0) quick.set();
    }
  }

  // Check the conditions between parameters.
  for (const Requirement& requirement : requirements_) {
    if (!requirement.condition()) {
      *err_ << name_ << ": error: " << requirement.problem() << "\n"
            << "Run with --help for more information.\n";
      return static_cast<int>(CLI::ExitCodes::ValidationError);
    }
  }

  // Apply the thread count.
  if (threads_ > 0) {
    omp_set_num_threads(threads_);
  }

  // Create the output directory and start the summary.
  output_dir_ = output_arg_;
  std::error_code failure;
  std::filesystem::create_directories(output_dir_, failure);
  if (failure || !std::filesystem::is_directory(output_dir_)) {
    *err_ << name_ << ": error: --output: cannot create directory " << output_dir_ << ": "
          << (failure ? failure.message() : "not a directory") << "\n";
    return static_cast<int>(CLI::ExitCodes::FileError);
  }
  remove_previous_outputs();
  parsed_ = true;
  summary_.clear();
  summary("chapter", name_);
  summary("title", title_);
  summary("mode", quick_ ? "quick" : "full");
  summary("threads", std::to_string(threads_ > 0 ? threads_ : omp_get_max_threads()));
  return -1;
}

bool Chapter::given(const std::string& flag) const { return cli_.count(flag) > 0; }

namespace {

const char* const files_list = "files.txt";  // the files the last run wrote, one a line

/// True for a plain file name, which can only name a file directly in the output directory.
bool plain_name(const std::string& file) {
  return !file.empty() && file != "." && file != ".." &&
         file.find_first_of("/\\") == std::string::npos;
}

/// Whether \p summary is a summary.txt written by the chapter called \p name.
bool written_by(const std::filesystem::path& summary, const std::string& name) {
  std::ifstream file(summary);
  for (std::string line; std::getline(file, line);) {
    if (line == "chapter = " + name) return true;
  }
  return false;
}

}  // namespace

void Chapter::remove_previous_outputs() const {
  // The files the previous run recorded, when it did; else, in a directory whose summary.txt
  // names this chapter, its figures and snapshots.
  std::vector<std::filesystem::path> previous;
  const std::filesystem::path list = output_dir_ / files_list;
  if (std::filesystem::exists(list)) {
    std::ifstream file(list);
    for (std::string line; std::getline(file, line);) {
      if (plain_name(line)) previous.push_back(output_dir_ / line);
    }
  } else if (written_by(output_dir_ / "summary.txt", name_)) {
    for (const auto& entry : std::filesystem::directory_iterator(output_dir_)) {
      const std::string extension = entry.path().extension().string();
      if (entry.is_regular_file() && (extension == ".png" || extension == ".dat")) {
        previous.push_back(entry.path());
      }
    }
  }
  previous.push_back(output_dir_ / "summary.txt");
  for (const std::filesystem::path& path : previous) {
    std::error_code ignored;  // a file already gone is fine
    std::filesystem::remove(path, ignored);
  }

  // Start this run's list.
  written_.clear();
  std::ofstream file(list);
  file << "summary.txt\n";
  if (!file) throw std::runtime_error("cannot write " + list.string());
}

std::filesystem::path Chapter::figure_path(const std::string& file) const {
  if (!plain_name(file)) {
    throw std::invalid_argument("app::Chapter::figure_path: \"" + file +
                                "\" must be a file name without a directory");
  }
  if (parsed_ && std::find(written_.begin(), written_.end(), file) == written_.end()) {
    written_.push_back(file);
    std::ofstream list(output_dir_ / files_list, std::ios::app);
    list << file << "\n";
    if (!list) throw std::runtime_error("cannot write " + (output_dir_ / files_list).string());
  }
  return output_dir_ / file;
}

// ---- Summary and checks -----------------------------------------------------------------------

void Chapter::summary(const std::string& key, const std::string& value) {
  if (!parsed_) {
    throw std::logic_error("app::Chapter::summary(\"" + key + "\") called before parse()");
  }
  const bool good_key = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (!good_key) {
    throw std::invalid_argument("app::Chapter::summary: bad key \"" + key +
                                "\" (use letters, digits, '_', '-', '.')");
  }
  std::string one_line = value;
  std::replace(one_line.begin(), one_line.end(), '\n', ' ');
  std::replace(one_line.begin(), one_line.end(), '\r', ' ');

  auto same_key = [&key](const auto& entry) { return entry.first == key; };
  if (auto entry = std::find_if(summary_.begin(), summary_.end(), same_key);
      entry != summary_.end()) {
    entry->second = one_line;
  } else {
    summary_.emplace_back(key, one_line);
  }
  write_summary();
}

void Chapter::write_summary() const {
  // Write a temporary file and rename it, so a reader never sees half a summary.
  const std::filesystem::path path = output_dir_ / "summary.txt";
  const std::filesystem::path temporary = output_dir_ / "summary.txt.tmp";
  {
    std::ofstream file(temporary);
    file << "# " << title_ << ": summary written by the program (key = value)\n";
    for (const auto& [key, value] : summary_) {
      file << key << " = " << value << "\n";
    }
    if (!file) {
      throw std::runtime_error("cannot write " + temporary.string());
    }
  }
  std::filesystem::rename(temporary, path);
}

bool Chapter::check(bool ok, const std::string& message) {
  checks_.push_back({ok, message});
  if (!ok) {
    *err_ << name_ << ": check failed: " << message << "\n" << std::flush;
  }
  return ok;
}

void Chapter::begin_claims(bool own_schemes) {
  own_schemes_ = own_schemes;
  *out_ << "\nChecks\n";
  if (!own_schemes)
    *out_ << "  (the options change the schemes: the claims are reported, not checked)\n";
  *out_ << std::flush;
}

// One claim line, "  [tag] what", wrapped at 100 columns (continuation lines indented).
void Chapter::print_claim(const std::string& tag, const std::string& what) {
  *out_ << wrap("  [" + tag + "] " + what, 100, 6) << "\n" << std::flush;
}

bool Chapter::claim(bool ok, const std::string& what, bool always) {
  if (!own_schemes_ && !always) {
    print_claim(ok ? "as claimed" : "not as claimed", what);
    return ok;
  }
  print_claim(ok ? "ok" : "FAILED", what);
  return check(ok, what);
}

bool Chapter::not_reproduced(bool holds, const std::string& what) {
  if (!own_schemes_) {
    print_claim(holds ? "reproduced" : "not reproduced", what);
    return holds;
  }
  print_claim(holds ? "FAILED: reproduces" : "not reproduced", what);
  check(!holds, what + " (the chapter found it not to reproduce; it now does)");
  return holds;
}

int Chapter::failed_checks() const {
  return static_cast<int>(
      std::count_if(checks_.begin(), checks_.end(), [](const Check& c) { return !c.ok; }));
}

int Chapter::finish() {
  const int failed = failed_checks();
  const int total = static_cast<int>(checks_.size());
  if (parsed_) {
    summary("checks",
            std::to_string(total - failed) + " passed, " + std::to_string(failed) + " failed");
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.3f s", clock_.seconds());
    summary("run_time", seconds);
  }
  if (failed == 0) {
    if (total > 0) {
      *out_ << "All " << total << (total == 1 ? " check" : " checks") << " passed.\n" << std::flush;
    }
    return 0;
  }
  *err_ << name_ << ": error: " << failed << " of " << total << (total == 1 ? " check" : " checks")
        << " failed:\n";
  for (const Check& c : checks_) {
    if (!c.ok) *err_ << "  - " << c.message << "\n";
  }
  // The checks hold the chapter's numbers at its defaults (full or --quick): when the user
  // changed a scene parameter, say which, so that a failure is not read as a broken program.
  std::string changed;
  for (const CLI::Option* option : cli_.get_options()) {
    if (option->get_group() != "Scene parameters" || option->count() == 0) continue;
    const auto& given = option->results();
    std::string value;
    for (const std::string& r : given) value += (value.empty() ? "" : " ") + r;
    changed +=
        "  " + option->get_name() + " " + value + " (default " + option->get_default_str() + ")\n";
  }
  if (!changed.empty()) {
    *err_ << "The checks are set for the chapter's defaults";
    *err_ << (quick_ ? " (with --quick)" : "") << "; these scene parameters differ from them:\n"
          << changed << "A failed check may then measure what they change, not a fault of the "
          << "program.\n";
  }
  *err_ << std::flush;
  return 1;
}

void Chapter::set_streams(std::ostream& out, std::ostream& err) {
  out_ = &out;
  err_ = &err;
}

int checked_output_status(int status) noexcept {
  errno = 0;
  bool lost = false;
  try {
    std::cout.flush();
    lost = !std::cout.good();
  } catch (...) {
    lost = true;
  }
  // (std::cout writes through C's stdout: an error there is where a full disk shows)
  lost = std::fflush(stdout) != 0 || std::ferror(stdout) != 0 || lost;
  if (!lost) return status;
  const int cause = errno;
  std::fprintf(stderr,
               "error: the standard output could not be written%s%s%s: the run's console "
               "output is incomplete\n",
               cause != 0 ? " (" : "", cause != 0 ? std::strerror(cause) : "",
               cause != 0 ? ")" : "");
  return status != 0 ? status : 1;
}

void report_exception(const char* what) noexcept {
  try {
    std::cout << std::flush;
    std::cerr << "error: " << what << std::endl;
  } catch (...) {
    std::fputs("error: (message could not be printed)\n", stderr);
  }
}

}  // namespace app
