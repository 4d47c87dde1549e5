// SPDX-License-Identifier: MIT
// Tests base/drag_curves.h (kept with the drag tests: the curves are the drag pipeline's shared formulas).
#include "base/drag_curves.h"

#include <cmath>
#include <vector>

#include <ceres/jet.h>
#include <doctest/doctest.h>

#include "base/rng.h"
#include "base/units.h"

using namespace pastemix::drag;

namespace {

// Checks, on a dense log grid over [1e-3, 1e4]: Cd > 0 and decreasing (never rising between grid points; the
// blend's tail can be flat to double precision, so overall strictly lower at 1e4 than at 1e-3), Cd Re' non-decreasing
// (unique terminal velocity), and continuity (a 1e-9 relative step in Re' moves Cd by < 1e-6 relative).
void check_well_posed(const DragCurve& curve, double y, bool strictly_lower_at_end = true) {
  const int n = 4000;
  double prev_cd = INFINITY, prev_h = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double re = std::pow(10.0, -3.0 + 7.0 * i / n);
    const double cd = curve.cd(re, y), h = cd * re;
    REQUIRE(std::isfinite(cd));
    REQUIRE(cd > 0.0);
    REQUIRE(cd <= prev_cd);
    REQUIRE(h >= prev_h * (1.0 - 1e-12));
    REQUIRE(std::abs(curve.cd(re * (1.0 + 1e-9), y) / cd - 1.0) < 1e-6);
    prev_cd = cd;
    prev_h = h;
  }
  if (strictly_lower_at_end) REQUIRE(curve.cd(1e4, y) < curve.cd(1e-3, y));
}

}  // namespace

TEST_CASE("drag curves: registry by name") {
  REQUIRE(find_curve("stokes") == CurveId::stokes);
  REQUIRE(find_curve("published_4_19") == CurveId::published_4_19);
  REQUIRE(find_curve("power_blend") == CurveId::power_blend);
  CHECK_FALSE(find_curve("nonsense").has_value());
  CHECK(curve_info(CurveId::power_sum).n_coefficients == 4);
  CHECK(curve_info(CurveId::power_blend).coefficient_names[4] == "n");
  CHECK(check_coefficients(CurveId::power_blend, {1, 2, 0.5, 0.4, 2}).empty());
  CHECK_FALSE(check_coefficients(CurveId::power_blend, {1, 2, 1.5, 0.4, 2}).empty());  // b >= 1
  CHECK_FALSE(check_coefficients(CurveId::power_sum, {1, 2, 0.5}).empty());            // too few
}

TEST_CASE("drag curves: published 4.19 values and its jumps at Re' = 1 and 150") {
  const DragCurve pub{CurveId::published_4_19, {}};
  CHECK(pub.cd(0.5, 0.0) == doctest::Approx(48.0));
  CHECK(pub.cd(10.0, 0.0) == doctest::Approx(2.912 + 0.195));
  CHECK(pub.cd(1000.0, 0.0) == doctest::Approx(0.4));
  CHECK(pub.cd(1.0 - 1e-12, 0.0) == doctest::Approx(24.0));
  CHECK(pub.cd(1.0, 0.0) == doctest::Approx(29.315));  // a 22 % jump: no consistent solution in between
  CHECK(pub.cd(150.0, 0.0) * 150.0 == doctest::Approx(58.37));
  CHECK(pub.cd(150.0 + 1e-9, 0.0) * 150.0 == doctest::Approx(60.0));
  CHECK_FALSE(pub.info().continuous);
}

TEST_CASE("drag curves: Stokes and the fitted families are well posed on [1e-3, 1e4]") {
  check_well_posed(DragCurve{CurveId::stokes, {}}, 0.0);
  for (CurveId id : {CurveId::power_sum, CurveId::power_blend}) {
    const auto& info = curve_info(id);
    check_well_posed(DragCurve{id, std::vector<double>(info.start.begin(), info.start.begin() + info.n_coefficients)}, 0.0);
    // Any admissible coefficient vector (seeded draws, log-uniform where the box spans decades).
    pastemix::Rng rng(3);
    for (int draw = 0; draw < 100; ++draw) {
      std::vector<double> c(info.n_coefficients);
      for (int i = 0; i < info.n_coefficients; ++i) {
        const double lo = std::max(info.lower[i], 1e-3), hi = info.upper[i];
        c[i] = std::exp(rng.uniform(std::log(lo), std::log(hi)));
      }
      REQUIRE(check_coefficients(id, c).empty());
      check_well_posed(DragCurve{id, c}, 0.0);
    }
  }
}

