// SPDX-License-Identifier: MIT
// The setups the flow tests share: a box of cubic cells, and a paste column at rest in one.
#pragma once

#include <array>
#include <vector>

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

// A smooth solid fraction on the cells of g: a porous ball of peak solid fraction 0.5 at its centre c (m),
// radius R (m); returns the fluid fraction 1 - solid per cell.
inline std::vector<double> porous_ball(const flow::Grid& g, std::array<double, 3> c, double R) {
  std::vector<double> eps(g.cell_count());
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const double x = (i + 0.5) * g.h[0] - c[0], y = (j + 0.5) * g.h[1] - c[1], z = (k + 0.5) * g.h[2] - c[2];
        const double r2 = (x * x + y * y + z * z) / (R * R);
        eps[g.cell(i, j, k)] = 1.0 - (r2 < 1.0 ? 0.5 * (1.0 - r2) * (1.0 - r2) : 0.0);
      }
  return eps;
}

}  // namespace pastemix::test
