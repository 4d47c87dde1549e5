// SPDX-License-Identifier: MIT
// Helpers of the error tests of every layer: the message a user would read, and a text with one edit.
#pragma once

#include <string>

#include <doctest/doctest.h>

#include "base/error.h"

namespace pastemix::test {

// The message of the InputError that f() throws; `none` if it throws none.
template <class F>
std::string input_error_of(F&& f, const std::string& none = "") {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return none;
}

// The message of the RuntimeFailure (a computation that cannot go on) that f() throws; "" if it throws none.
template <class F>
std::string runtime_failure_of(F&& f) {
  try {
    f();
  } catch (const RuntimeFailure& e) {
    return e.what();
  }
  return "";
}

// `s` with the first `from` replaced by `to`; a `from` that is not there fails the test (the edit would be lost).
inline std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

}  // namespace pastemix::test
