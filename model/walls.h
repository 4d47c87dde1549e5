// SPDX-License-Identifier: MIT
// Walls: a closed set of primitive surfaces (enum + switch, no virtual calls), each with a material, an
// optional prescribed translation and an optional removal time.
//
// Primitives:
//   plane      one-sided half-space: solid behind `normal` (points into the particle side).
//   rectangle  two-sided finite rectangle: origin = centre, half-axes u and v (their lengths are the
//              half-extents). An open box is five rectangles.
//   revolution two-sided surface of revolution about a vertical axis through `origin` (x, y): the segment
//              (r0, z0)-(r1, z1) in the meridian half-plane, z relative to origin.z. r0 == r1 is a cylinder,
//              z0 == z1 a disk or annulus, otherwise a cone frustum. The funnel is a frustum plus its exit
//              tube (a cylinder).
// Scene shapes (box, cylinder, cone, funnel, disk, plane) expand into these primitives in scene.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "model/vec3.h"

namespace pastemix::model {

enum class WallKind { plane, rectangle, revolution };

struct Wall {
  WallKind kind = WallKind::plane;
  std::string name;    // the scene's wall name (several primitives may share it)
  int material = 0;
  Vec3 origin;         // m, at t = 0
  Vec3 normal;         // plane: unit normal towards the particles
  Vec3 u, v;           // rectangle: half-axes (m)
  double inv_u2 = 0.0, inv_v2 = 0.0;  // rectangle: 1/|u|^2, 1/|v|^2 (1/m2), set by finish(); 0 = compute
  Vec3 unit_normal;    // rectangle: u x v / |u x v|, set by finish() (zero = unknown)
  bool square = false; // rectangle: u . v == 0 exactly (set by finish()): rectangle_distance's plane case holds
  double r0 = 0, z0 = 0, r1 = 0, z1 = 0;  // revolution: meridian segment (m)
  Vec3 velocity;       // m/s, prescribed translation while move_start <= t < move_end
  double move_start = 0.0;  // s
  double move_end = std::numeric_limits<double>::infinity();  // s
  double remove_at = std::numeric_limits<double>::infinity(); // s, the wall stops existing at this time

