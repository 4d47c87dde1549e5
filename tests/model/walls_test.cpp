// SPDX-License-Identifier: MIT
#include "model/walls.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

using namespace pastemix::model;

TEST_CASE("walls: distances and normals of the primitives") {
  Vec3 n;
  Wall plane;
  plane.kind = WallKind::plane;
  plane.normal = {0, 0, 1};
  CHECK(wall_distance(plane, {}, {0.3, 0.1, 0.02}, &n) == doctest::Approx(0.02));
  CHECK(n.z == -1.0);

  Wall rect;
  rect.kind = WallKind::rectangle;
  rect.u = {0.1, 0, 0};
  rect.v = {0, 0.1, 0};
  CHECK(wall_distance(rect, {}, {0.05, 0, 0.01}, &n) == doctest::Approx(0.01));
  CHECK(wall_distance(rect, {}, {0.13, 0, 0.04}, &n) == doctest::Approx(0.05));  // past the edge: to the edge

  // The thesis funnel: 19 cm top, 4 cm exit, 12 cm high; a point on the axis at mid height is at the
  // mid-height radius times cos(half-angle) from the wall.
  Wall cone;
  cone.kind = WallKind::revolution;
  cone.r0 = 0.02;
  cone.z0 = 0.0;
  cone.r1 = 0.095;
  cone.z1 = 0.12;
  const double half_angle = std::atan((0.095 - 0.02) / 0.12);
  const double r_mid = 0.5 * (0.02 + 0.095);
  CHECK(wall_distance(cone, {}, {0, 0, 0.06}, &n) == doctest::Approx(r_mid * std::cos(half_angle)));
  // A point inside near the wall: the normal points outwards and down the slope.
  wall_distance(cone, {}, {r_mid - 0.01, 0, 0.06}, &n);
  CHECK(n.x > 0);
  CHECK(n.z < 0);
  // Moving: lifted 1 cm after 1 s at 0.01 m/s.
  cone.velocity = {0, 0, 0.01};
  CHECK(cone.displacement(1.0).z == doctest::Approx(0.01));
  CHECK(wall_distance(cone, cone.displacement(1.0), {0, 0, 0.07}, &n) ==
        doctest::Approx(r_mid * std::cos(half_angle)));
  // A removed plate is inactive after its time.
  Wall plate;
  plate.remove_at = 0.5;
  CHECK(plate.active(0.4));
  CHECK_FALSE(plate.active(0.5));
}

