// SPDX-License-Identifier: MIT
#include "lab/drag/terminal_velocity.h"

#include <cmath>

#include <doctest/doctest.h>

#include "base/units.h"

using namespace pastemix::lab::drag;
using pastemix::drag::CurveId;
using pastemix::units::g;

namespace {
constexpr double pi = pastemix::units::pi;
}

TEST_CASE("terminal velocity: Stokes curve, tau_y = 0, matches (rho_p - rho_f) g d^2 / (18 eta) within 1e-6") {
  const DragCurve stokes{CurveId::stokes, {}};
  for (const BinghamSphere s : {BinghamSphere{1e-4, 2650, 1000, 0, 1e-3}, BinghamSphere{0.0126, 7800, 1843, 0, 0.7},
                                BinghamSphere{0.05, 3000, 1200, 0, 50.0}}) {
    const double exact = stokes_terminal_velocity(s, g);
    for (const auto& tv : {solve_terminal_velocity(stokes, s, g), solve_terminal_velocity_monotone(stokes, s, g)}) {
      REQUIRE(tv.outcome == SettlingOutcome::settling);
      const double rel = std::abs(tv.v / exact - 1.0);
      MESSAGE("d = ", s.d, " m: v = ", tv.v, " m/s, Stokes ", exact, " m/s, |rel. err.| ", rel);
      CHECK(rel < 1e-6);
    }
    CHECK(solve_terminal_velocity(stokes, s, g).sign_changes == 1);
  }
  // Table 4.1 particle (0.1 mm, 2700 kg/m3 in water): 0.009265 m/s per the dataset README.
  CHECK(stokes_terminal_velocity({1e-4, 2700, 1000, 0, 1e-3}, g) == doctest::Approx(0.009265).epsilon(1e-3));
}

TEST_CASE("terminal velocity: Stokes curve with a yield stress has a closed form") {
  // 24/Re' makes the dynamic drag 3 pi d^2 tau_y + 3 pi eta d v, so
  //   v = (W - pi^2 d^2 tau_y / 4 - 3 pi d^2 tau_y) / (3 pi eta d), and suspended when that is <= 0.
  const DragCurve stokes{CurveId::stokes, {}};
  const BinghamSphere s{0.0254, 6000, 1226, 17.5, 0.0081};
  const double W = (s.rho_p - s.rho_f) * g * pi * std::pow(s.d, 3) / 6;
  const double exact = (W - pi * pi * s.d * s.d * s.tau_y / 4 - 3 * pi * s.d * s.d * s.tau_y) / (3 * pi * s.eta_B * s.d);
  const auto tv = solve_terminal_velocity(stokes, s, g);
  REQUIRE(tv.outcome == SettlingOutcome::settling);
  CHECK(tv.v == doctest::Approx(exact).epsilon(1e-9));
  // Yield threshold: W = (pi^2/4 + 3 pi) d^2 tau_y. Just above it the sphere is held; just below it moves.
  const double tau_crit = W / ((pi * pi / 4 + 3 * pi) * s.d * s.d);
  BinghamSphere held = s, moving = s;
  held.tau_y = tau_crit * (1 + 1e-6);
  moving.tau_y = tau_crit * (1 - 1e-3);
  CHECK(solve_terminal_velocity(stokes, held, g).outcome == SettlingOutcome::suspended);
  CHECK(solve_terminal_velocity_monotone(stokes, held, g).outcome == SettlingOutcome::suspended);
  const auto slow = solve_terminal_velocity(stokes, moving, g);
  CHECK(slow.outcome == SettlingOutcome::settling);
  CHECK(slow.v > 0.0);
}

TEST_CASE("terminal velocity: published 4.19 traps suspension 1, d = 50.8 mm, 2673 kg/m3 at sqrt(tau_y/rho_f)") {
  const DragCurve pub{CurveId::published_4_19, {}};
  const BinghamSphere s{0.0508, 2673, 1280, 30.5, 0.0131};
  const auto tv = solve_terminal_velocity(pub, s, g);
  CHECK(tv.outcome == SettlingOutcome::no_consistent_solution);
  const double v_trap = std::sqrt(s.tau_y / s.rho_f);  // Re' = 1 when the viscous term is negligible
  CHECK(v_trap == doctest::Approx(0.1544).epsilon(1e-3));
  CHECK(tv.bracket_lo <= tv.bracket_hi);
  MESSAGE("trap bracket [", tv.bracket_lo, ", ", tv.bracket_hi, "] m/s, G = ", tv.residual_lo, " / ",
          tv.residual_hi, " N, sqrt(tau_y/rho_f) = ", v_trap, " m/s");
  CHECK(std::abs(tv.v / v_trap - 1.0) < 0.01);
  CHECK(tv.bracket_hi - tv.bracket_lo < 1e-9);
  // The residual jumps from + to - across the bracket: weight exceeds drag just below, drag exceeds it above.
  CHECK(tv.residual_lo > 0.0);
  CHECK(tv.residual_hi < 0.0);
  // Re' at the bracket is 1 (the discontinuity of 4.19).
  CHECK(pastemix::drag::bingham_reynolds(s.rho_f, tv.v, s.tau_y, s.eta_B, s.d) == doctest::Approx(1.0).epsilon(1e-9));
  // A heavier sphere passes the jump and settles normally on the middle branch.
  BinghamSphere heavy = s;
  heavy.rho_p = 7000;
  const auto ok = solve_terminal_velocity(pub, heavy, g);
  CHECK(ok.outcome == SettlingOutcome::settling);
  CHECK(pastemix::drag::bingham_reynolds(s.rho_f, ok.v, s.tau_y, s.eta_B, s.d) > 1.0);
}

TEST_CASE("terminal velocity: a fluid as dense as the sphere holds it") {
  const DragCurve stokes{CurveId::stokes, {}};
  CHECK(solve_terminal_velocity(stokes, {0.01, 1000, 1000, 0, 1e-3}, g).outcome == SettlingOutcome::suspended);
}

TEST_CASE("terminal velocity: fast and full solvers agree for a fitted-family curve") {
  const DragCurve curve{CurveId::power_blend, {5.0, 15.0, 0.75, 0.4, 4.0}};
  for (double rho_p : {2200.0, 3000.0, 7000.0}) {
    const BinghamSphere s{0.0254, rho_p, 1207, 13, 0.0067};
    const auto full = solve_terminal_velocity(curve, s, g), fast = solve_terminal_velocity_monotone(curve, s, g);
    REQUIRE(full.outcome == SettlingOutcome::settling);
    CHECK(full.sign_changes == 1);
    CHECK(fast.v == doctest::Approx(full.v).epsilon(1e-12));
    CHECK(curve.drag(s, full.v, pastemix::drag::yield_number(s, g)) == doctest::Approx(pastemix::drag::net_weight(s, g)).epsilon(1e-10));
  }
}
