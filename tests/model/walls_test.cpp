// SPDX-License-Identifier: MIT
#include "model/walls.h"

#include <doctest/doctest.h>

#include <cmath>

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
