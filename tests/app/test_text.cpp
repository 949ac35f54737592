// lib/app/text.hpp: printf into a string, and long lines broken at spaces.
#include <catch2/catch.hpp>

#include <string>

#include "app/text.hpp"

TEST_CASE("format: printf patterns into a string of any length", "[text]") {
  CHECK(app::format("L1 = %.3e at N = %d", 0.00123, 450) == "L1 = 1.230e-03 at N = 450");
  CHECK(app::format("%s: %zu pairs", "streams", std::size_t{79800}) == "streams: 79800 pairs");
  CHECK(app::format("no arguments") == "no arguments");
  CHECK(app::format("%s", "").empty());
  const std::string long_word(600, 'x');
  CHECK(app::format("<%s>", long_word.c_str()) == "<" + long_word + ">");
}

TEST_CASE("wrap: lines break at spaces and continue indented", "[text]") {
  CHECK(app::wrap("short line") == "short line");
  CHECK(app::wrap("  one two three four", 12, 4) == "  one two\n    three\n    four");
  // The first line keeps its own indentation; runs of spaces collapse.
  CHECK(app::wrap("   a  b   c", 100, 2) == "   a b c");
  // A word longer than the width stays whole on a line of its own.
  CHECK(app::wrap("a abcdefghij b", 5, 1) == "a\n abcdefghij\n b");
  CHECK(app::wrap("") == "");
  CHECK(app::wrap("    ") == "    ");
}
