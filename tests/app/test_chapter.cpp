// lib/app: the conventions every chapter program follows — options, errors, summary, checks.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/chapter.hpp"

namespace {

namespace fs = std::filesystem;

/// A command line that owns its strings and hands out main()-style argc/argv.
struct CommandLine {
  explicit CommandLine(std::vector<std::string> words) : words_(std::move(words)) {
    for (std::string& word : words_) pointers_.push_back(word.data());
    pointers_.push_back(nullptr);
  }
  int argc() const { return static_cast<int>(words_.size()); }
  char** argv() { return pointers_.data(); }

 private:
  std::vector<std::string> words_;
  std::vector<char*> pointers_;
};

/// A fresh output directory for one test.
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(SPH_TEST_OUTPUT_DIR) / "app" / name;
  fs::remove_all(dir);
  return dir;
}

/// The result of parsing one command line with a chapter that has two parameters.
struct Parsed {
  int code;
  std::string out;
  std::string err;
  double gamma;
  int particles;
  bool quick;
};

Parsed parse(std::vector<std::string> words) {
  CommandLine line(std::move(words));
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  std::ostringstream out, err;
  chapter.set_streams(out, err);
  double gamma = 1.4;
  int particles = 450;
  chapter.parameter("--gamma", gamma, "adiabatic index").check(app::greater_than(1.0));
  chapter.parameter("--particles", particles, "particles").check(app::at_least(2));
  const int code = chapter.parse();
  return {code, out.str(), err.str(), gamma, particles, chapter.quick()};
}

