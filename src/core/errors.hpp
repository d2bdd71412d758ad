#pragma once
/// The exception hierarchy of seqmassage: every module throws one of these; only cli/ catches.
///
/// - InputError:  malformed or inconsistent input data (a file, a frame, a mesh); the message names
///                the file, frame, line or element.
/// - IoError:     the operating system refused a read or a write (missing file, unwritable folder).
/// - ConfigError: a configuration value is missing, unknown, of the wrong type or out of range; the
///                message names the JSON path of the key.
/// - SolverError: a numerical failure (factorization, non-convergence, NaN in the positions).
/// - OptionError: an options struct built in code holds a value its table refuses, or one that does
///                not fit the mesh (a pinned vertex past its end). The numerical modules throw it
///                naming the member ("pinned", "vertex_weights[3]"): they do not know where the
///                struct came from. The layer that does (a job, a Python keyword) wraps the call
///                in with_option_path, which turns it into ConfigError naming the config path.
#include <stdexcept>
#include <string>
#include <utility>

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

class OptionError : public Error {
 public:
  /// `key`: the member's path inside the options struct; `reason`: "expected ..., got ...".
  OptionError(std::string key, std::string reason)
      : Error(key + ": " + reason), key_(std::move(key)), reason_(std::move(reason)) {}
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }
  /// The same error one struct further out: key "pinned" under "massage" is "massage.pinned".
  OptionError under(const std::string& parent) const { return {parent + "." + key_, reason_}; }

 private:
  std::string key_;
  std::string reason_;
};

/// Runs `body()`; an OptionError it throws becomes ConfigError("<path>.<key>: <reason>") (just
/// "<key>: <reason>" for an empty path), the words the config's reader uses for the same value.
template <class Body>
decltype(auto) with_option_path(const std::string& path, Body&& body) {
  try {
    return body();
  } catch (const OptionError& e) {
    throw ConfigError((path.empty() ? e.key() : path + "." + e.key()) + ": " + e.reason());
  }
}

}  // namespace sm
