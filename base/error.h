// SPDX-License-Identifier: MIT
// Errors that point at the input that caused them.
//
// Every malformed input must name the file, the line and the field, and say what was expected, so a user
// can fix it without reading our code. InputError carries those pieces; what() is already formatted as
//   datasets/thesis/slump_tests.csv:3: column 'slump_mm': expected a positive number, got '-4'
#pragma once

#include <stdexcept>
#include <string>

namespace pastemix {

class InputError : public std::runtime_error {
 public:
  // line <= 0 means "the whole file" (e.g. it is empty or missing); field may be empty.
  InputError(std::string file, int line, std::string field, std::string message);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_;
  std::string field_;
  std::string message_;
};

// A simulation or computation that cannot go on (NaN, blow-up, lost particle, no solution).
class RuntimeFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace pastemix
