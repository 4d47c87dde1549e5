// SPDX-License-Identifier: MIT
#include "base/error.h"

#include <fmt/format.h>

namespace pastemix {

static std::string format_input_error(const std::string& file, int line, const std::string& field,
                                      const std::string& message) {
  std::string where = line > 0 ? fmt::format("{}:{}", file, line) : file;
  if (field.empty()) return fmt::format("{}: {}", where, message);
  return fmt::format("{}: {}: {}", where, field, message);
}

InputError::InputError(std::string file, int line, std::string field, std::string message)
    : std::runtime_error(format_input_error(file, line, field, message)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      message_(std::move(message)) {}

}  // namespace pastemix
