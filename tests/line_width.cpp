// line_width FILE WIDTH: exits 1 (and names each such line) if a line of FILE is wider than
// WIDTH characters (UTF-8 code points, so "Δx" is two), 2 if FILE cannot be read.  The chapter
// tests run it on each chapter's console output, which the documentation shows in a box of
// 100 columns: a wider line would hide behind a sideways scroll.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: line_width FILE WIDTH\n";
    return 2;
  }
  std::ifstream file(argv[1]);
  if (!file) {
    std::cerr << "line_width: cannot read " << argv[1] << "\n";
    return 2;
  }
  const long width = std::strtol(argv[2], nullptr, 10);
  int wide = 0;
  long number = 0;
  for (std::string line; std::getline(file, line);) {
    ++number;
    long characters = 0;
    for (unsigned char c : line) characters += (c & 0xC0) != 0x80;  // not a continuation byte
    if (characters > width) {
      std::cerr << argv[1] << ":" << number << ": " << characters << " characters (at most "
                << width << "): " << line << "\n";
      ++wide;
    }
  }
  return wide > 0 ? 1 : 0;
}
