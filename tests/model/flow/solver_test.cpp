// SPDX-License-Identifier: MIT
// FlowSolver: the time step follows its bounds, results do not depend on the thread count, and hydrostatic
// equilibrium holds in a layered column.
#include "model/flow/solver.h"

#include <doctest/doctest.h>
#include <omp.h>

#include <cmath>

#include "tests/model/flow/flow_fixture.h"

using namespace pastemix::flow;

namespace {
FlowSolver sloshing(int threads) {
  omp_set_num_threads(threads);
  Phases ph;
  ph.rho_paste = 1850.0;
  ph.paste = std::make_shared<Newtonian>(0.5);
  FlowSolver s(pastemix::test::cube_box({12, 4, 10}, 0.01, true), ph, FlowSettings{});
  s.add_paste_box({0, 0, 0}, {0.05, 0.04, 0.073});  // a column that collapses
  s.add_paste_box({0.05, 0, 0}, {0.12, 0.04, 0.021});
  s.advance_to(0.05);
  return s;
}
}  // namespace

TEST_CASE("solver: a collapsing column gives the same bits on 1 and 2 threads") {
  const FlowSolver a = sloshing(1), b = sloshing(2);
  omp_set_num_threads(1);
  REQUIRE(a.totals().steps == b.totals().steps);
  CHECK(a.alpha() == b.alpha());
  CHECK(a.pressure() == b.pressure());
  for (int c = 0; c < 3; ++c) CHECK(a.velocity()[c] == b.velocity()[c]);
  CHECK(a.max_speed() > 0.05);  // it did move
}

TEST_CASE("solver: the step respects the CFL number and the gravity bound") {
  Grid g;
  g.n = {4, 4, 4};
  g.h = {0.02, 0.01, 0.01};
  FlowSettings fs;
  fs.cfl = 0.25;
  fs.max_time_step = 1.0;
  FlowSolver s(g, Phases{}, fs);
  CHECK(s.next_time_step() == doctest::Approx(std::sqrt(0.25 * 0.01 / 9.81)));
  s.velocity()[0][g.face(0, {2, 1, 1})] = 10.0;  // 10 m/s across 2 cm cells: dt = 0.25 * 0.02 / 10
  CHECK(s.next_time_step() == doctest::Approx(5e-4));
  CHECK_THROWS(FlowSolver(g, Phases{}, FlowSettings{0.6}));
}

TEST_CASE("solver: a three-layer column at rest has the hydrostatic pressure and stays at rest") {
  FlowSolver s = pastemix::test::paste_column({3, 3, 30}, 0.01, 2000.0, 0.1234);
  const Grid& g = s.grid();
  s.advance_to(0.2);
  CHECK(s.max_speed() < 1e-9);
  // Bottom cell centre at z = 0.005: p = rho_air g (0.3 - 0.1234) + rho_paste g (0.1234 - 0.005), to the cell
  // discretisation of the interface cell (its density is the mixture's over the whole cell).
  const double p_bottom = 1.2 * 9.81 * (0.3 - 0.1234) + 2000.0 * 9.81 * (0.1234 - 0.005);
  CHECK(s.pressure()[g.cell(1, 1, 0)] == doctest::Approx(p_bottom).epsilon(2e-3));
}