  bool active(double t) const { return t < remove_at; }
  // Precomputes what wall_distance would otherwise recompute at every call.
  void finish() {
    if (kind == WallKind::rectangle) {
      inv_u2 = 1.0 / norm2(u);
      inv_v2 = 1.0 / norm2(v);
      const Vec3 c = cross(u, v);
      unit_normal = c * (1.0 / norm(c));
      square = dot(u, v) == 0.0;
    }
  }
  // Displacement since t = 0 (m) and current velocity (m/s).
  Vec3 displacement(double t) const;
  Vec3 velocity_at(double t) const;
};

// Closest point of a wall's surface (at displacement `shift`) to a point; returns the distance (m) and
// the unit vector `n` from the point towards the wall. For a plane the distance is signed (negative
// behind it). Used by contacts, insertion and scene checks.
double wall_distance(const Wall& w, const Vec3& shift, const Vec3& p, Vec3* n_to_wall);

// Cheap lower bounds of wall_distance (m) per kind, o = origin + shift: a rectangle's is the distance to
// its plane (unit normal n); a surface of revolution's the height of p above or below the meridian
// segment's z range [z_lo, z_hi] (every point of the surface lies in it, so none is nearer). The wall-list
// rebuild skips the exact distance when the bound already rules a wall out (a funnel high above a mould's
// pile: its exact distance, two square roots and a division, was 3-4 % of a chapter-7 pour, issue 19); it
// picks the kind once per wall, so its loop over the particles is one expression (model/wall_contacts.cpp).
inline double rectangle_distance_bound(const Vec3& o, const Vec3& n, const Vec3& p) { return std::abs(dot(p - o, n)); }
inline double revolution_distance_bound(double z_lo, double z_hi, const Vec3& o, const Vec3& p) {
  const double z = p.z - o.z;
  return std::max({z_lo - z, z - z_hi, 0.0});
}
// The bound of any wall (0 where its kind has none).
inline double wall_distance_bound(const Wall& w, const Vec3& shift, const Vec3& p) {
  const Vec3 o = w.origin + shift;
  if (w.kind == WallKind::rectangle) return rectangle_distance_bound(o, w.unit_normal, p);
  if (w.kind == WallKind::revolution) return revolution_distance_bound(std::min(w.z0, w.z1), std::max(w.z0, w.z1), o, p);
  return 0.0;
}

// The rectangle case of wall_distance, inline for the wall force pass (the box walls of most scenes),
// with the shifted centre `o` = origin + shift computed once per step by the caller.
// Where the point's projection falls inside the rectangle (the common case: a sphere resting on a floor or
// against a side) the nearest point is the foot of the perpendicular, so the distance is the height |h|
// above the plane and the direction -sign(h) n: one dot product instead of the clamped closest point's square
// root and division, whose latency (~35 cycles, one candidate after another) was 6 % of the bench pour's
// samples (issue 19). It needs u and v at right angles (every scene's box faces); the edges, corners, a
// point on the plane (h = 0) and NaN take the general closest-point form.
inline double rectangle_distance(const Wall& w, const Vec3& o, const Vec3& p, Vec3* n_to_wall) {
  const Vec3 rel = p - o;
  const double iu = w.inv_u2 > 0.0 ? w.inv_u2 : 1.0 / norm2(w.u);
  const double iv = w.inv_v2 > 0.0 ? w.inv_v2 : 1.0 / norm2(w.v);
  const double pu = dot(rel, w.u) * iu, pv = dot(rel, w.v) * iv;
  if (w.square && std::abs(pu) < 1.0 && std::abs(pv) < 1.0) {
    const double h = dot(rel, w.unit_normal);  // m, signed height above the plane
    if (h != 0.0) {
      *n_to_wall = h > 0.0 ? -w.unit_normal : w.unit_normal;
      return std::abs(h);
    }
  }
  const double su = std::min(std::max(pu, -1.0), 1.0);
  const double sv = std::min(std::max(pv, -1.0), 1.0);
  const Vec3 c = o + w.u * su + w.v * sv;
  const Vec3 d = c - p;
  const double len = norm(d);
  *n_to_wall = len > 0.0 ? d * (1.0 / len) : Vec3{0, 0, -1};
  return len;
}

// The revolution case of wall_distance, with o = origin + shift: the closest point of the meridian segment
// (r0, z0)-(r1, z1) in the point's (rho, z) half-plane. Inline, and written so that model/wall_batch.h's
// eight-lane form performs the same operations in the same order (the same bits).
inline double revolution_distance(const Wall& w, const Vec3& o, const Vec3& p, Vec3* n_to_wall) {
  const double dx = p.x - o.x, dy = p.y - o.y;
  const double rho = std::sqrt(dx * dx + dy * dy);
  const double z = p.z - o.z;
  const double ar = w.r1 - w.r0, az = w.z1 - w.z0;
  const double l2 = ar * ar + az * az;
  double s = l2 > 0.0 ? ((rho - w.r0) * ar + (z - w.z0) * az) / l2 : 0.0;
  s = std::min(std::max(s, 0.0), 1.0);
  const double cr = w.r0 + s * ar, cz = w.z0 + s * az;
  const double er = cr - rho, ez = cz - z;
  const double len = std::sqrt(er * er + ez * ez);
  // Radial unit vector of the point (any horizontal direction on the axis).
  const double ux = rho > 0.0 ? dx / rho : 1.0, uy = rho > 0.0 ? dy / rho : 0.0;
  *n_to_wall = len > 0.0 ? Vec3{ux * er / len, uy * er / len, ez / len} : Vec3{0, 0, -1};
  return len;
}

}  // namespace pastemix::model
