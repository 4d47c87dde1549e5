// SPDX-License-Identifier: MIT
#include "analysis/pile/repose_angle.h"

#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include "base/error.h"
#include "base/rng.h"

using namespace pastemix::analysis;

namespace {
constexpr double kPi = 3.14159265358979323846;
// A synthetic cone pile: sphere tops sampled uniformly inside a cone of base radius R and angle theta
// (overlaps allowed: only the surface matters to the measurement).
void cone_pile(double theta_deg, double R, double d, std::vector<std::array<double, 3>>& pos, std::vector<double>& rad,
               std::uint64_t seed) {
  pastemix::Rng rng(seed);
  const double t = std::tan(theta_deg * kPi / 180.0);
  const double h0 = R * t;
  while (pos.size() < 40000) {
    const double x = rng.uniform(-R, R), y = rng.uniform(-R, R), top = rng.uniform(d, h0);
    if (top > h0 - std::hypot(x, y) * t) continue;
    pos.push_back({x + 0.3, y + 0.2, top - d / 2});
    rad.push_back(d / 2);
  }
}
}  // namespace

TEST_CASE("repose angle: synthetic cones of 25, 35 and 40 degrees within 1 degree") {
  for (double theta : {25.0, 35.0, 40.0}) {
    std::vector<std::array<double, 3>> pos;
    std::vector<double> rad;
    cone_pile(theta, 0.06, 0.003, pos, rad, 9);
    auto a = measure_repose_angle(pos, rad);
    CAPTURE(theta);
    MESSAGE("cone " << theta << " deg: measured " << a.angle_deg << " +- " << a.sd_deg << " deg");
    CHECK(std::abs(a.angle_deg - theta) < 1.0);
    CHECK(a.diameter == doctest::Approx(0.12).epsilon(0.1));
    CHECK(a.sectors_used >= 10);
  }
}

TEST_CASE("repose angle: particles that flowed away are a failure, not zero degrees") {
  std::vector<std::array<double, 3>> pos;
  std::vector<double> rad;
  pastemix::Rng rng(1);
  for (int k = 0; k < 500; ++k) {  // a single flat layer spread over the floor
    pos.push_back({rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), 0.0015});
    rad.push_back(0.0015);
  }
  CHECK_THROWS_AS(measure_repose_angle(pos, rad), pastemix::RuntimeFailure);
}
