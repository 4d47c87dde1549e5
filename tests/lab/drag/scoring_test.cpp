// SPDX-License-Identifier: MIT
// The drag pipeline on the real Valentik & Whitmore data: the acceptance numbers of issue #3.
#include "lab/drag/scoring.h"

#include <algorithm>
#include <cmath>

#include <doctest/doctest.h>

#include "base/units.h"
#include "tests/run_command.h"

using namespace pastemix::lab::drag;
using pastemix::units::g;

namespace {

// One full run (published, thesis model, every candidate in sample and LOSO) shared by the tests below.
const DragFitResult& result() {
  static const DragFitResult r = run_drag_fit(pastemix::test::source_path("datasets/thesis"), g);
  return r;
}

}  // namespace

TEST_CASE("scoring: summary statistics") {
  std::vector<Prediction> p{{1, 1, 1.0, 1.1}, {2, 1, 1.0, 0.7}, {3, 1, 2.0, 0.0, SettlingOutcome::suspended},
                            {4, 1, 1.0, 1.05}};
  const auto s = score("x", p);
  CHECK(s.n == 4);
  CHECK(s.mean_abs == doctest::Approx((0.1 + 0.3 + 1.0 + 0.05) / 4));
  CHECK(s.median_abs == doctest::Approx(0.2));
  CHECK(s.max_abs == doctest::Approx(1.0));
  CHECK(s.above_20 == 2);
  CHECK(s.suspended == 1);
}

TEST_CASE("scoring: the chosen fitted curve is continuous, monotone and settles all 121 spheres uniquely") {
  const auto& r = result();
  const auto& b = r.best();
  CHECK(pastemix::drag::check_coefficients(b.family, b.in_sample.curve.coefficients).empty());
  // For every yield number in the data's range (11 values from its minimum to its maximum; one suffices for
  // a curve of Re' alone): Cd > 0, continuous, decreasing, and Cd Re' non-decreasing on [1e-3, 1e4].
  double y_min = INFINITY, y_max = 0.0;
  for (const auto& s : r.data.spheres) {
    const double y = pastemix::drag::yield_number(s.sphere, g);
    y_min = std::min(y_min, y), y_max = std::max(y_max, y);
  }
  for (int k = 0; k <= 10; ++k) {
    const double y = y_min + (y_max - y_min) * k / 10.0;
    double prev_cd = INFINITY, prev_h = 0.0;
    for (int i = 0; i <= 7000; ++i) {
      const double re = std::pow(10.0, -3.0 + i / 1000.0), cd = b.in_sample.curve.cd(re, y);
      REQUIRE(cd > 0.0);
      REQUIRE(cd <= prev_cd);
      REQUIRE(cd * re >= prev_h * (1 - 1e-12));
      REQUIRE(std::abs(b.in_sample.curve.cd(re * (1 + 1e-9), y) / cd - 1) < 1e-6);
      prev_cd = cd;
      prev_h = cd * re;
    }
    CHECK(b.in_sample.curve.cd(1e4, y) < b.in_sample.curve.cd(1e-3, y));
  }
  // Full scanning solver: one continuous root for every sphere, in sample and with every LOSO curve.
  for (const auto& p : b.in_sample_predictions) CHECK_MESSAGE(p.outcome == SettlingOutcome::settling, "row ", p.row_id);
  for (const auto& p : b.loso_predictions) CHECK_MESSAGE(p.outcome == SettlingOutcome::settling, "row ", p.row_id);
  CHECK(b.in_sample_score.trapped + b.in_sample_score.suspended == 0);
  CHECK(b.loso_score.trapped + b.loso_score.suspended == 0);
  CHECK(b.in_sample.converged);
}

TEST_CASE("scoring: the published curve traps spheres, the thesis model's 90 pairs score as documented") {
  const auto& r = result();
  CHECK(r.published_score.n == 121);
  CHECK(r.published_score.trapped > 0);
  // Table 4.3 row 20 is suspension 1, d = 50.8 mm, 2673 kg/m3: trapped at sqrt(tau_y/rho_f).
  const auto& p20 = r.published[19];
  REQUIRE(p20.row_id == 20);
  CHECK(p20.outcome == SettlingOutcome::no_consistent_solution);
  CHECK(p20.v_predicted == doctest::Approx(0.154).epsilon(0.01));
  // (d): dataset README: mean 17.9 %, 22 pairs above 20 %, over 90 pairs.
  CHECK(r.thesis_score.n == 90);
  CHECK(r.thesis_score.mean_abs == doctest::Approx(0.179).epsilon(0.005));
  CHECK(r.thesis_score.above_20 == 22);
  CHECK(r.thesis_score.trapped > 0);  // its 0.15 / 0.11 / 0.08 / 0.05 m/s outputs sit at Re' ~ 1
  // The published curve through our force balance reproduces the thesis f-EDEM speeds themselves (median
  // 0.45 %); only the trapped spheres differ, by up to 18 %, where the DEM chatters about the jump.
  CHECK(r.published_vs_thesis_model.n == 90);
  CHECK(r.published_vs_thesis_model.median_abs < 0.01);
  CHECK(r.published_vs_thesis_model.above_20 == 0);
}

TEST_CASE("scoring: held-out prediction of the chosen curve (regression bounds on what this fit achieves)") {
  // Achieved on 2026-11-22 by yield_blend/velocity: LOSO mean 13.8 %, median 5.9 %, 16 above 20 % (power_blend,
  // the best curve of Re' alone: 17.7 %, 7.9 %). These bounds catch regressions; the target is the next
  // test case.
  const auto& b = result().best();
  CHECK(b.family == pastemix::drag::CurveId::yield_blend);
  CHECK(b.loso_score.n == 121);
  CHECK(b.loso_score.mean_abs <= 0.145);
  CHECK(b.loso_score.median_abs <= 0.065);
  CHECK(b.loso_score.above_20 <= 18);
  // Better than the published curve in sample, on the mean and the worst case of the trapped spheres' kind.
  CHECK(b.loso_score.mean_abs < result().published_score.mean_abs);
  CHECK(b.in_sample_score.mean_abs < result().thesis_score.mean_abs);
}

// Issue #3 acceptance: LOSO median <= 7 % and mean <= 15 % over the 121 spheres. Met by yield_blend/velocity
// (2026-11-22: median 5.9 %, mean 13.8 %).
TEST_CASE("scoring: issue #3 target, LOSO median <= 7 % and mean <= 15 %") {
  const auto& b = result().best();
  CHECK(b.loso_score.median_abs <= 0.07);
  CHECK(b.loso_score.mean_abs <= 0.15);
}
