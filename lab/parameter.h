// SPDX-License-Identifier: MIT
// A parameter reduced from lab data: value, uncertainty, how and from what it was obtained.
//
// Every ingester returns Parameters; `pastemix lab reduce` writes them to parameters.toml under their
// dotted key. Keeping provenance on the value itself is what lets a scene say where each number came from
// and lets us keep calibration data apart from validation data.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace pastemix::lab {

enum class Provenance {
  measured,    // reduced from this project's lab files
  literature,  // taken from a publication as printed
  calibrated,  // found by matching simulations to a calibration experiment
  fitted,      // fitted to data (e.g. a drag curve), with a covariance
  assumed,     // a stated assumption (e.g. rheology of an unmeasured paste)
};

const char* to_string(Provenance p);

struct Parameter {
  std::string key;  // dotted TOML path, e.g. "paste.yield_stress"
  double value = std::numeric_limits<double>::quiet_NaN();
  double sd = std::numeric_limits<double>::quiet_NaN();  // standard deviation; NaN if not known
  int n = 0;                                              // trials/observations behind the value
  std::string unit;                                       // SI unit ("Pa", "-", "m", ...)
  std::string method;                                     // how: "Pashias-Boger cylinder, Lambert W inverse"
  Provenance provenance = Provenance::measured;
  std::string source;           // input file, relative to the dataset folder
  std::vector<double> trials;   // per-trial values, when there are trials
  std::string text;             // for string-valued parameters (a chosen curve's name); value is NaN then
  std::string note;
};

// A warning about the input: a printed value that disagrees with our recomputation, a capped value, ...
struct Warning {
  std::string where;  // "file:line" or "file"
  std::string message;
};

}  // namespace pastemix::lab
