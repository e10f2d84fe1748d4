// The library's exceptions (DESIGN.md, "Conventions"). The CLI maps them to
// exit codes: InvalidArgument -> 2, everything else -> 1.
#pragma once

#include <stdexcept>
#include <string>

namespace sharpmesh {

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
