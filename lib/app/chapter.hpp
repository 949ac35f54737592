#pragma once
/// \file
/// \brief app::Chapter: what every chapter program shares — its command line, its output
/// directory, its summary file and its checks — and app::run_main, which turns any exception
/// into a clear message and a non-zero exit.
///
/// A chapter program reads like this:
///
/// \code
/// #include "app/chapter.hpp"
///
/// int main(int argc, char** argv) {
///   return app::run_main([&] {
///     app::Chapter chapter("03-sod", "Chapter 3: the Sod shock tube", argc, argv);
///     double gamma = 1.4;
///     int particles = 450;
///     double t_end = 0.2;
///     chapter.parameter("--gamma", gamma, "adiabatic index").check(app::greater_than(1.0));
///     chapter.parameter("--particles", particles, "particles on the high-density side", 50)
///         .check(app::between(10, 100000));      // 50 with --quick, unless given
///     chapter.parameter("--t-end", t_end, "end time").check(app::between(1e-6, 10));
///     if (int rc = chapter.parse(); rc >= 0) return rc;   // --help, or a bad option
///
///     app::Progress progress(t_end, "Sod 1D");
///     // ... for each step: progress.update(step, t, dt);
///     progress.finish();
///     // ... plot into chapter.figure_path("sod_1d.png")
///
///     double l1 = 0.0021;
///     chapter.summary("error", "L1(rho) = " + app::format("%g", l1));
///     chapter.check(l1 < 0.003, "L1(rho) = " + app::format("%g", l1) + " exceeds 0.003");
///     return chapter.finish();   // non-zero if a check failed
///   });
/// }
/// \endcode
///
/// Every chapter understands `--help`, `--quick`, `--output DIR` and `--threads N`, plus its own
/// parameters.  An unknown option or an impossible value stops the program before it runs,
/// with a message on standard error naming the option and the problem, and a non-zero exit
/// status (CLI11's exit codes: 105 for a rejected value, 109 for an unknown option, ...).
///
/// **Ranges.**  Every numeric parameter has a range that `--help` states and parse() enforces
/// before any work starts: counts have an upper bound as well as a lower one, so that no value
/// can run for hours or ask for more memory than a machine has (app::count_between says, for a
/// count that is too large, how much memory it would need).
///
/// **Quick defaults.**  `--quick` changes the defaults of the resolution parameters, never an
/// option given on the command line: a parameter declared with a quick value
/// (`parameter(flag, value, description, quick_value)`) takes that value under `--quick` only
/// when the option is absent, and `--help` shows both defaults.  given() tells whether an
/// option was on the command line, for the rare default that depends on other options.
///
/// **Output files.**  A reader must never find the figures of two runs side by side in one
/// output directory, as a run that stops half-way into a used directory would leave them.  So
/// every file a chapter writes is named through figure_path(), which records it in `files.txt`
/// of the output directory as it is handed out; parse() first removes the files that the
/// previous run recorded there (and, in a directory written before `files.txt` existed, the
/// `.png` and `.dat` files of a directory whose summary.txt names this chapter).  Nothing else is
/// removed, so `--output` may name a directory that holds other files.  A directory that is
/// being written therefore holds the files of one run only, finished or not; summary.txt says
/// which (its `checks` and `run_time` lines are written at the end).  We preferred this to
/// writing into a temporary directory renamed at the end: a run that stops keeps what it made
/// for inspection, and no rename has to replace a directory that other files share.

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <map>
#include <memory>
#include <sstream>
#include <type_traits>
#include <utility>
#include <vector>

#include "app/options.hpp"
#include "app/progress.hpp"
#include "app/stopwatch.hpp"

namespace app {

/// The command line, output directory, summary file and checks of one chapter program.
///
/// Lifecycle: construct, declare parameters with parameter() / flag() / require(), call
/// parse() and return its code if it is >= 0, run the scene, write figures to figure_path(),
/// record numbers with summary() and verdicts with check(), and return finish().
class Chapter {
 public:
  /// A chapter called \p name (its directory name, e.g. `"01-kernel"`, which is also the
  /// default output directory `figures/01-kernel` in the source tree) with the heading
  /// \p title shown by `--help`.  \p argc and \p argv are main()'s; they are read by parse().
  Chapter(std::string name, std::string title, int argc, char** argv);

