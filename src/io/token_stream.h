// Whitespace-separated tokens across lines, with the line number of each,
// for formats whose records span lines (Bundler, NVM, Strecha cameras).
#pragma once

#include <cmath>
#include <string>
#include <string_view>

#include "io/text.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {

class TokenStream {
 public:
  TokenStream(std::string_view text, std::string path) : cursor_(text), path_(std::move(path)) {}

  /// Next token; false at the end of the text. Lines starting with '#' are skipped.
  bool next(std::string_view& token) {
    while (!io::next_token(line_, token)) {
      std::string_view line;
      if (!cursor_.next(line)) return false;
      std::size_t i = 0;
      while (i < line.size() && is_space(line[i])) ++i;
      line_ = (i < line.size() && line[i] == '#') ? std::string_view() : line;
    }
    return true;
  }
  std::string_view token(const char* what) {
    std::string_view t;
    if (!next(t)) throw InvalidInput(path_ + ": unexpected end of file, expected " + what);
    return t;
  }
  double number(const char* what) {
    const std::string_view t = token(what);
    double v;
    if (!parse_double(t, v) || !std::isfinite(v)) throw error("'" + std::string(t) + "' is not a finite number (" + what + ")");
    return v;
  }
  std::int64_t integer(const char* what, std::int64_t min = 0, std::int64_t max = INT64_MAX) {
    const std::string_view t = token(what);
    std::int64_t v;
    if (!parse_integer(t, v) || v < min || v > max) throw error("'" + std::string(t) + "' is not a valid " + what);
    return v;
  }
  /// The rest of the current line (used for names that may contain spaces).
  std::string_view rest_of_line() {
    std::string_view r = line_;
    line_ = {};
    while (!r.empty() && is_space(r.front())) r.remove_prefix(1);
    while (!r.empty() && is_space(r.back())) r.remove_suffix(1);
    return r;
  }
  InvalidInput error(const std::string& what) const {
    return InvalidInput(path_ + ": line " + std::to_string(cursor_.line_number()) + ": " + what);
  }
  const std::string& path() const { return path_; }

 private:
  LineCursor cursor_;
  std::string_view line_;
  std::string path_;
};

}  // namespace sharpmesh::io
