// SPDX-License-Identifier: MIT
#include "model/flow/finite_check.h"

#include <cmath>

#include <fmt/format.h>

#include "base/error.h"

namespace pastemix::flow {

namespace {

bool bad(double v, bool positive) { return !std::isfinite(v) || (positive && !(v > 0.0)); }

[[noreturn]] void fail(const char* what, double v, const std::string& where, const CheckPoint& at) {
  throw RuntimeFailure(fmt::format("flow: {} {} {} at {}, {}, in the step from t = {:.9g} s (step {})", what,
                                   std::isfinite(v) ? "not positive:" : "non-finite:", v, where, at.stage, at.time,
                                   at.step));
}

}  // namespace

void require_finite_cells(const Grid& g, const std::vector<double>& v, const char* what, const CheckPoint& at,
                          bool positive) {
  for (long c = 0; c < static_cast<long>(v.size()); ++c) {
    if (!bad(v[c], positive)) continue;
    const auto [i, j, k] = g.cell_at(c);
    fail(what, v[c], fmt::format("cell ({}, {}, {})", i, j, k), at);
  }
}

void require_finite_faces(const Grid& g, const Faces& u, const char* what, const CheckPoint& at, bool positive) {
  for (int comp = 0; comp < 3; ++comp) {
    const auto fd = g.face_dims(comp);
    for (long f = 0; f < static_cast<long>(u[comp].size()); ++f) {
      if (!bad(u[comp][f], positive)) continue;
      const int i = static_cast<int>(f % fd[0]), j = static_cast<int>((f / fd[0]) % fd[1]);
      const int k = static_cast<int>(f / (static_cast<long>(fd[0]) * fd[1]));
      fail(what, u[comp][f], fmt::format("{} face ({}, {}, {})", "xyz"[comp], i, j, k), at);
    }
  }
}

}  // namespace pastemix::flow
