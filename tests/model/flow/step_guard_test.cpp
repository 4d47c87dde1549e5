// SPDX-License-Identifier: MIT
// The step-collapse guard (model/flow/step_guard.h): a CFL step below 1/100 of the reference step stops the run
// with a RuntimeFailure (exit 3) that names the time, the fastest face, its speed, the paste fraction on its two
// sides and the cause; a step at the floor or above passes, and so does every state of a flow at rest.
#include "model/flow/step_guard.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "base/error.h"
#include "model/flow/solver.h"
#include "tests/input_error.h"
#include "tests/model/flow/flow_fixture.h"

using namespace pastemix;
using namespace pastemix::flow;

namespace {

// 10 mm cells, 4 x 3 x 10, open top; paste below z = 45 mm (the interface inside layer k = 4). A 50 ms cap:
// the gravity bound (17.5 ms) is the reference.
FlowSolver column() {
  FlowSettings fs;
  fs.max_time_step = 0.05;
  return pastemix::test::paste_column({4, 3, 10}, 0.01, 1843.0, 0.045, fs);
}

using pastemix::test::runtime_failure_of;

// The CFL step (s) with face q of component c at speed v (m/s), everything else at rest.
double cfl_step(FlowSolver& s, int c, const std::array<int, 3>& q, double v) {
  for (auto& comp : s.velocity()) std::fill(comp.begin(), comp.end(), 0.0);
  s.velocity()[c][s.grid().face(c, q)] = v;
  return s.settings().cfl * s.grid().h[c] / v;
}

}  // namespace

TEST_CASE("step guard: the floor is 1/100 of the smallest of the cap, the gravity bound and each wall's CFL step") {
  Grid g;
  g.n = {4, 4, 4};
  g.h = {0.01, 0.02, 0.005};
  // The gravity bound at the smallest cell (5 mm): sqrt(0.3 x 0.005 / 9.81) = 12.4 ms, above the 10 ms cap.
  StepControl c{0.3, 1e-2, {0.0, 0.0, -9.81}};
  CHECK(reference_step(g, c).dt == 1e-2);
  CHECK(std::string(reference_step(g, c).what) == "step cap");
  CHECK(time_step_floor(g, c) == 1e-4);
  c.max_time_step = 2e-2;
  CHECK(reference_step(g, c).dt == std::sqrt(0.3 * 0.005 / 9.81));
  CHECK(std::string(reference_step(g, c).what) == "gravity bound sqrt(cfl h / g)");
  g.bc[5].wall_velocity = {3.0, 0.0, 0.0};  // a lid at 3 m/s: cfl h / U = 0.5 ms
  CHECK(reference_step(g, c).dt == 0.3 * 0.005 / 3.0);
  CHECK(std::string(reference_step(g, c).what) == "CFL step of the fastest wall");
  c.gravity = {0.0, 0.0, 0.0};
  g.bc[5].wall_velocity = {};
  CHECK(time_step_floor(g, c) == 2e-4);
}

TEST_CASE("step guard: an air face far faster than the flow stops next_time_step with the diagnosis") {
  FlowSolver s = column();
  CHECK_NOTHROW(s.next_time_step());  // at rest
  const double floor = time_step_floor(s.grid(), {0.3, 0.05, {0.0, 0.0, -9.81}});
  CHECK(floor == doctest::Approx(std::sqrt(0.3 * 0.01 / 9.81) / 100.0).epsilon(1e-15));  // 175 us
  // The z face between cell k = 4 (paste fraction 0.5) and k = 5 (air): at the floor's speed the step is the
  // floor and passes; 1 % faster it is below and the run stops.
  const std::array<int, 3> q{1, 2, 5};
  const double at_floor = 0.3 * 0.01 / floor;  // 17.16 m/s
  CHECK(cfl_step(s, 2, q, at_floor * (1.0 - 1e-9)) > floor);
  CHECK_NOTHROW(s.next_time_step());
  cfl_step(s, 2, q, 1.01 * at_floor);
  const std::string what = runtime_failure_of([&] { (void)s.next_time_step(); });
  CAPTURE(what);
  CHECK(what.find("flow: time step collapse at t = 0 s (step 0)") != std::string::npos);
  CHECK(what.find("below the floor 0.000175 s (1/100 of the gravity bound sqrt(cfl h / g) 0.0175 s)") !=
        std::string::npos);
  CHECK(what.find("fastest face: z face (1, 2, 5) at (0.015, 0.025, 0.05) m, |u| = 17.33 m/s") != std::string::npos);
  CHECK(what.find("paste fraction 0.500 | 0.000 on its two sides") != std::string::npos);
  CHECK(what.find("fastest paste face 0 m/s: air velocity runaway at the interface") != std::string::npos);
}