  /// Declares a scene parameter `flag` (e.g. `"--gamma"`, `"-n,--neighbours"`) bound to
  /// \p value, whose current value is the default shown by `--help`.  Floating-point values
  /// must be finite, integers whole.  Returns the CLI11 option, so validators can be attached:
  /// `.check(app::positive())`.  A flag without a leading dash throws std::invalid_argument.
  template <class T>
  CLI::Option& parameter(const std::string& flag, T& value, const std::string& description) {
    require_dashes(flag);
    CLI::Option* option = cli_.add_option(flag, value, description);
    option->capture_default_str()->group("Scene parameters");
    if constexpr (std::is_floating_point_v<T>) {
      option->check(finite());
    } else if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
      option->transform(whole_number());  // (a transform: it may rewrite 2e9 as 2000000000)
    }
    return *option;
  }

  /// The same, with a quick default: under `--quick`, parse() sets \p value to \p quick_value
  /// unless the option is given on the command line, which always wins.  `--help` shows
  /// "(default 800, with --quick 400; ...)".  The quick value must lie in the option's range.
  template <class T>
  CLI::Option& parameter(const std::string& flag, T& value, const std::string& description,
                         std::type_identity_t<T> quick_value) {
    CLI::Option& option = parameter(flag, value, description);
    std::ostringstream text;
    text.precision(12);
    text << quick_value;
    quick_defaults_.push_back({&option, [&value, quick_value] { value = quick_value; }});
    (*quick_notes_)[&option] = text.str();
    return option;
  }

  /// Declares an on/off switch `flag` (e.g. `"--no-viscosity"`) that sets \p value to true.
  CLI::Option& flag(const std::string& flag, bool& value, const std::string& description);

  /// Declares a condition between parameters that parse() checks after reading them, e.g.
  /// `chapter.require([&] { return h_min < h_max; }, "--h-min must be smaller than --h-max")`.
  void require(std::function<bool()> condition, std::string problem);
  /// The same, with the message made when the condition fails, so that it can quote the
  /// values: `[&] { return "--neighbours " + app::show(n) + " needs --cells >= ..."; }`.
  void require(std::function<bool()> condition, std::function<std::string()> problem);

  /// Reads the command line.  Returns -1 when the program should go on; otherwise the exit
  /// status to return from main(): 0 after `--help`, non-zero after an error, which has been
  /// reported on standard error.  On success it applies `--threads`, creates the output
  /// directory and starts summary.txt there.
  [[nodiscard]] int parse();

  /// True with `--quick`: a reduced resolution that runs in seconds, used by the tests.
  [[nodiscard]] bool quick() const { return quick_; }
  /// True when the option \p flag (any of its names, e.g. `"--cells"`) was given on the
  /// command line.  Call after parse().  An undeclared flag throws.
  [[nodiscard]] bool given(const std::string& flag) const;
  /// The `--threads` value; 0 means all the machine's cores (OpenMP's default).
  [[nodiscard]] int threads() const { return threads_; }
  /// The directory for figures and summary.txt (`--output`), created by parse().
  [[nodiscard]] const std::filesystem::path& output_dir() const { return output_dir_; }
  /// The path of a figure (or any output file) called \p file in the output directory, which
  /// records \p file in the directory's `files.txt`, so that the next run removes it before it
  /// starts (see "Output files" above).  \p file is a plain name, without a directory.
  [[nodiscard]] std::filesystem::path figure_path(const std::string& file) const;
  /// The chapter's name, e.g. `"01-kernel"`.
  [[nodiscard]] const std::string& name() const { return name_; }
  /// The chapter's title, e.g. `"Chapter 1: the smoothing kernel"`.
  [[nodiscard]] const std::string& title() const { return title_; }
  /// Wall-clock seconds since the chapter object was created.
  [[nodiscard]] double seconds() const { return clock_.seconds(); }
  /// The underlying CLI11 application, for anything the helpers above do not cover.
  CLI::App& cli() { return cli_; }

  /// Records `key = value` in `output_dir()/summary.txt`, which is rewritten at once (a later
  /// value for the same key replaces the earlier one).  The figures runner shows the `error`
  /// key in its table.  Keys are letters, digits, `_`, `-` and `.`; newlines in \p value become
  /// spaces.  Call after parse().
  void summary(const std::string& key, const std::string& value);

  /// Records a verdict.  When \p ok is false, \p message (which should say what was found and
  /// what was expected) is printed on standard error at once and again by finish(), and
  /// finish() returns non-zero.  Returns \p ok.
  bool check(bool ok, const std::string& message);

