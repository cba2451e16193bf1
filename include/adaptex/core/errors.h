#pragma once
/// \file errors.h
/// The exception hierarchy (after pmp-library). Every message is one line, names the file (when there
/// is one) and says what is wrong. The CLI prints it as is; its exit code says what happened
/// (README, "Exit codes"): 2 for InvalidInputError and everything derived from it (bad input),
/// 3 for OutputError (an output could not be written), 4 out of memory, 1 anything else.
#include <stdexcept>
#include <string>

namespace adaptex {

/// Base of all adaptex errors.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The input (file content, options, arguments) is invalid: bad data, NaN, out-of-range values.
class InvalidInputError : public Error {
 public:
  using Error::Error;
};

/// The mesh has a topology the operation cannot handle (non-manifold, no faces, ...).
class TopologyError : public InvalidInputError {
 public:
  using InvalidInputError::InvalidInputError;
};

/// An input file could not be read (missing, not a regular file, larger than the caps of
/// core/limits.h, unreadable) or is corrupt / truncated. Bad input: exit code 2.
class IoError : public InvalidInputError {
 public:
  using InvalidInputError::InvalidInputError;
};

/// An output could not be written (permission denied, disk full, cannot create a directory or
/// rename into place, an encoder failed). Not bad input: exit code 3.
class OutputError : public Error {
 public:
  using Error::Error;
};

/// A numerical solver failed (factorization, non-convergence). Not the user's fault: exit code 1.
class SolverError : public Error {
 public:
  using Error::Error;
};

/// The operation was cancelled through a progress callback.
class CancelledError : public Error {
 public:
  CancelledError() : Error("cancelled") {}
};

}  // namespace adaptex