TEST_CASE("step guard: the cause names where the fastest face is: in the air, through the open side, or in the paste") {
  FlowSolver s = column();
  const double v = 40.0;  // m/s: above the 17 m/s ceiling
  cfl_step(s, 0, {2, 1, 8}, v);  // an x face high in the air
  CHECK(runtime_failure_of([&] { (void)s.next_time_step(); }).ends_with("air velocity runaway in the air"));
  cfl_step(s, 2, {2, 1, 10}, v);  // a z face of the open top (the 10 mm slump's runaway, VALIDATION.md)
  CHECK(runtime_failure_of([&] { (void)s.next_time_step(); })
            .ends_with("air velocity runaway in the air, through the open z_hi side"));
  cfl_step(s, 0, {2, 1, 1}, v);  // an x face inside the paste
  const std::string what = runtime_failure_of([&] { (void)s.next_time_step(); });
  CHECK(what.find("fastest paste face 40 m/s: velocity runaway in the paste") != std::string::npos);
}

TEST_CASE("step guard: a run with a runaway face stops in advance_to instead of running on") {
  FlowSolver s = column();
  cfl_step(s, 2, {1, 1, 6}, 30.0);
  long steps = -1;
  const std::string what = runtime_failure_of([&] { steps = s.advance_to(1.0); });
  CHECK(what.find("time step collapse") != std::string::npos);
  CHECK(steps == -1);
  CHECK(s.time() == 0.0);  // no step was taken at the collapsed dt
}

TEST_CASE("step guard: with particles in the cells the diagnosis names the fluid fraction on the face's two sides") {
  // A runaway inside a packed rock pile (case 3's crater, issue 22) reads "air ... in the air" by the paste
  // fraction alone; the fluid fraction on the two sides says the face is in the pile.
  FlowSolver s = column();
  const StepControl c{0.3, 0.05, {0.0, 0.0, -9.81}};
  const double dt = 0.5 * time_step_floor(s.grid(), c);
  std::vector<double> eps_f(s.grid().cell_count(), 1.0);
  const std::array<int, 3> q{2, 1, 8};  // an x face between cells (1, 1, 8) and (2, 1, 8)
  eps_f[s.grid().cell(1, 1, 8)] = 0.43;
  eps_f[s.grid().cell(2, 1, 8)] = 0.45;
  cfl_step(s, 0, q, 40.0);
  const std::string with = runtime_failure_of(
      [&] { require_time_step_above_floor(s.grid(), c, s.velocity(), s.alpha(), dt, 1.5, 7, &eps_f); });
  CAPTURE(with);
  CHECK(with.ends_with("air velocity runaway in the air (fluid fraction 0.430 | 0.450 on its two sides)"));
  const std::string without = runtime_failure_of(
      [&] { require_time_step_above_floor(s.grid(), c, s.velocity(), s.alpha(), dt, 1.5, 7); });
  CHECK(without.ends_with("air velocity runaway in the air"));
}

// Chapter-7 test 3 with flow stopped on "internal error: flow advection: CFL above 1/2 per sweep" when a 50 mm
// rock entered the box in one coupling cycle: the step had been chosen from u before the continuity projection.
TEST_CASE("step guard: a fluid-fraction change too fast for the step throws FluxStepTooLong and leaves u as it was") {
  // 6 x 6 x 16 cells of 10 mm, open top at 16 cm, paste below 10.37 cm; a ball of solid (peak 0.5, radius 4 cm)
  // appears at z = 13 cm, mostly in the air, within one 5 ms step: its air leaves through the top.
  FlowSolver s = pastemix::test::paste_column({6, 6, 16}, 0.01, 1843.0, 0.1037);
  const Grid& g = s.grid();
  s.set_fluid_fraction(std::vector<double>(g.cell_count(), 1.0));
  const std::vector<double> eps1 = pastemix::test::porous_ball(g, {0.03, 0.03, 0.13}, 0.04);
  s.set_next_fluid_fraction(eps1);
  const Faces u0 = s.velocity();
  const double t0 = s.time();
  FluxStepTooLong caught("", 0.0);
  bool thrown = false;
  try {
    s.step(5e-3);
  } catch (const FluxStepTooLong& e) {
    caught = e, thrown = true;
  }
  REQUIRE(thrown);
  const std::string what = caught.what();
  CAPTURE(what);
  CHECK(caught.cfl() > 0.5);
  CHECK(what.find("flow: the particles' volume change outruns the flow step at t = 0 s (step 0)") != std::string::npos);
  CHECK(what.find("(bound 0.5) over the step 0.005 s") != std::string::npos);
  CHECK(what.find("largest fluid-fraction change of a cell over the step 0.") != std::string::npos);
  for (int c = 0; c < 3; ++c) CHECK(s.velocity()[c] == u0[c]);  // bit for bit: nothing was done
  CHECK(s.time() == t0);
  // The same change over the same 5 ms in parts short enough for the flux passes, the ball's air out of the top.
  const int parts = static_cast<int>(std::ceil(caught.cfl() / s.settings().cfl));
  const std::vector<double> eps0(g.cell_count(), 1.0);
  for (int j = 1; j <= parts; ++j) {
    std::vector<double> eps(g.cell_count());
    for (long c = 0; c < g.cell_count(); ++c) eps[c] = eps0[c] + (static_cast<double>(j) / parts) * (eps1[c] - eps0[c]);
    s.set_next_fluid_fraction(j == parts ? eps1 : eps);
    CHECK_NOTHROW(s.step(5e-3 / parts));
  }
  CHECK(s.time() == doctest::Approx(5e-3).epsilon(1e-12));
}
