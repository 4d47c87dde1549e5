// SPDX-License-Identifier: MIT
// The sweep's reference and choice on synthetic ladders with known limits.
#include "app/study/ladder.h"

#include <doctest/doctest.h>

#include <cmath>

using namespace pastemix::app::study;

namespace {

// q(h) = L + C h^p on h = h0, h0/2, ..., coarse -> fine; wall cost doubling per halving.
std::vector<LadderPoint> ladder(double L, double C, double p, int n, double h0 = 1.0) {
  std::vector<LadderPoint> v;
  for (int k = 0; k < n; ++k) {
    const double h = h0 / std::pow(2.0, k);
    v.push_back({h, L + C * std::pow(h, p), 0.0, 1, std::pow(2.0, k)});
  }
  return v;
}

}  // namespace

TEST_CASE("Richardson on a p-th order sequence recovers the limit and the order") {
  for (double p : {1.0, 1.5, 2.0, 4.0}) {
    const auto pts = ladder(3.0, -0.7, p, 5);
    const Reference r = reference_of(pts, 2.0);
    CHECK(r.order == doctest::Approx(p).epsilon(1e-9));
    CHECK(r.qoi == doctest::Approx(3.0).epsilon(1e-12));
    CHECK(r.method.rfind("Richardson", 0) == 0);
  }
}

TEST_CASE("no extrapolation without a geometric ladder, with divergence, or inside the seed spread") {
  auto pts = ladder(3.0, 0.5, 2.0, 4);
  CHECK(reference_of(pts, 0.0).qoi == pts.back().qoi);
  CHECK(reference_of(pts, 0.0).method.find("finest run") == 0);
  // Oscillating differences: not monotone.
  std::vector<LadderPoint> osc = {{4, 3.1, 0, 1, 1}, {2, 2.95, 0, 1, 2}, {1, 3.01, 0, 1, 4}};
  CHECK(reference_of(osc, 2.0).method.find("not monotonically") != std::string::npos);
  // Ensembles whose differences are smaller than twice the standard error: the "order" would be noise.
  for (auto& q : pts) {
    q.qoi_sd = 1.0;
    q.seeds = 4;
  }
  const Reference noisy = reference_of(pts, 2.0);
  CHECK(noisy.method.find("seed spread") != std::string::npos);
  CHECK(noisy.qoi == pts.back().qoi);
}

TEST_CASE("choice: the cheapest point within tolerance - none when nothing is") {
  const auto pts = ladder(3.0, 0.3, 2.0, 5);  // errors 0.1, 0.025, 0.00625, ... (relative to 3)
  const Reference r = reference_of(pts, 2.0);
  const Choice c = choose(pts, r, 0.01);
  REQUIRE(c.index == 2);  // 0.3 * 0.25^2 / 3 = 6.25e-3 <= 0.01; the point before has 2.5e-2
  CHECK(c.rel_error[2] == doctest::Approx(0.3 / 16 / 3));
  CHECK(choose(pts, r, 1e-9).index == -1);
}
