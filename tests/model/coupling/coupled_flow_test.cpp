// SPDX-License-Identifier: MIT
// One coupling interval (model/coupling/coupled_flow.cpp: CoupledFlow::flow_interval) when the particles' volume
// change outruns the flow's sub-steps: chapter-7 test 3 with flow stopped on "internal error: flow advection:
// CFL above 1/2 per sweep" when a 50 mm rock entered the box in one 1 ms cycle (its solid put in at once). The
// interval now splits its sub-steps again from the one the flow refused (flow::FluxStepTooLong) and goes on.
#include "model/coupling/coupled_flow.h"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "base/drag_curves.h"
#include "model/flow/step_guard.h"
#include "model/fluid/drag_kick.h"
#include "model/laws/newtonian_stokes.h"
#include "tests/model/flow/flow_fixture.h"

using namespace pastemix;

namespace {

coupling::SphereDrag stokes_drag(double d, double eta) {
  static const drag::DragCurve stokes{drag::CurveId::stokes, {}};
  const model::NewtonianStokes::Params prm{1843.0, eta};
  const auto sphere = model::NewtonianStokes::sphere(prm, stokes, d, 0.0);
  coupling::SphereDrag s;
  s.magnitude = [sphere](double v) { return model::NewtonianStokes::magnitude(sphere, v); };
  s.reynolds = [=](double v) { return drag::bingham_reynolds(1843.0, v, 0.0, eta, d); };
  s.rest = model::NewtonianStokes::magnitude(sphere, model::fluid::kRestSpeed);
  s.rest_speed = model::fluid::kRestSpeed;
  return s;
}

}  // namespace

TEST_CASE("coupled flow: a rock whose solid arrives faster than a sub-step can carry is split again, not a crash") {
  // 6 x 6 x 16 cells of 10 mm, open top at 16 cm, paste below 10.37 cm. A 40 mm rock held in the air at
  // z = 13 cm and moved 2 cm sideways between two 5 ms cycles: the cells it leaves and enters change their
  // fluid fraction by most of a cell within the cycle's one sub-step.
  flow::FlowSettings fs;
  fs.max_time_step = 0.01;
  flow::FlowSolver flow = pastemix::test::paste_column({6, 6, 16}, 0.01, 1843.0, 0.1037, fs);
  coupling::CouplingSettings cs;
  cs.width_factor = 1.25;  // a kernel as narrow as the sphere: its solid fraction peaks near 1
  coupling::CoupledFlow cf(flow, cs);
  coupling::CoupledParticles p;
  const double d = 0.04;
  p.x.push_back({0.02, 0.03, 0.13});
  p.v.push_back({0.0, 0.0, 0.0});
  p.d.push_back(d);
  p.m.push_back(2760.0 * std::numbers::pi * d * d * d / 6.0);
  p.drag.push_back(stokes_drag(d, 0.7));
  cf.start(p);
  // Held: no gravity on the rock (its weight taken out), so only the move changes the fluid fraction.
  const auto hold = [](std::size_t i, const coupling::CoupledParticles& q) {
    return std::array<double, 3>{0.0, 0.0, 9.81 * q.m[i]};
  };
  const coupling::CycleStats before = cf.cycle(p, 1, 5e-3, hold);
  p.x[0] = {0.04, 0.03, 0.13};
  p.v[0] = {0.0, 0.0, 0.0};
  coupling::CycleStats moved;
  CHECK_NOTHROW(moved = cf.cycle(p, 1, 5e-3, hold));
  CAPTURE(before.flow_steps);
  CAPTURE(moved.flow_steps);
  REQUIRE(before.flow_steps == 1);  // from rest the velocity CFL asks for one sub-step of the cycle
  CHECK(moved.flow_steps > 1);      // the refused sub-step was split again
  CHECK(std::isfinite(flow.max_speed()));
}

// Particles packed beyond what the kernel spreads (chapter-7 test 3 with flow: "the particles fill cell 4766"
// somewhere after t = 0.59 s, with no time or place in the message): the diagnosis names the cell by its indices
// and centre, and the flow's time.
TEST_CASE("coupled flow: an overfilled cell is named with its place and the time") {
  flow::FlowSettings fs;
  fs.max_time_step = 0.01;
  flow::FlowSolver flow = pastemix::test::paste_column({6, 6, 16}, 0.01, 1843.0, 0.1037, fs);
  coupling::CouplingSettings cs;
  cs.width_factor = 1.25;
  coupling::CoupledFlow cf(flow, cs);
  coupling::CoupledParticles p;
  const double d = 0.012;
  for (int k = 0; k < 4; ++k) {  // four 12 mm spheres on one spot: four times one sphere's peak solid fraction
    p.x.push_back({0.035, 0.035, 0.055});
    p.v.push_back({0.0, 0.0, 0.0});
    p.d.push_back(d);
    p.m.push_back(2760.0 * std::numbers::pi * d * d * d / 6.0);
    p.drag.push_back(stokes_drag(d, 0.7));
  }
  try {
    cf.start(p);
    FAIL("an overfilled cell was accepted");
  } catch (const RuntimeFailure& e) {
    const std::string what = e.what();
    CAPTURE(what);
    CHECK(what.find("the particles fill cell") != std::string::npos);
    CHECK(what.find("(3, 3, 5) at (0.035, 0.035, 0.055) m") != std::string::npos);
    CHECK(what.find("at t = 0 s of the flow") != std::string::npos);
  }
}
