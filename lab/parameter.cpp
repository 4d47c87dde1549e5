// SPDX-License-Identifier: MIT
#include "lab/parameter.h"

namespace pastemix::lab {

const char* to_string(Provenance p) {
  switch (p) {
    case Provenance::measured: return "measured";
    case Provenance::literature: return "literature";
    case Provenance::calibrated: return "calibrated";
    case Provenance::fitted: return "fitted";
    case Provenance::assumed: return "assumed";
  }
  return "unknown";
}

}  // namespace pastemix::lab
