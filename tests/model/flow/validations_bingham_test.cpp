// SPDX-License-Identifier: MIT
// The yield-stress validations at cheap resolutions with their stated tolerances (the acceptance resolutions:
// `pastemix validate flow poiseuille | incline | cliff`, model/flow/VALIDATION.md part 2).
#include "model/flow/validations_bingham.h"

#include <doctest/doctest.h>
#include <omp.h>

#include <cmath>

using namespace pastemix::flow;

TEST_CASE("validation poiseuille: Bingham plug flow, L2 error <= 1 % at 32 cells, second order from 16 (measured 0.32 %, 2.00)") {
  omp_set_num_threads(1);
  const PoiseuilleResult a = bingham_poiseuille(16, 1000.0), b = bingham_poiseuille(32, 1000.0);
  CHECK(b.l2_error <= 0.01);
  CHECK(std::log2(a.l2_error / b.l2_error) >= 1.8);
  // The yield surfaces within a tenth of a cell of tau_y / G either side of the centre.
  CHECK(std::abs(b.plug_width - b.plug_width_exact) < 0.1 * b.H / 32);
  CHECK(b.plug_speed == doctest::Approx(b.plug_speed_exact).epsilon(1e-3));
  CHECK(b.last_change < 1e-9);
  CHECK(b.volume_drift <= 1e-8);
}

TEST_CASE("validation incline: at 0.8 h_c the surface creeps below 1e-5 m/s and halves with m doubled") {
  omp_set_num_threads(1);
  const InclineResult a = bingham_incline(0.8, 12, 1000.0), b = bingham_incline(0.8, 12, 2000.0);
  CHECK(a.surface_speed < 1e-5);
  CHECK(b.surface_speed < 1e-5);
  // Papanastasiou's creep rate at a stress below tau_y is -ln(1 - tau/tau_y) / m: the ratio is 2 - O(eta_B / (tau_y m)).
  CHECK(a.surface_speed / b.surface_speed >= 1.999);
  CHECK(a.volume_drift <= 1e-8);
}

TEST_CASE("validation incline: at 1.5 h_c the surface speed is the analytic Bingham film's within 2 % (12 cells: 0.06 %)") {
  omp_set_num_threads(1);
  const InclineResult r = bingham_incline(1.5, 12, 1000.0);
  CHECK(std::abs(r.surface_speed / r.surface_speed_exact - 1.0) < 0.02);
  CHECK(r.last_change < 1e-4);
  CHECK(r.volume_drift <= 1e-8);
}

TEST_CASE("validation cliff: a cut of 2 tau_y/(rho g) stands (< 0.1 cell in 2 s), one of 6 tau_y/(rho g) collapses") {
  omp_set_num_threads(1);
  const CliffResult stand = bingham_cliff(2.0, 8, 1000.0);
  CHECK(stand.displacement < 0.1 * stand.h);
  CHECK(stand.volume_drift <= 1e-8);
  const CliffResult fall = bingham_cliff(6.0, 8, 1000.0);
  CHECK(fall.front_advance > 0.5 * fall.H);  // measured 36 mm of a 46 mm cut
  CHECK(fall.volume_drift <= 1e-8);
}

TEST_CASE("validation slump: the references (Pashias-Boger 101.7 mm at 138 Pa, Roussel-Coussot's shape holds its volume)") {
  CHECK(pashias_boger_slump(137.97137433825228, 1843.0, 0.152) == doctest::Approx(0.1017).epsilon(5e-4));
  // The stopped shape h = sqrt(2 tau_y (R - r) / (rho g)) on r < R, integrated numerically, holds the volume R
  // was computed from (the 152 mm cylinder's).
  const double tau = 138.0, rho = 1843.0, V = 3.14159265358979 * 0.076 * 0.076 * 0.152;
  const double R = roussel_coussot_radius(tau, rho, V);
  double vol = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double r = (i + 0.5) * R / n;
    vol += 2.0 * 3.14159265358979 * r * std::sqrt(2.0 * tau * (R - r) / (rho * 9.81)) * R / n;
  }
  CHECK(vol == doctest::Approx(V).epsilon(1e-6));
  CHECK(2 * R == doctest::Approx(0.3556).epsilon(1e-3));
}

TEST_CASE("validation slump: 20 mm cells for 0.5 s keep the paste volume to 1e-8 (the slump's accuracy: the command)") {
  omp_set_num_threads(1);
  const SlumpResult r = bingham_slump(0.02, 1000.0, 138.0, 1843.0, 0.7, 0.5);
  CHECK(r.volume_drift <= 1e-8);
  CHECK(r.max_divergence <= 1e-10);
  CHECK(r.slump > 0.02);  // it has slumped by more than a cell in 0.5 s
}

TEST_CASE("validation slump: the mould lifted at 60 mm/s, 20 mm cells for 0.5 s keep the paste volume to 1e-8") {
  omp_set_num_threads(1);
  const SlumpResult r = bingham_slump(0.02, 1000.0, 138.0, 1843.0, 0.7, 0.5, {}, 0.06);
  CHECK(r.volume_drift <= 1e-8);
  CHECK(r.max_divergence <= 1e-10);
  CHECK(!r.at_rest);           // the edge is at 30 mm at 0.5 s: the mould still holds the paste
  CHECK(r.slump > 0.0);        // it has started to slump below the edge
  const SlumpResult at_once = bingham_slump(0.02, 1000.0, 138.0, 1843.0, 0.7, 0.5);
  CHECK(r.slump < at_once.slump);  // held back by the mould
}
