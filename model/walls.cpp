// SPDX-License-Identifier: MIT
#include "model/walls.h"

#include <algorithm>
#include <cmath>

namespace pastemix::model {

Vec3 Wall::displacement(double t) const {
  const double t0 = std::min(std::max(t, move_start), move_end);
  return velocity * (t0 - move_start);
}

Vec3 Wall::velocity_at(double t) const {
  return (t >= move_start && t < move_end) ? velocity : Vec3{};
}

double wall_distance(const Wall& w, const Vec3& shift, const Vec3& p, Vec3* n_to_wall) {
  const Vec3 o = w.origin + shift;
  switch (w.kind) {
    case WallKind::plane: {
      const double d = dot(p - o, w.normal);
      *n_to_wall = -w.normal;
      return d;
    }
    case WallKind::rectangle:
      return rectangle_distance(w, o, p, n_to_wall);
    case WallKind::revolution:
      return revolution_distance(w, o, p, n_to_wall);
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace pastemix::model
