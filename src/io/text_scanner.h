#pragma once
/// \file text_scanner.h
/// Internal to the io area: a whitespace token scanner over a file held in memory, used by the strict
/// OFF and ascii PLY readers. Numbers are converted with std::from_chars (correctly rounded doubles,
/// so the file's decimal text is kept exactly). Not installed.
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <system_error>
#include <vector>

namespace adaptex::io_detail {

/// A blank inside an OBJ or MTL-reference line: space, tab or carriage return.
inline bool is_line_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/// Tokens separated by blanks and line ends; with \p comments, '#' starts a comment to the line end.
struct TextScanner {
  std::string_view text;  ///< The whole file.
  std::size_t pos = 0;    ///< Next unread byte.
  bool comments = false;  ///< Skip '#' comments.

  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

  /// Skips blanks, line ends and comments.
  void skip_space() {
    while (pos < text.size()) {
      if (is_space(text[pos])) {
        ++pos;
      } else if (comments && text[pos] == '#') {
        skip_line();
      } else {
        break;
      }
    }
  }
  /// Moves past the next line end (or to the end of the text).
  void skip_line() {
    const std::size_t nl = text.find('\n', pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
  }
  /// The next token (empty at the end of the text).
  std::string_view token() {
    skip_space();
    const std::size_t start = pos;
    while (pos < text.size() && !is_space(text[pos]) && !(comments && text[pos] == '#')) ++pos;
    return text.substr(start, pos - start);
  }
  /// The tokens left on the current line (up to a comment), then moves past the line end.
  std::vector<std::string_view> rest_of_line() {
    std::vector<std::string_view> out;
    while (true) {
      while (pos < text.size() && is_space(text[pos]) && text[pos] != '\n') ++pos;
      if (pos >= text.size() || text[pos] == '\n' || (comments && text[pos] == '#')) break;
      const std::size_t start = pos;
      while (pos < text.size() && !is_space(text[pos]) && !(comments && text[pos] == '#')) ++pos;
      out.push_back(text.substr(start, pos - start));
    }
    skip_line();
    return out;
  }
  std::size_t bytes_left() const { return text.size() - pos; }
};

/// Whole-token signed integer. False on anything else (also on overflow).
inline bool parse_int(std::string_view t, std::int64_t& out) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  const auto res = std::from_chars(t.data(), t.data() + t.size(), out);
  return !t.empty() && res.ec == std::errc() && res.ptr == t.data() + t.size();
}

/// Whole-token decimal number (nan/inf accepted, reported later by the validation). False on anything
/// else, also on a number out of the double range.
inline bool parse_double(std::string_view t, double& out) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  const auto res = std::from_chars(t.data(), t.data() + t.size(), out);
  return !t.empty() && res.ec == std::errc() && res.ptr == t.data() + t.size();
}

}  // namespace adaptex::io_detail
