// Line and token scanning for the text formats, with line numbers for errors.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>

namespace sharpmesh::io {

class LineCursor {
 public:
  LineCursor(std::string_view text, std::size_t first_line = 1) : p_(text.data()), end_(text.data() + text.size()), next_line_number_(first_line) {}
  /// Next line without its end-of-line characters; false at the end of the text.
  bool next(std::string_view& line) {
    if (p_ >= end_) return false;
    const char* start = p_;
    while (p_ < end_ && *p_ != '\n') ++p_;
    const char* stop = p_;
    if (p_ < end_) ++p_;
    if (stop > start && stop[-1] == '\r') --stop;
    line = std::string_view(start, static_cast<std::size_t>(stop - start));
    line_number_ = next_line_number_++;
    return true;
  }
  std::size_t line_number() const { return line_number_; }
  std::size_t offset(std::string_view text) const { return static_cast<std::size_t>(p_ - text.data()); }

 private:
  const char* p_;
  const char* end_;
  std::size_t next_line_number_;
  std::size_t line_number_ = 0;
};

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/// Splits off the next whitespace-separated token; false when none is left.
inline bool next_token(std::string_view& text, std::string_view& token) {
  std::size_t i = 0;
  while (i < text.size() && is_space(text[i])) ++i;
  if (i == text.size()) { text = {}; return false; }
  std::size_t j = i;
  while (j < text.size() && !is_space(text[j])) ++j;
  token = text.substr(i, j - i);
  text.remove_prefix(j);
  return true;
}

inline bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && ptr == token.data() + token.size();
}

inline bool parse_integer(std::string_view token, std::int64_t& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && ptr == token.data() + token.size();
}

/// Strips a '#' comment and surrounding blanks.
inline std::string_view strip_comment(std::string_view line) {
  const std::size_t hash = line.find('#');
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
  while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
  return line;
}

}  // namespace sharpmesh::io
