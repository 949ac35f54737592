// The check that prose outweighs code in every chapter program: lines of text (`///`) against
// lines of code (not blank, not a comment), as the house style asks of a chapter (the model, the
// deal.II tutorial steps, has about 1.3).  Moving a chapter's scaffolding into lib/app/<topic>/
// or writing what a step does, why, and what to look for are the two ways to meet it.
//
//   sph_prose_ratio <root>    prints each chapter's ratio; exits 1 if one is below 1
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Count {
  long prose = 0, code = 0;
};

Count count_lines(const fs::path& file) {
  std::ifstream in(file);
  Count count;
  for (std::string line; std::getline(in, line);) {
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos) continue;  // blank
    if (line.compare(start, 3, "///") == 0) {
      ++count.prose;
    } else if (line.compare(start, 2, "//") != 0) {
      ++count.code;
    }
  }
  return count;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: sph_prose_ratio <project root>\n");
    return 2;
  }
  const fs::path chapters = fs::path(argv[1]) / "chapters";
  std::vector<fs::path> programs;
  for (const auto& dir : fs::directory_iterator(chapters)) {
    if (!dir.is_directory()) continue;
    for (const auto& file : fs::directory_iterator(dir.path()))
      if (file.path().extension() == ".cpp") programs.push_back(file.path());
  }
  std::sort(programs.begin(), programs.end());
  if (programs.empty()) {
    std::fprintf(stderr, "sph_prose_ratio: no chapter programs under %s\n",
                 chapters.string().c_str());
    return 2;
  }
  int below = 0;
  for (const auto& program : programs) {
    const Count c = count_lines(program);
    const double ratio = c.code > 0 ? double(c.prose) / double(c.code) : 0.0;
    const bool ok = c.prose >= c.code;
    below += !ok;
    std::printf("%-60s prose %4ld  code %4ld  ratio %.2f%s\n",
                fs::relative(program, argv[1]).string().c_str(), c.prose, c.code, ratio,
                ok ? "" : "  <- less prose than code");
  }
  return below > 0 ? 1 : 0;
}
