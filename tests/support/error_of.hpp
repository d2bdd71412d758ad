#pragma once
/// The message of the exception a call throws, for tests that check error messages word for word.
#include <string>

#include "core/errors.hpp"

namespace sm::test {

/// The message of the exception of type E (by default any of the library's errors) that `f`
/// throws, or "" if it throws none.
template <class E = Error, class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

}  // namespace sm::test
