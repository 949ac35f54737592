// The form of a chapter, measured over its whole folder (the program and every helper file
// beside it: everything the chapter's page shows), so that no measure can be met by moving a
// chapter's code out of sight.
//
//  - No code without prose for long: a chapter page shows each run of code lines between two
//    prose lines (`///`) as one block, and no block may be longer than 40 non-blank lines
//    (plain `//` comments count: they sit inside the block).  deal.II's step-4, the model, has
//    at most 20 and 9 on average; a reader who meets 40 lines of code without a sentence has
//    lost the thread.  Every block over the limit is named with its file and line.
//  - Prose and code, counted: lines of prose (`///`) and of code (not blank, not a comment) over
//    the folder, with their ratio.  Printed, not enforced: a ratio is a symptom to watch (the
//    house style), and a floor on it was met once by moving code to where no page showed it.
//
//   sph_chapter_form <project root> [--limit N]    exits 1 if a block is longer than the limit
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// Whether a line is prose, as the page converter reads it: `///`, but not `////` or `///<`.
bool is_prose(const std::string& line, std::size_t start) {
  if (line.compare(start, 3, "///") != 0) return false;
  return start + 3 >= line.size() || (line[start + 3] != '/' && line[start + 3] != '<');
}

/// One block of code as the page shows it: where it starts and how many non-blank lines.
struct Block {
  fs::path file;
  std::size_t line = 0;
  long length = 0;
};

/// The counts of one file, and its code blocks.
struct FileForm {
  long prose = 0, code = 0;
  std::vector<Block> blocks;
};

FileForm measure(const fs::path& file) {
  std::ifstream in(file);
  FileForm form;
  Block block{file, 0, 0};
  const auto close = [&] {
    if (block.length > 0) form.blocks.push_back(block);
    block = Block{file, 0, 0};
  };
  std::size_t number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const auto start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos) continue;  // blank: neither breaks nor lengthens a block
    if (is_prose(line, start)) {
      ++form.prose;
      close();
      continue;
    }
    if (line.compare(start, 12, "#pragma once") == 0) continue;  // not shown on the page
    if (line.compare(start, 2, "//") != 0) ++form.code;
    if (block.length == 0) block.line = number;
    ++block.length;
  }
  close();
  return form;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && !(argc == 4 && std::string(argv[2]) == "--limit")) {
    std::fprintf(stderr, "usage: sph_chapter_form <project root> [--limit N]\n");
    return 2;
  }
  const long limit = argc == 4 ? std::atol(argv[3]) : 40;
  if (limit <= 0) {
    std::fprintf(stderr, "sph_chapter_form: --limit must be a positive number of lines\n");
    return 2;
  }
  const fs::path root = argv[1];
  const fs::path chapters = root / "chapters";
  std::vector<fs::path> dirs;
  if (fs::is_directory(chapters)) {
    for (const auto& dir : fs::directory_iterator(chapters))
      if (dir.is_directory()) dirs.push_back(dir.path());
  }
  std::sort(dirs.begin(), dirs.end());
  if (dirs.empty()) {
    std::fprintf(stderr, "sph_chapter_form: no chapter folders under %s\n",
                 chapters.string().c_str());
    return 2;
  }
  std::vector<Block> too_long;
  std::printf("%-32s %6s %6s %6s %7s  %s\n", "chapter (whole folder)", "files", "prose", "code",
              "ratio", "longest block of code without prose");
  for (const fs::path& dir : dirs) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
      const auto ext = entry.path().extension();
      if (entry.is_regular_file() && (ext == ".cpp" || ext == ".hpp")) files.push_back(entry);
    }
    if (files.empty()) continue;
    std::sort(files.begin(), files.end());
    long prose = 0, code = 0, blocks = 0, lines_in_blocks = 0;
    Block longest;
    for (const fs::path& file : files) {
      const FileForm form = measure(file);
      prose += form.prose, code += form.code;
      for (const Block& b : form.blocks) {
        ++blocks, lines_in_blocks += b.length;
        if (b.length > longest.length) longest = b;
        if (b.length > limit) too_long.push_back(b);
      }
    }
    const double ratio = code > 0 ? double(prose) / double(code) : 0.0;
    const double mean = blocks > 0 ? double(lines_in_blocks) / double(blocks) : 0.0;
    std::printf("%-32s %6zu %6ld %6ld %7.2f  %ld lines at %s:%zu (mean %.1f)\n",
                dir.filename().string().c_str(), files.size(), prose, code, ratio, longest.length,
                longest.file.filename().string().c_str(), longest.line, mean);
  }
  if (!too_long.empty()) {
    std::printf("\n%zu blocks of code are longer than %ld lines without a line of prose:\n",
                too_long.size(), limit);
    for (const Block& b : too_long) {
      std::printf("  %s:%zu  %ld lines\n", fs::relative(b.file, root).string().c_str(), b.line,
                  b.length);
    }
    return 1;
  }
  std::printf("\nno block of code is longer than %ld lines without prose\n", limit);
  return 0;
}
