// SPDX-License-Identifier: MIT
#include "model/walls.h"

#include <doctest/doctest.h>

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