  /// Starts the chapter's claims: prints the heading "Checks", and, when the options have
  /// changed the schemes the claims are about (\p own_schemes false), says that those claims
  /// are reported, not checked.
  void begin_claims(bool own_schemes);

  /// A claim of the chapter, printed on one line (wrapped at 100 columns).  A check ("[ok]" or
  /// "[FAILED]", recorded as check() records it) when the run uses the chapter's own schemes
  /// (begin_claims) or when
  /// \p always -- a claim that must hold whatever the options, such as conservation; otherwise
  /// only reported, "[as claimed]" or "[not as claimed]", and it cannot fail the run.
  /// Returns \p ok.
  bool claim(bool ok, const std::string& what, bool always = false);

  /// A claim of a paper that the chapter found *not* to reproduce, with \p holds whether it
  /// holds in this run.  With the chapter's own schemes it is a check of that finding:
  /// "[not reproduced]" when the claim fails as the text says, and "[FAILED: reproduces]"
  /// (a failed check) when it holds -- the text must then change.  With other options it is
  /// only reported, "[not reproduced]" or "[reproduced]".  Returns \p holds.
  bool not_reproduced(bool holds, const std::string& what);

  /// Number of failed checks so far.
  [[nodiscard]] int failed_checks() const;

  /// Ends the run: records the checks and the run time in summary.txt, prints "All N checks
  /// passed." on standard output or the failed checks on standard error.  Returns the exit
  /// status for main(): 0 if every check passed, 1 otherwise.
  [[nodiscard]] int finish();

  /// Sends the messages that would go to std::cout and std::cerr to other streams (tests).
  void set_streams(std::ostream& out, std::ostream& err);

 private:
  void print_claim(const std::string& tag, const std::string& what);
  void write_summary() const;
  void remove_previous_outputs() const;
  static void require_dashes(const std::string& flag);

  struct QuickDefault {
    const CLI::Option* option;
    std::function<void()> set;  // sets the bound variable to the quick value
  };

  struct Requirement {
    std::function<bool()> condition;
    std::function<std::string()> problem;
  };
  struct Check {
    bool ok;
    std::string message;
  };

  bool own_schemes_ = true;  // begin_claims: whether claims about the schemes are checked
  std::string name_;
  std::string title_;
  int argc_;
  char** argv_;
  CLI::App cli_;
  Stopwatch clock_;
  bool quick_ = false;
  int threads_ = 0;
  std::string output_arg_;
  std::filesystem::path output_dir_;
  bool parsed_ = false;
  std::vector<Requirement> requirements_;
  std::vector<QuickDefault> quick_defaults_;
  // the quick value of each option that has one, shared with the help formatter
  std::shared_ptr<std::map<const CLI::Option*, std::string>> quick_notes_ =
      std::make_shared<std::map<const CLI::Option*, std::string>>();
  mutable std::vector<std::string> written_;  // the files handed out by figure_path()
  std::vector<std::pair<std::string, std::string>> summary_;
  std::vector<Check> checks_;
  std::ostream* out_ = &std::cout;
  std::ostream* err_ = &std::cerr;
};

/// Prints "error: <what>" on standard error (used by run_main).
void report_exception(const char* what) noexcept;

/// Flushes standard output and returns \p status, or 1 (with a message on standard error) if
/// anything the program wrote there was lost -- a full disk, a closed file -- so that a run
/// whose console output is incomplete never ends as a success (used by run_main).
int checked_output_status(int status) noexcept;

/// Runs \p body (a callable returning the exit status, or void for 0) and turns any exception
/// into "error: <what>" on standard error and exit status 1, so that bad input never crashes
/// a program; a standard output that could not be written is an error too.  Use as
/// `int main(int argc, char** argv) { return app::run_main([&] { ... }); }`.
template <class Body>
int run_main(Body&& body) noexcept {
  try {
    if constexpr (std::is_void_v<std::invoke_result_t<Body>>) {
      std::forward<Body>(body)();
      return checked_output_status(0);
    } else {
      return checked_output_status(static_cast<int>(std::forward<Body>(body)()));
    }
  } catch (const std::exception& error) {
    report_exception(error.what());
  } catch (...) {
    report_exception("unknown exception");
  }
  return 1;
}

}  // namespace app
