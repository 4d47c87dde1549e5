// SPDX-License-Identifier: MIT
// What every output of `lab reduce` records about how it was made.
#pragma once

#include <string>

namespace pastemix::lab {

struct RunInfo {
  std::string software;  // "pastemix 0.1.0"
  std::string command;   // the command line
  std::string created;   // UTC time, ISO 8601
};

// Software name and version of this build.
std::string software_version();
// Current UTC time as "YYYY-MM-DDThh:mm:ssZ".
std::string utc_now();

}  // namespace pastemix::lab
