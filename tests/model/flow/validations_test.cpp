// SPDX-License-Identifier: MIT
// The cheap validations at their stated tolerances (the full-size ones: `pastemix validate flow`, VALIDATION.md).
#include "model/flow/validations.h"

#include <doctest/doctest.h>
#include <omp.h>

#include <cmath>

#include "tests/run_command.h"

using namespace pastemix::flow;

TEST_CASE("validation still: ratio 1800, interface at 10.37 cells, 1 s: max|u| < 1e-6 m/s, volume to 1e-10") {
  omp_set_num_threads(1);
  const StillResult r = still(1.0);
  CHECK(r.max_speed < 1e-6);
  CHECK(r.volume_drift < 1e-10);
  CHECK(r.max_divergence <= 1e-10);
}

TEST_CASE("validation cavity: Re 100 on 16 x 16 is within 3 % of the lid speed of Ghia (measured 2.2 %, 64 x 64: the command)") {
  omp_set_num_threads(1);
  const GhiaReference ref = read_ghia(pastemix::test::source_path("datasets/reference/ghia_ghia_shin_1982_cavity.csv"), 100);
  const CavityResult r = cavity(16, 100, ref, 30.0);
  CHECK(r.steady_change < 1e-4);
  CHECK(r.max_error_u < 0.03);
  CHECK(r.max_error_v < 0.03);
  CHECK(r.volume_drift < 1e-8);
}

TEST_CASE("validation dam-break: 10 cells across, the front within 15 % of Martin & Moyce for 1 <= T <= 3") {
  omp_set_num_threads(1);
  const Series mm = read_martin_moyce(pastemix::test::source_path("datasets/reference/martin_moyce_1952_n2_2.csv"));
  std::vector<double> T, Z;
  for (std::size_t i = 0; i < mm.T.size(); ++i)
    if (mm.T[i] >= 1.0 && mm.T[i] <= 3.0) T.push_back(mm.T[i]), Z.push_back(mm.Z[i]);
  const DamBreakResult r = dam_break(10, T);
  for (std::size_t i = 0; i < T.size(); ++i) CHECK(std::abs(r.front[i] - Z[i]) / Z[i] < 0.15);
  CHECK(r.volume_drift < 1e-8);
}