TEST_CASE("drag curves: yield_blend is well posed on [1e-3, 1e4] for every yield number a sphere can settle at") {
  const auto& info = curve_info(CurveId::yield_blend);
  CHECK(info.uses_yield_number);
  CHECK_FALSE(curve_info(CurveId::power_blend).uses_yield_number);
  // Y from Newtonian (0) through the data's range (0.0015 to 0.045) to the suspension limit 2/(3 pi) ~ 0.212.
  const double ys[] = {0.0, 0.0015, 0.01, 0.02, 0.045, 0.1, 0.2};
  pastemix::Rng rng(5);
  for (int draw = 0; draw < 60; ++draw) {
    std::vector<double> c(info.n_coefficients);
    for (int i = 0; i < info.n_coefficients; ++i) {
      const double lo = std::max(info.lower[i], 1e-3), hi = info.upper[i];
      // q spans zero (either sign is admissible): uniform; the others log-uniform over their decades.
      c[i] = i == 5 ? rng.uniform(info.lower[i], info.upper[i]) : std::exp(rng.uniform(std::log(lo), std::log(hi)));
    }
    REQUIRE(check_coefficients(CurveId::yield_blend, c).empty());
    for (double y : ys) {
      // Where exp(-q Y) and a are so small that the viscous-yield branch is below 1e-15 c even at Re' = 1e-3,
      // Cd equals c to the last bit on the whole range: still well posed, but not visibly lower at 1e4.
      const double x = c[0] * std::exp(-c[5] * y) / 1e-3 + c[1] * std::pow(1e-3, -c[2]);
      check_well_posed(DragCurve{CurveId::yield_blend, c}, y, std::pow(x / c[3], c[4]) > 1e-15);
    }
  }
  // At fixed Y it is power_blend with k exp(-q Y) in place of k.
  const std::vector<double> c{60.0, 5.0, 0.5, 0.4, 3.0, 30.0};
  for (double re : {1e-3, 0.7, 40.0, 5e3})
    CHECK(DragCurve{CurveId::yield_blend, c}.cd(re, 0.03) ==
          doctest::Approx(DragCurve{CurveId::power_blend, {60.0 * std::exp(-0.9), 5.0, 0.5, 0.4, 3.0}}.cd(re, 0.7))
              .epsilon(1e-14));
  CHECK(yield_number(BinghamSphere{0.02, 3000.0, 1200.0, 18.0, 0.01}, 9.81) ==
        doctest::Approx(18.0 / (9.81 * 0.02 * 1800.0)).epsilon(1e-15));
}

TEST_CASE("drag curves: Jets give the derivative of yield_blend in q") {
  using J = ceres::Jet<double, 6>;
  const std::vector<double> c{60.0, 5.0, 0.5, 0.4, 3.0, 30.0};
  const double re = 3.0, y = 0.03;
  J cj[6];
  for (int i = 0; i < 6; ++i) cj[i] = J(c[i], i);
  const J out = drag_coefficient(CurveId::yield_blend, cj, J(re), y);
  auto hi = c, lo = c;
  hi[5] += 1e-5, lo[5] -= 1e-5;
  const double fd = (DragCurve{CurveId::yield_blend, hi}.cd(re, y) - DragCurve{CurveId::yield_blend, lo}.cd(re, y)) / 2e-5;
  CHECK(out.v[5] == doctest::Approx(fd).epsilon(1e-6));
  CHECK(out.v[5] < 0.0);  // larger q lowers the viscous-yield branch
}

TEST_CASE("drag curves: Jets give the derivative of Cd in Re' and in the coefficients") {
  using J = ceres::Jet<double, 6>;
  const std::vector<double> c{5.0, 12.0, 0.7, 0.4, 3.0};
  const double re = 37.0;
  J cj[5];
  for (int i = 0; i < 5; ++i) cj[i] = J(c[i], i);
  const J out = drag_coefficient(CurveId::power_blend, cj, J(re, 5), 0.0);
  const DragCurve curve{CurveId::power_blend, c};
  CHECK(out.a == doctest::Approx(curve.cd(re, 0.0)).epsilon(1e-14));
  for (int i = 0; i < 6; ++i) {
    auto c_hi = c, c_lo = c;
    double re_hi = re, re_lo = re;
    const double h = 1e-6 * (i < 5 ? c[i] : re);
    if (i < 5) c_hi[i] += h, c_lo[i] -= h;
    else re_hi += h, re_lo -= h;
    const double fd =
        (DragCurve{CurveId::power_blend, c_hi}.cd(re_hi, 0.0) - DragCurve{CurveId::power_blend, c_lo}.cd(re_lo, 0.0)) /
        (2 * h);
    CHECK(out.v[i] == doctest::Approx(fd).epsilon(1e-6));
  }
}

TEST_CASE("drag curves: Dedegil drag and the settling Cd (4.17) are consistent") {
  // At any speed, the Cd that (4.17) backs out of a force balance is the Cd the drag used.
  const BinghamSphere s{0.0254, 3000.0, 1226.0, 17.5, 0.0081};
  const DragCurve curve{CurveId::power_sum, {24.0, 3.0, 0.5, 0.3}};
  for (double v : {0.05, 0.3, 1.2}) {
    // Pick g so that net weight equals the drag at v, then (4.17) must return curve.cd(Re'(v)).
    const double g = curve.drag(s, v, 0.0) / ((s.rho_p - s.rho_f) * pastemix::units::pi * s.d * s.d * s.d / 6.0);
    const double re = bingham_reynolds(s.rho_f, v, s.tau_y, s.eta_B, s.d);
    CHECK(settling_drag_coefficient(s, v, g) == doctest::Approx(curve.cd(re, 0.0)).epsilon(1e-12));
  }
}