std::string read(const fs::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("a good command line parses and sets the parameters", "[app]") {
  const fs::path dir = scratch("good");
  const Parsed result =
      parse({"ch99", "--gamma", "1.6", "--particles=100", "--quick", "--output", dir.string()});
  CHECK(result.code == -1);
  CHECK(result.err.empty());
  CHECK(result.gamma == 1.6);
  CHECK(result.particles == 100);
  CHECK(result.quick);
  CHECK(fs::is_directory(dir));
}

TEST_CASE("--help prints the options and exits with zero", "[app]") {
  const Parsed result = parse({"ch99", "--help"});
  CHECK(result.code == 0);
  CHECK(result.out.find("Chapter 99: a test") != std::string::npos);
  CHECK(result.out.find("--gamma") != std::string::npos);
  CHECK(result.out.find("--quick") != std::string::npos);
  CHECK(result.out.find("--threads") != std::string::npos);
  CHECK(result.err.empty());
}

TEST_CASE("an unknown option is an error naming the option", "[app]") {
  const Parsed result = parse({"ch99", "--gama", "1.6"});
  CHECK(result.code > 0);
  CHECK(result.err.find("--gama") != std::string::npos);
  CHECK(result.err.find("error") != std::string::npos);
}

TEST_CASE("an impossible value is an error naming the option and the problem", "[app]") {
  SECTION("below the bound") {
    const Parsed result = parse({"ch99", "--gamma", "0.5"});
    CHECK(result.code > 0);
    CHECK(result.err.find("--gamma") != std::string::npos);
    CHECK(result.err.find("must be greater than 1") != std::string::npos);
  }
  SECTION("not a number") {
    const Parsed result = parse({"ch99", "--particles", "many"});
    CHECK(result.code > 0);
    CHECK(result.err.find("--particles") != std::string::npos);
  }
  SECTION("not finite") {
    const Parsed result = parse({"ch99", "--gamma", "nan"});
    CHECK(result.code > 0);
    CHECK(result.err.find("--gamma") != std::string::npos);
    CHECK(result.err.find("finite") != std::string::npos);
  }
  SECTION("a fraction for a whole number") {
    const Parsed result = parse({"ch99", "--particles", "35.5"});
    CHECK(result.code > 0);
    CHECK(result.err.find("--particles: must be a whole number") != std::string::npos);
  }
  SECTION("a huge number is quoted readably") {
    const Parsed result = parse({"ch99", "--particles", "1" + std::string(300, '0')});
    CHECK(result.code > 0);
    CHECK(result.err.find("--particles: is far too large, got 1e+300") != std::string::npos);
  }
  SECTION("a whole number may be written with an exponent") {
    const fs::path dir = scratch("exponent");
    const Parsed result = parse({"ch99", "--particles", "2e3", "--output", dir.string()});
    CHECK(result.code == -1);
    CHECK(result.particles == 2000);
  }
  SECTION("a missing value") {
    const Parsed result = parse({"ch99", "--gamma"});
    CHECK(result.code > 0);
    CHECK(result.err.find("--gamma: needs a value") != std::string::npos);
  }
  SECTION("a negative thread count") {
    const Parsed result = parse({"ch99", "--threads", "-2"});
    CHECK(result.code > 0);
    CHECK(result.err.find("--threads") != std::string::npos);
  }
  // The messages below were CLI11's own ("Could not convert: --threads = 2.5", "At Most 1
  // required but received 2", "The following argument was not expected"): every option error
  // now reads "--option: what is wrong".
  SECTION("a fraction of a thread") {
    const Parsed result = parse({"ch99", "--threads", "2.5"});
    CHECK(result.code > 0);
    CHECK(result.err.find("--threads: must be a whole number, got 2.5") != std::string::npos);
  }
  SECTION("an option given twice") {
    const Parsed result = parse({"ch99", "--gamma", "1.4", "--gamma", "1.6"});
    CHECK(result.code > 0);
    CHECK(result.err.find("--gamma: given 2 times; give it once") != std::string::npos);
  }
  SECTION("an argument without a name") {
    const Parsed result = parse({"ch99", "1.4"});
    CHECK(result.code > 0);
    CHECK(result.err.find("unexpected argument 1.4: every parameter is named") !=
          std::string::npos);
  }
}

TEST_CASE("a parameter must be named with dashes", "[app]") {
  CommandLine line({"ch99"});
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  double gamma = 1.4;
  CHECK_THROWS_AS(chapter.parameter("gamma", gamma, "adiabatic index"), std::invalid_argument);
}

TEST_CASE("a switch is off by default and on when given", "[app]") {
  for (const bool given : {false, true}) {
    std::vector<std::string> words{"ch99", "--output", scratch("flag").string()};
    if (given) words.push_back("--no-viscosity");
    CommandLine line(words);
    app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
    std::ostringstream out, err;
    chapter.set_streams(out, err);
    bool no_viscosity = false;
    chapter.flag("--no-viscosity", no_viscosity, "switch the viscosity off");
    REQUIRE(chapter.parse() == -1);
    CHECK(no_viscosity == given);
  }
}

TEST_CASE("a condition between parameters is checked by parse", "[app]") {
  CommandLine line(
      {"ch99", "--h-min", "2", "--h-max", "1", "--output", scratch("require").string()});
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  std::ostringstream out, err;
  chapter.set_streams(out, err);
  double h_min = 0.1, h_max = 1.0;
  chapter.parameter("--h-min", h_min, "smallest smoothing length");
  chapter.parameter("--h-max", h_max, "largest smoothing length");
  chapter.require([&] { return h_min < h_max; }, "--h-min must be smaller than --h-max");
  CHECK(chapter.parse() > 0);
  CHECK(err.str().find("--h-min must be smaller than --h-max") != std::string::npos);
}

TEST_CASE("a condition's message can quote the values read", "[app]") {
  CommandLine line({"ch99", "--neighbours", "12", "--quick", "--output", scratch("why").string()});
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  std::ostringstream out, err;
  chapter.set_streams(out, err);
  double neighbours = 4;
  int cells = 800;
  chapter.parameter("--neighbours", neighbours, "neighbours");
  chapter.parameter("--cells", cells, "cells", 400);
  chapter.require([&] { return cells >= 50 * neighbours; },
                  [&] {
                    return "--neighbours " + app::show(neighbours) +
                           " needs --cells >= " + app::show(50 * neighbours) + ", got " +
                           app::show(cells);
                  });
  CHECK(chapter.parse() > 0);  // (the condition sees the quick default)
  CHECK(err.str().find("--neighbours 12 needs --cells >= 600, got 400") != std::string::npos);
}

TEST_CASE("summary.txt holds key = value lines, later values replacing earlier", "[app]") {
  const fs::path dir = scratch("summary");
  CommandLine line({"ch99", "--output", dir.string()});
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  std::ostringstream out, err;
  chapter.set_streams(out, err);
  REQUIRE(chapter.parse() == -1);
  chapter.summary("error", "L1(rho) = 0.5");
  chapter.summary("error", "L1(rho) = 0.0021 at N = 1800");
  chapter.summary("note", "two\nlines");
  CHECK_THROWS_AS(chapter.summary("bad key", "x"), std::invalid_argument);
  CHECK(chapter.finish() == 0);

  const std::string text = read(dir / "summary.txt");
  CHECK(text.find("chapter = 99-test\n") != std::string::npos);
  CHECK(text.find("mode = full\n") != std::string::npos);
  CHECK(text.find("error = L1(rho) = 0.0021 at N = 1800\n") != std::string::npos);
  CHECK(text.find("L1(rho) = 0.5") == std::string::npos);
  CHECK(text.find("note = two lines\n") != std::string::npos);
  CHECK(text.find("checks = 0 passed, 0 failed\n") != std::string::npos);
  CHECK(text.find("run_time = ") != std::string::npos);
}

TEST_CASE("a failed check makes finish return non-zero and is reported", "[app]") {
  const fs::path dir = scratch("checks");
  CommandLine line({"ch99", "--output", dir.string()});
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  std::ostringstream out, err;
  chapter.set_streams(out, err);
  REQUIRE(chapter.parse() == -1);
  CHECK(chapter.check(true, "fine"));
  CHECK_FALSE(chapter.check(false, "L1(rho) = 0.004 exceeds 0.003"));
  CHECK(chapter.failed_checks() == 1);
  CHECK(chapter.finish() != 0);
  CHECK(err.str().find("1 of 2 checks failed") != std::string::npos);
  CHECK(err.str().find("L1(rho) = 0.004 exceeds 0.003") != std::string::npos);
  CHECK(read(dir / "summary.txt").find("checks = 1 passed, 1 failed") != std::string::npos);
}

// A check that fails under parameters the user changed names them, so that the failure is
// read as what they change, not as a broken program; with the defaults nothing is added.
TEST_CASE("a failed check names the scene parameters that differ from the defaults", "[app]") {
  const auto run = [](std::vector<std::string> args) {
    CommandLine line(std::move(args));
    app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
    double gamma = 1.4;
    int particles = 450;
    chapter.parameter("--gamma", gamma, "adiabatic index");
    chapter.parameter("--particles", particles, "particles");
    std::ostringstream out, err;
    chapter.set_streams(out, err);
    REQUIRE(chapter.parse() == -1);
    chapter.check(false, "L1(rho) = 0.004 exceeds 0.003");
    CHECK(chapter.finish() != 0);
    return err.str();
  };
  const std::string changed =
      run({"ch99", "--gamma", "1.6", "--output", scratch("changed").string()});
  CHECK(changed.find("these scene parameters differ") != std::string::npos);
  CHECK(changed.find("--gamma 1.6 (default 1.4)") != std::string::npos);
  CHECK(changed.find("--particles") == std::string::npos);
  const std::string defaults = run({"ch99", "--output", scratch("defaults").string()});
  CHECK(defaults.find("differ") == std::string::npos);
}

TEST_CASE("all checks passing makes finish return zero", "[app]") {
  CommandLine line({"ch99", "--output", scratch("pass").string()});
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  std::ostringstream out, err;
  chapter.set_streams(out, err);
  REQUIRE(chapter.parse() == -1);
  chapter.check(true, "fine");
  CHECK(chapter.finish() == 0);
  CHECK(out.str() == "All 1 check passed.\n");
}

TEST_CASE("run_main turns exceptions into exit status 1 and a message", "[app]") {
  CHECK(app::run_main([] { return 0; }) == 0);
  CHECK(app::run_main([] { return 3; }) == 3);
  CHECK(app::run_main([] {}) == 0);

  // Catch what run_main writes to std::cerr.
  std::ostringstream captured;
  std::streambuf* const original = std::cerr.rdbuf(captured.rdbuf());
  const int from_error =
      app::run_main([]() -> int { throw std::runtime_error("particle 7 has negative mass"); });
  const int from_other = app::run_main([]() -> int { throw 42; });
  std::cerr.rdbuf(original);

  CHECK(from_error == 1);
  CHECK(from_other == 1);
  CHECK(captured.str() == "error: particle 7 has negative mass\nerror: unknown exception\n");
}

TEST_CASE("progress reports a final line and a status line with an estimate", "[app]") {
  std::ostringstream live, report;
  app::ProgressDisplay display;
  display.live = &live;
  display.report = &report;
  display.delay_seconds = 0.0;
  display.refresh_seconds = 0.0;
  {
    app::Progress progress(1.0, "test run", display);
    progress.update(0, 0.25, 0.25);
    progress.update(1, 0.5, 0.25);
    CHECK(progress.steps() == 2);
    CHECK(progress.status_line().find("step 2") != std::string::npos);
    CHECK(progress.status_line().find("ETA") != std::string::npos);
    progress.finish();
  }
  CHECK(live.str().find("test run: step") != std::string::npos);
  CHECK(report.str().rfind("test run: 2 steps to t = 0.5 in ", 0) == 0);
}

TEST_CASE("durations read naturally", "[app]") {
  CHECK(app::format_duration(0.4213) == "0.42 s");
  CHECK(app::format_duration(12.34) == "12.3 s");
  CHECK(app::format_duration(245.0) == "4 min 05 s");
  CHECK(app::format_duration(7380.0) == "2 h 03 min");
}

TEST_CASE("a claim is a check only when it is about the chapter's own schemes", "[app]") {
  const fs::path dir = scratch("claims");
  CommandLine line({"ch99", "--output", dir.string()});
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  std::ostringstream out, err;
  chapter.set_streams(out, err);
  REQUIRE(chapter.parse() == -1);
  chapter.begin_claims(false);  // the options changed the chapter's schemes
  CHECK(out.str().find("Checks\n") != std::string::npos);
  CHECK(out.str().find("reported, not checked") != std::string::npos);
  CHECK_FALSE(chapter.claim(false, "reported only"));
  CHECK(chapter.claim(true, "holds", true));
  CHECK(chapter.failed_checks() == 0);
  CHECK(out.str().find("  [not as claimed] reported only\n") != std::string::npos);
  CHECK(out.str().find("  [ok] holds\n") != std::string::npos);
  CHECK_FALSE(chapter.claim(false, "fails", true));
  CHECK(out.str().find("  [FAILED] fails\n") != std::string::npos);
  CHECK(chapter.failed_checks() == 1);
  CHECK(chapter.finish() == 1);
}

TEST_CASE("a claim found not to reproduce is checked as such, and fails if it reproduces",
          "[app]") {
  const fs::path dir = scratch("refuted");
  CommandLine line({"ch99", "--output", dir.string()});
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  std::ostringstream out, err;
  chapter.set_streams(out, err);
  REQUIRE(chapter.parse() == -1);
  chapter.begin_claims(true);
  CHECK_FALSE(chapter.not_reproduced(false, "a paper's claim"));
  CHECK(out.str().find("  [not reproduced] a paper's claim\n") != std::string::npos);
  CHECK(chapter.failed_checks() == 0);
  CHECK(chapter.not_reproduced(true, "now holds"));
  CHECK(out.str().find("  [FAILED: reproduces] now holds\n") != std::string::npos);
  CHECK(chapter.failed_checks() == 1);
  chapter.begin_claims(false);  // other options: reported only
  CHECK(chapter.not_reproduced(true, "reported"));
  CHECK(out.str().find("  [reproduced] reported\n") != std::string::npos);
  CHECK(chapter.failed_checks() == 1);
  CHECK(chapter.finish() == 1);
}

namespace {

/// A chapter with a resolution parameter whose quick default is 40 (default 400).
struct QuickRun {
  int code;
  int cells;
  bool given;
  std::string help;
};

QuickRun quick_run(std::vector<std::string> words) {
  words.insert(words.begin(), "ch99");
  words.insert(words.end(), {"--output", scratch("quick").string()});
  CommandLine line(words);
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  std::ostringstream out, err;
  chapter.set_streams(out, err);
  int cells = 400;
  chapter.parameter("--cells", cells, "cells per unit length", 40).check(app::between(10, 4000));
  const int code = chapter.parse();
  return {code, cells, code == -1 && chapter.given("--cells"), out.str()};
}

}  // namespace

TEST_CASE("an option given on the command line wins over its quick default", "[app]") {
  SECTION("the default without --quick") {
    const QuickRun run = quick_run({});
    CHECK(run.code == -1);
    CHECK(run.cells == 400);
    CHECK_FALSE(run.given);
  }
  SECTION("the quick default with --quick") {
    const QuickRun run = quick_run({"--quick"});
    CHECK(run.code == -1);
    CHECK(run.cells == 40);
    CHECK_FALSE(run.given);
  }
  SECTION("the given value, before or after --quick") {
    for (const auto& words : std::vector<std::vector<std::string>>{{"--quick", "--cells", "2000"},
                                                                   {"--cells=2000", "--quick"}}) {
      const QuickRun run = quick_run(words);
      CHECK(run.code == -1);
      CHECK(run.cells == 2000);
      CHECK(run.given);
    }
  }
  SECTION("a given value equal to the full default is kept too") {
    const QuickRun run = quick_run({"--quick", "--cells", "400"});
    CHECK(run.cells == 400);
  }
  SECTION("--help shows both defaults and the range") {
    const QuickRun run = quick_run({"--help"});
    CHECK(run.code == 0);
    CHECK(run.help.find("(default 400, with --quick 40; in [10, 4000])") != std::string::npos);
  }
}

TEST_CASE("a count above its bound is refused with the memory it would need", "[app]") {
  CommandLine line({"ch99", "--particles", "2e9", "--output", scratch("count").string()});
  app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
  std::ostringstream out, err;
  chapter.set_streams(out, err);
  double particles = 1000;
  chapter.parameter("--particles", particles, "particles")
      .check(app::count_between(100, 200000, [](double n) { return 200 * n; }));
  CHECK(chapter.parse() > 0);
  CHECK(err.str().find("--particles: 2e+09 would need about 400 GB of memory; at most 200000") !=
        std::string::npos);
}

TEST_CASE("numbers in messages read as %g prints them", "[app]") {
  CHECK(app::show(0.2) == "0.2");
  CHECK(app::show(1e-6) == "1e-06");
  CHECK(app::show(2e9) == "2e+09");
  CHECK(app::show(3200) == "3200");
  CHECK(app::show(1e300) == "1e+300");
  CHECK(app::show(1.0 / 3.0, 3) == "0.333");
  CHECK(app::show_bytes(512) == "512 B");
  CHECK(app::show_bytes(4e11) == "400 GB");
  CHECK(app::show_bytes(3.14e6) == "3.14 MB");
}

TEST_CASE("a run removes the files of the previous run in its output directory", "[app]") {
  const fs::path dir = scratch("cleanup");
  fs::create_directories(dir);
  const auto touch = [&dir](const std::string& file) { std::ofstream(dir / file) << "x\n"; };
  const auto run = [&dir](const std::vector<std::string>& files) {
    CommandLine line({"ch99", "--output", dir.string()});
    app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
    std::ostringstream out, err;
    chapter.set_streams(out, err);
    REQUIRE(chapter.parse() == -1);
    // (never finished: as a run that stops half-way)
    for (const std::string& file : files) std::ofstream(chapter.figure_path(file)) << "new\n";
  };
  // A file of someone else's is in the directory before the first run.
  touch("notes.md");

  // The first run writes two figures and a snapshot; the second stops after one figure.
  run({"a.png", "b.png", "state_t0.1.dat"});
  CHECK(fs::exists(dir / "b.png"));
  run({"a.png"});
  CHECK(read(dir / "a.png") == "new\n");
  CHECK_FALSE(fs::exists(dir / "b.png"));
  CHECK_FALSE(fs::exists(dir / "state_t0.1.dat"));
  CHECK(fs::exists(dir / "notes.md"));
  CHECK(read(dir / "files.txt") == "summary.txt\na.png\n");
  CHECK(fs::exists(dir / "summary.txt"));

  SECTION("a directory written before files.txt existed: its figures go if it is this chapter's") {
    fs::remove(dir / "files.txt");
    touch("old.png");
    touch("old.dat");
    run({});
    CHECK_FALSE(fs::exists(dir / "old.png"));
    CHECK_FALSE(fs::exists(dir / "old.dat"));
    CHECK(fs::exists(dir / "notes.md"));
  }
  SECTION("a directory that is not this chapter's keeps its figures") {
    fs::remove(dir / "files.txt");
    std::ofstream(dir / "summary.txt") << "chapter = 98-other\n";
    touch("old.png");
    run({});
    CHECK(fs::exists(dir / "old.png"));
  }
  SECTION("a name with a directory is refused") {
    CommandLine line({"ch99", "--output", dir.string()});
    app::Chapter chapter("99-test", "Chapter 99: a test", line.argc(), line.argv());
    std::ostringstream out, err;
    chapter.set_streams(out, err);
    REQUIRE(chapter.parse() == -1);
    CHECK_THROWS_AS(chapter.figure_path("../escape.png"), std::invalid_argument);
  }
}
