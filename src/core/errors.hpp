#pragma once
/// The exception hierarchy of seqmassage: every module throws one of these; only cli/ catches.
///
/// - InputError:  malformed or inconsistent input data (a file, a frame, a mesh); the message names
///                the file, frame, line or element.
/// - IoError:     the operating system refused a read or a write (missing file, unwritable folder).
/// - ConfigError: a configuration value is missing, unknown, of the wrong type or out of range; the
///                message names the JSON path of the key.
/// - SolverError: a numerical failure (factorization, non-convergence, NaN in the positions).
#include <stdexcept>
#include <string>

namespace sm {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InputError : public Error {
 public:
  using Error::Error;
};

class IoError : public Error {
 public:
  using Error::Error;
};

class ConfigError : public Error {
 public:
  using Error::Error;
};

class SolverError : public Error {
 public:
  using Error::Error;
};

}  // namespace sm
