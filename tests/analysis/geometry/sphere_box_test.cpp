// SPDX-License-Identifier: MIT
#include "analysis/geometry/sphere_box.h"

#include <cmath>

#include <doctest/doctest.h>

#include "base/rng.h"
#include "base/units.h"
#include "base/vec3.h"

using pastemix::analysis::Box3;
using pastemix::analysis::disc_rectangle_area;
using pastemix::analysis::sphere_box_volume;

namespace {

// Component d (0, 1, 2) of a vector: the tests loop over the axes.
double& at(pastemix::Vec3& v, int d) { return d == 0 ? v.x : d == 1 ? v.y : v.z; }
double at(const pastemix::Vec3& v, int d) { return d == 0 ? v.x : d == 1 ? v.y : v.z; }
double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }
const double kBig = 1.0;  // a box face far outside the sphere
}  // namespace

TEST_CASE("disc-rectangle area: whole disc, half, quarter, segment") {
  const double r = 0.7;
  CHECK(rel(disc_rectangle_area(r, -1, 1, -1, 1), pastemix::units::pi * r * r) < 1e-14);
  CHECK(rel(disc_rectangle_area(r, 0, 1, -1, 1), 0.5 * pastemix::units::pi * r * r) < 1e-14);
  CHECK(rel(disc_rectangle_area(r, 0, 1, 0, 1), 0.25 * pastemix::units::pi * r * r) < 1e-14);
  const double a = 0.3;  // segment beyond x = a: r^2 acos(a/r) - a sqrt(r^2 - a^2)
  CHECK(rel(disc_rectangle_area(r, a, 1, -1, 1), r * r * std::acos(a / r) - a * std::sqrt(r * r - a * a)) < 1e-13);
  CHECK(disc_rectangle_area(r, 0.8, 1, -1, 1) == 0.0);
}

TEST_CASE("sphere-box volume: analytic cases within 1e-6 relative (achieved ~1e-12)") {
  const double r = 0.0025;  // a 5 mm rock
  const pastemix::Vec3 c{0.01, 0.02, 0.03};
  const double full = 4.0 / 3.0 * pastemix::units::pi * r * r * r;
  // Inside.
  CHECK(rel(sphere_box_volume(c, r, Box3{{0, 0, 0}, {kBig, kBig, kBig}}), full) < 1e-12);
  // Cut by one plane at height h below the top of the sphere: cap volume pi h^2 (3r - h) / 3.
  for (double h : {0.1 * r, 0.5 * r, 1.0 * r, 1.7 * r}) {
    const double cap = pastemix::units::pi * h * h * (3 * r - h) / 3.0;
    Box3 box{{0, 0, c.z + r - h}, {kBig, kBig, kBig}};
    CHECK(rel(sphere_box_volume(c, r, box), cap) < 1e-10);
    Box3 side{{c.x + r - h, 0, 0}, {kBig, kBig, kBig}};  // the same cut through an x face
    CHECK(rel(sphere_box_volume(c, r, side), cap) < 1e-10);
  }
  // Two and three planes through the centre: quarter and eighth.
  CHECK(rel(sphere_box_volume(c, r, Box3{{c.x, c.y, 0}, {kBig, kBig, kBig}}), full / 4) < 1e-10);
  CHECK(rel(sphere_box_volume(c, r, Box3{{c.x, c.y, c.z}, {kBig, kBig, kBig}}), full / 8) < 1e-10);
  CHECK(rel(sphere_box_volume(c, r, Box3{{0, 0, 0}, {c.x, c.y, c.z}}), full / 8) < 1e-10);
  // Two parallel planes (a slab through the centre of half-width w): pi (2 w r^2 - 2 w^3 / 3).
  const double w = 0.4 * r;
  CHECK(rel(sphere_box_volume(c, r, Box3{{0, 0, c.z - w}, {kBig, kBig, c.z + w}}),
            pastemix::units::pi * (2 * w * r * r - 2 * w * w * w / 3.0)) < 1e-10);
  // Disjoint.
  CHECK(sphere_box_volume(c, r, Box3{{0.1, 0.1, 0.1}, {0.2, 0.2, 0.2}}) == 0.0);
}

TEST_CASE("sphere-box volume: the 8 octant boxes around any point sum to the sphere") {
  pastemix::Rng rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const double r = rng.uniform(0.5, 2.0);
    const pastemix::Vec3 c{0, 0, 0};
    const std::array<double, 3> p{rng.uniform(-1.5, 1.5) * r, rng.uniform(-1.5, 1.5) * r, rng.uniform(-1.5, 1.5) * r};
    double sum = 0.0;
    for (int k = 0; k < 8; ++k) {
      Box3 b;
      for (int d = 0; d < 3; ++d) {
        const bool upper = (k >> d) & 1;
        at(b.lo, d) = upper ? p[d] : -10.0;
        at(b.hi, d) = upper ? 10.0 : p[d];
      }
      sum += sphere_box_volume(c, r, b);
    }
    CHECK(rel(sum, 4.0 / 3.0 * pastemix::units::pi * r * r * r) < 1e-11);
  }
}

TEST_CASE("sphere-box volume: random boxes agree with Monte Carlo within 4 standard errors") {
  pastemix::Rng rng(17);
  const int samples = 200000;
  for (int trial = 0; trial < 8; ++trial) {
    const double r = 1.0;
    const pastemix::Vec3 c{rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)};
    Box3 box;
    for (int d = 0; d < 3; ++d) {
      const double a = rng.uniform(-1.2, 1.2), b = rng.uniform(-1.2, 1.2);
      at(box.lo, d) = std::min(a, b);
      at(box.hi, d) = std::max(a, b) + 0.05;
    }
    const double exact = sphere_box_volume(c, r, box);
    // Uniform points in the sphere's bounding cube.
    int hits = 0;
    for (int k = 0; k < samples; ++k) {
      std::array<double, 3> q;
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        q[d] = rng.uniform(-r, r);
        d2 += q[d] * q[d];
      }
      if (d2 > r * r) continue;
      bool in = true;
      for (int d = 0; d < 3; ++d) in = in && (at(c, d) + q[d] >= at(box.lo, d) && at(c, d) + q[d] <= at(box.hi, d));
      hits += in;
    }
    const double cube = 8.0 * r * r * r, p = static_cast<double>(hits) / samples;
    const double mc = cube * p, se = cube * std::sqrt(p * (1 - p) / samples);
    CHECK(std::abs(exact - mc) <= 4.0 * se + 1e-12);
  }
}
