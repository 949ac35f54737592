#pragma once
/// \file
/// \brief Text for the console and for messages: app::format, printf into a std::string, and
/// app::wrap, a long line broken at spaces.
///
/// Every chapter prints its numbers with printf-style patterns, because a pattern such as
/// `"%.3e"` says in four characters what the reader will see.  The same patterns build the
/// messages of the checks and the labels of the figures, and that is what these helpers are for:
///
/// \code
/// chapter.check(l1 < 0.003, app::format("L1(rho) = %.3e at N = %d exceeds 0.003", l1, n));
/// std::printf("%s\n", app::wrap("  exact: " + solution.describe()).c_str());
/// \endcode

#include <cstdio>
#include <string>
#include <type_traits>

namespace app {

/// printf into a std::string of any length: `app::format("L1 = %.3e at N = %d", l1, n)`.
/// The arguments must be what printf takes, numbers and C strings; a std::string is passed as
/// `s.c_str()` (passing the std::string itself does not compile).
template <class... Args>
std::string format(const char* pattern, Args... args) {
  static_assert(((std::is_arithmetic_v<Args> || std::is_pointer_v<Args>)&&...),
                "app::format takes numbers and C strings (for a std::string s, pass s.c_str())");
  const int length = std::snprintf(nullptr, 0, pattern, args...);
  if (length <= 0) return {};
  std::string text(static_cast<std::size_t>(length), '\0');
  std::snprintf(text.data(), text.size() + 1, pattern, args...);
  return text;
}

/// \p text broken at spaces into lines of at most \p width characters, the first line keeping
/// the text's own leading spaces and every further line indented by \p indent spaces.  Runs of
/// spaces between words become one; a word longer than the width stays whole on its own line.
/// No newline is added at the end.  (Widths count bytes: meant for ASCII console output.)
inline std::string wrap(const std::string& text, std::size_t width = 100, std::size_t indent = 4) {
  const std::size_t first = text.find_first_not_of(' ');
  if (first == std::string::npos) return text;
  std::string out, line = text.substr(0, first);
  bool line_has_word = false;
  for (std::size_t pos = first; pos < text.size();) {
    std::size_t end = text.find(' ', pos);
    if (end == std::string::npos) end = text.size();
    if (end > pos) {
      const std::size_t length = end - pos;
      if (line_has_word && line.size() + 1 + length > width) {
        out += line + '\n';
        line.assign(indent, ' ');
        line_has_word = false;
      }
      if (line_has_word) line += ' ';
      line.append(text, pos, length);
      line_has_word = true;
    }
    pos = end + 1;
  }
  return out + line;
}

}  // namespace app
