// line_width FILE WIDTH: exits 1 (and names each such line) if a line of FILE is wider than
// WIDTH characters (UTF-8 code points, so "Δx" is two), 2 if FILE cannot be read.  The chapter
// tests run it on each chapter's console output, which the documentation shows in a box of
// 100 columns: a wider line would hide behind a sideways scroll.
//
// line_width --sources WIDTH FILE...: the same for source files, whose listings the
// documentation shows in the same box; a row of a Markdown table in the text (a line whose
// text starts with `/// |`) is let through, since a table row cannot be wrapped.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace {

bool is_table_row(const std::string& line) {
  const auto start = line.find_first_not_of(" \t");
  if (start == std::string::npos || line.compare(start, 3, "///") != 0) return false;
  const auto text = line.find_first_not_of(" \t", start + 3);
  return text != std::string::npos && line[text] == '|';
}

// The lines of `path` wider than `width`, each named on stderr; -1 if it cannot be read.
int wide_lines(const char* path, long width, bool sources) {
  std::ifstream file(path);
  if (!file) {
    std::cerr << "line_width: cannot read " << path << "\n";
    return -1;
  }
  int wide = 0;
  long number = 0;
  for (std::string line; std::getline(file, line);) {
    ++number;
    long characters = 0;
    for (unsigned char c : line) characters += (c & 0xC0) != 0x80;  // not a continuation byte
    if (characters > width && !(sources && is_table_row(line))) {
      std::cerr << path << ":" << number << ": " << characters << " characters (at most " << width
                << "): " << line << "\n";
      ++wide;
    }
  }
  return wide;
}

}  // namespace

int main(int argc, char** argv) {
  const bool sources = argc >= 3 && std::string(argv[1]) == "--sources";
  if (!sources && argc != 3) {
    std::cerr << "usage: line_width FILE WIDTH | line_width --sources WIDTH FILE...\n";
    return 2;
  }
  const long width = std::strtol(argv[2], nullptr, 10);  // WIDTH is second in both forms
  if (!sources) {
    const int wide = wide_lines(argv[1], width, false);
    return wide < 0 ? 2 : wide > 0 ? 1 : 0;
  }
  int wide = 0;
  for (int k = 3; k < argc; ++k) {
    const int w = wide_lines(argv[k], width, true);
    if (w < 0) return 2;
    wide += w;
  }
  return wide > 0 ? 1 : 0;
}
