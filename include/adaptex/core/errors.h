#pragma once
/// \file errors.h
/// The exception hierarchy (after pmp-library). Every message is one line, names the file (when there
/// is one) and says what is wrong; the CLI prints it as is and exits with code 2 for the input errors.
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

/// A file could not be opened, read or written, or is corrupt / truncated.
class IoError : public InvalidInputError {
 public:
  using InvalidInputError::InvalidInputError;
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