// The wall-list rebuild skips a wall whose bound already exceeds r + skin, so the bound must never exceed
// the exact distance (or a touching wall would be missed); and it must rule out the far ones it is for.
TEST_CASE("walls: the distance bound never exceeds the exact distance, and rules far walls out") {
  Wall cone;  // the thesis funnel's cone, shifted and moved as a scene may place it
  cone.kind = WallKind::revolution;
  cone.origin = {0.1, 0.025, 0.52};
  cone.r0 = 0.02, cone.z0 = 0.0, cone.r1 = 0.095, cone.z1 = 0.12;
  Wall tube = cone;
  tube.r0 = 0.02, tube.z0 = -0.02, tube.r1 = 0.02, tube.z1 = 0.0;
  Wall disk = cone;  // a plate: r from 0 to 3 cm at one height (z0 == z1), listed downwards
  disk.r0 = 0.03, disk.z0 = -0.02, disk.r1 = 0.0, disk.z1 = -0.02;
  Wall rect;
  rect.kind = WallKind::rectangle;
  rect.origin = {0.1, 0.08, 0.0};
  rect.u = {0.1, 0, 0};
  rect.v = {0, 0.0825, 0};
  rect.finish();
  const Vec3 shift{0.001, -0.002, 0.003};
  std::uint64_t state = 12345;
  auto uniform = [&](double lo, double hi) {  // a small LCG: the test's own, seeded
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  int ruled_out = 0;
  for (const Wall* w : {&cone, &tube, &disk, &rect})
    for (int k = 0; k < 4000; ++k) {
      const Vec3 p{uniform(-0.05, 0.25), uniform(-0.1, 0.2), uniform(-0.05, 0.75)};
      Vec3 n;
      const double exact = wall_distance(*w, shift, p, &n);
      const double bound = wall_distance_bound(*w, shift, p);
      REQUIRE(bound >= 0.0);
      REQUIRE(bound <= exact * (1.0 + 1e-12));
      ruled_out += bound > 0.01;
    }
  // Most random points of the tall domain are more than 1 cm above or below the funnel's 14 cm.
  CHECK(ruled_out > 3 * 4000 / 2);
}

// rectangle_distance's plane case (the projection inside the rectangle: |h| and -sign(h) n, no square root)
// against the general closest-point form, written out here: the same distance and direction to round-off
// inside, the general form itself at the edges and corners, on the plane, for NaN and for axes that are not at
// right angles.
TEST_CASE("walls: a rectangle's plane case agrees with the closest point") {
  auto closest = [](const Wall& w, const Vec3& o, const Vec3& p, Vec3& n) {
    const Vec3 rel = p - o;
    const double su = std::clamp(dot(rel, w.u) * (1.0 / norm2(w.u)), -1.0, 1.0);  // finish()'s inv_u2
    const double sv = std::clamp(dot(rel, w.v) * (1.0 / norm2(w.v)), -1.0, 1.0);
    const Vec3 d = o + w.u * su + w.v * sv - p;
    const double len = norm(d);
    n = len > 0.0 ? d * (1.0 / len) : Vec3{0, 0, -1};
    return len;
  };
  Wall side;  // a box's x = 0 side as scene/walls.cpp lays it out: u along y, v along z
  side.kind = WallKind::rectangle;
  side.origin = {0.0, 0.1, 0.125};
  side.u = {0, 0.1, 0};
  side.v = {0, 0, 0.125};
  side.finish();
  REQUIRE(side.square);
  Wall tilted = side;  // a parallelogram: the general form only
  tilted.v = {0, 0.03, 0.125};
  tilted.finish();
  CHECK_FALSE(tilted.square);
  std::uint64_t state = 777;
  auto uniform = [&](double lo, double hi) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  int inside = 0, outside = 0;
  for (const Wall* w : {&side, &tilted})
    for (int k = 0; k < 20000; ++k) {
      const Vec3 p{uniform(-0.02, 0.02), uniform(-0.05, 0.25), uniform(-0.05, 0.3)};
      Vec3 n, n_ref;
      const double d = rectangle_distance(*w, w->origin, p, &n);
      const double d_ref = closest(*w, w->origin, p, n_ref);
      const Vec3 rel = p - w->origin;
      const bool in = std::abs(dot(rel, w->u) * w->inv_u2) < 1.0 && std::abs(dot(rel, w->v) * w->inv_v2) < 1.0;
      if (w->square && in) {
        ++inside;
        // The general form's closest point carries a round-off of ~1e-17 m (coordinates of 0.1-0.3 m): its
        // distance errs by that, its direction by that over the distance.
        REQUIRE(std::abs(d - d_ref) < 1e-16);
        REQUIRE(d == std::abs(p.x));  // the height above the x = 0 plane, exactly
        REQUIRE(norm(n - n_ref) * d < 1e-16);
        REQUIRE(n.x == (p.x > 0.0 ? -1.0 : 1.0));
      } else {
        outside += w->square;
        REQUIRE(d == d_ref);  // the general form, to the bit
        REQUIRE(n.x == n_ref.x);
        REQUIRE(n.y == n_ref.y);
        REQUIRE(n.z == n_ref.z);
      }
    }
  CHECK(inside > 5000);
  CHECK(outside > 5000);
  Vec3 n;
  // On the plane: the general form (a zero distance, the fallback direction).
  CHECK(rectangle_distance(side, side.origin, {0.0, 0.12, 0.1}, &n) == 0.0);
  CHECK(n.z == -1.0);
  // A corner region: to the corner.
  CHECK(rectangle_distance(side, side.origin, {0.03, 0.24, 0.29}, &n) ==
        doctest::Approx(std::sqrt(0.03 * 0.03 + 0.04 * 0.04 + 0.04 * 0.04)));
  CHECK(std::isnan(rectangle_distance(side, side.origin, {NAN, 0.1, 0.1}, &n)));
}
