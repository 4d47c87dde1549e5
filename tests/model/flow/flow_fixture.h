// SPDX-License-Identifier: MIT
// The setups the flow tests share: a box of cubic cells, and a paste column at rest in one.
#pragma once

#include <array>

#include "model/flow/solver.h"

namespace pastemix::test {

// n cubic cells of h (m) from the origin, no-slip walls, open on top (z_hi) when open_top.
inline flow::Grid cube_box(const std::array<int, 3>& n, double h, bool open_top) {
  flow::Grid g;
  g.n = n;
  g.h = {h, h, h};
  if (open_top) g.bc[5].type = flow::BoundaryType::open;
  return g;
}

// An open-top cube_box with paste of density rho_paste (kg/m3, the default law) over the whole floor up to
// z = top (m), air above.
inline flow::FlowSolver paste_column(const std::array<int, 3>& n, double h, double rho_paste, double top,
                                     const flow::FlowSettings& settings = {}) {
  flow::Phases ph;
  ph.rho_paste = rho_paste;
  flow::FlowSolver s(cube_box(n, h, true), ph, settings);
  s.add_paste_box({0.0, 0.0, 0.0}, {n[0] * h, n[1] * h, top});
  return s;
}

}  // namespace pastemix::test
