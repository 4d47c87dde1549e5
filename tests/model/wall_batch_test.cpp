// SPDX-License-Identifier: MIT
// model/wall_batch.h: the eight-lane distances to surfaces of revolution are wall_distance's, bit for bit, for
// cones, cylinders, disks and a degenerate (point) meridian, on the axis, on the surface, at the segment's
// ends and beyond them, and with NaN coordinates; for any number of lanes 1-8.
#include "model/wall_batch.h"

#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "base/rng.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

Wall revolution(double r0, double z0, double r1, double z1) {
  Wall w;
  w.kind = WallKind::revolution, w.origin = {0.1, 0.08, 0.2}, w.r0 = r0, w.z0 = z0, w.r1 = r1, w.z1 = z1;
  return w;
}

// The same double, NaN included (any NaN matches any NaN: both forms give a NaN from a NaN input).
bool same(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

}  // namespace

TEST_CASE("wall batch: eight lanes give wall_distance's distance and direction to a surface of revolution") {
  const std::vector<Wall> walls{revolution(0.02, 0.0, 0.095, 0.12),   // cone (a funnel's)
                                revolution(0.095, 0.12, 0.02, 0.0),   // the same cone, segment reversed
                                revolution(0.02, -0.02, 0.02, 0.0),   // cylinder (its exit tube)
                                revolution(0.0, 0.0, 0.03, 0.0),      // disk
                                revolution(0.01, 0.05, 0.01, 0.05)};  // a point meridian (l2 = 0): a circle
  const Vec3 shift{0.0, 0.0, -0.003};
  Rng rng(37);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  long checked = 0, on_axis = 0, on_surface = 0;
  for (int round = 0; round < 4000; ++round) {
    const int n = 1 + round % RevolutionLanes::kLanes;
    RevolutionLanes b;
    Vec3 pts[RevolutionLanes::kLanes];
    const Wall* ws[RevolutionLanes::kLanes];
    for (int l = 0; l < n; ++l) {
      const Wall& w = walls[static_cast<std::size_t>((round + l) % walls.size())];
      const Vec3 o = w.origin + shift;
      Vec3 x{o.x + rng.uniform(-0.12, 0.12), o.y + rng.uniform(-0.12, 0.12), o.z + rng.uniform(-0.05, 0.15)};
      const int kind = (round * 8 + l) % 23;
      if (kind == 0) x.x = o.x, x.y = o.y, ++on_axis;  // rho = 0: the radial direction defaults to +x
      if (kind == 1) {  // at the meridian's first end (len 0 to round-off; exactly 0 for the disk, on its axis)
        x = {o.x + w.r0, o.y, o.z + w.z0};
        ++on_surface;
      }
      if (kind == 2) x.y = nan;
      if (kind == 3) x.z = nan;
      pts[l] = x, ws[l] = &w;
      b.set(l, w, o, x);
    }
    revolution_distances(b, n);
    for (int l = 0; l < n; ++l) {
      Vec3 nv;
      const double d = wall_distance(*ws[l], shift, pts[l], &nv);
      CAPTURE(round);
      CAPTURE(l);
      CHECK(same(b.dist[l], d));
      CHECK(same(b.nx[l], nv.x));
      CHECK(same(b.ny[l], nv.y));
      CHECK(same(b.nz[l], nv.z));
      ++checked;
    }
  }
  CHECK(checked == 18000);
  CHECK(on_axis > 500);
  CHECK(on_surface > 500);
}

TEST_CASE("wall batch: revolution_distance is wall_distance's revolution case (the point towards the surface)") {
  const Wall cone = revolution(0.02, 0.0, 0.095, 0.12);
  Vec3 n;
  // Inside the cone at mid-height, 5 mm from its surface along the inward normal: the distance is 5 mm and
  // the direction the outward normal.
  const double ar = 0.075, az = 0.12, l = std::hypot(ar, az);
  const double rho = 0.02 + 0.5 * ar - 0.005 * az / l, z = 0.5 * az + 0.005 * ar / l;
  const Vec3 p{cone.origin.x + rho, cone.origin.y, cone.origin.z + z};
  const double d = revolution_distance(cone, cone.origin, p, &n);
  CHECK(d == doctest::Approx(0.005).epsilon(1e-12));
  CHECK(n.x == doctest::Approx(az / l).epsilon(1e-12));
  CHECK(n.y == 0.0);
  CHECK(n.z == doctest::Approx(-ar / l).epsilon(1e-12));
}
