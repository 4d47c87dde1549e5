// SPDX-License-Identifier: MIT
// The open box of the wall tests (tests/model/contacts_test.cpp, wall_contacts_test.cpp).
#pragma once

#include <vector>

#include "model/walls.h"

namespace pastemix::model::test {

// Floor and four sides (in that order: z = 0, x = 0, x = L, y = 0, y = L) of a cube of side L (m) with a
// corner at the origin, as rectangles of material `material`.
inline std::vector<Wall> open_box(double L, int material) {
  std::vector<Wall> walls;
  auto rect = [&](Vec3 o, Vec3 u, Vec3 v) {
    Wall w;
    w.kind = WallKind::rectangle, w.material = material, w.origin = o, w.u = u, w.v = v;
    w.finish();
    walls.push_back(w);
  };
  const double h = 0.5 * L;
  rect({h, h, 0}, {h, 0, 0}, {0, h, 0});
  rect({0, h, h}, {0, h, 0}, {0, 0, h});
  rect({L, h, h}, {0, h, 0}, {0, 0, h});
  rect({h, 0, h}, {h, 0, 0}, {0, 0, h});
  rect({h, L, h}, {h, 0, 0}, {0, 0, h});
  return walls;
}

}  // namespace pastemix::model::test
