// SPDX-License-Identifier: MIT
#include "model/insert/fill.h"

#include <doctest/doctest.h>

#include "base/rng.h"

using namespace pastemix;
using namespace pastemix::model;

TEST_CASE("fill: spheres inside the region, no overlaps, same seed same positions, funnel frustum") {
  Rng rng(5);
  std::vector<double> radii;
  for (int k = 0; k < 400; ++k) radii.push_back(rng.uniform(1.25e-3, 2.5e-3));
  FillRegion frustum;
  frustum.shape = FillRegion::frustum;
  frustum.z_min = 0.0;
  frustum.z_max = 0.12;
  frustum.r_bottom = 0.02;
  frustum.r_top = 0.095;
  const auto a = fill_region(frustum, radii, {}, {}, {}, 9);
  REQUIRE(a.complete);
  for (std::size_t i = 0; i < radii.size(); ++i) {
    CHECK(frustum.contains(a.positions[i], radii[i]));
    for (std::size_t j = i + 1; j < radii.size(); ++j)
      CHECK(norm(a.positions[i] - a.positions[j]) >= radii[i] + radii[j]);
  }
  const auto b = fill_region(frustum, radii, {}, {}, {}, 9);
  CHECK(a.positions[17].x == b.positions[17].x);
  // Too many for a small box: reports failure instead of overlapping.
  FillRegion box;
  box.lo = {0, 0, 0};
  box.hi = {0.01, 0.01, 0.01};
  const auto c = fill_region(box, radii, {}, {}, {}, 9, 200);
  CHECK_FALSE(c.complete);
  CHECK(c.placed < radii.size());
}
