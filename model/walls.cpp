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

namespace {

double clamp_unit(double s, double lo, double hi) { return std::min(std::max(s, lo), hi); }

}  // namespace

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
    case WallKind::revolution: {
      const double dx = p.x - o.x, dy = p.y - o.y;
      const double rho = std::sqrt(dx * dx + dy * dy);
      const double z = p.z - o.z;
      // Closest point on the meridian segment in the (rho, z) half-plane.
      const double ar = w.r1 - w.r0, az = w.z1 - w.z0;
      const double l2 = ar * ar + az * az;
      double s = l2 > 0.0 ? ((rho - w.r0) * ar + (z - w.z0) * az) / l2 : 0.0;
      s = clamp_unit(s, 0.0, 1.0);
      const double cr = w.r0 + s * ar, cz = w.z0 + s * az;
      const double er = cr - rho, ez = cz - z;
      const double len = std::sqrt(er * er + ez * ez);
      // Radial unit vector of the point (any horizontal direction on the axis).
      const double ux = rho > 0.0 ? dx / rho : 1.0, uy = rho > 0.0 ? dy / rho : 0.0;
      if (len > 0.0) {
        *n_to_wall = Vec3{ux * er / len, uy * er / len, ez / len};
      } else {
        *n_to_wall = Vec3{0, 0, -1};
      }
      return len;
    }
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace pastemix::model
