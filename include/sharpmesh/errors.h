// The library's exceptions (DESIGN.md, "Conventions"). The CLI maps them to
// exit codes: InvalidArgument -> 2, everything else -> 1.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace sharpmesh {

/// A number for a message: 6 significant digits (1e-09, not 0.000000).
inline std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}
template <class Integer, std::enable_if_t<std::is_integral_v<Integer>, int> = 0>
std::string format_number(Integer value) {
  return std::to_string(value);
}

/// Base class of every error the library throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file or data set that cannot be used: unreadable, malformed, NaN, empty, degenerate.
class InvalidInput : public Error {
 public:
  using Error::Error;
};

/// A parameter out of its valid range.
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

/// A computation that failed on valid input (solver did not converge, empty result).
class NumericalFailure : public Error {
 public:
  using Error::Error;
};

/// The progress callback asked to stop.
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled") {}
};

}  // namespace sharpmesh
