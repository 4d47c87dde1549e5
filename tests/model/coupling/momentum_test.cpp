// SPDX-License-Identifier: MIT
// The issue's `momentum` acceptance test, through the whole coupled step (model/coupling/coupled_flow.h): in a
// periodic box full of paste, particles (1.5-25 mm, some with a yield part, relaxation times from ~1e-3 to
// ~10 s against a coupling interval of 20 ms) and the fluid together gain exactly the gravity impulse
// M g t, and the drag on the particles is minus the force on the fluid to round-off. The momentum counts the
// pressure impulses still pending for the particles (given over the next sub-cycle).
#include "model/coupling/coupled_flow.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "base/drag_curves.h"
#include "model/fluid/drag_kick.h"
#include "model/laws/bingham_dedegil.h"
#include "model/laws/newtonian_stokes.h"

using namespace pastemix;

namespace {

using Vec = std::array<double, 3>;

template <class Law>
coupling::SphereDrag law_drag(const typename Law::Params& prm, double d, double tau_y, double eta) {
  static const drag::DragCurve stokes{drag::CurveId::stokes, {}};
  const auto sphere = Law::sphere(prm, stokes, d, 0.0);
  coupling::SphereDrag s;
  s.magnitude = [sphere](double v) { return Law::magnitude(sphere, v); };
  s.reynolds = [=](double v) { return drag::bingham_reynolds(prm.density, v, tau_y, eta, d); };
  s.rest = Law::magnitude(sphere, model::fluid::kRestSpeed);
  s.rest_speed = model::fluid::kRestSpeed;
  return s;
}

struct Box {
  flow::Grid g;
  flow::Phases ph;
  flow::FlowSettings fs;
};

Box periodic_paste(double eta) {
  Box b;
  b.g.n = {6, 5, 8};
  b.g.h = {0.01, 0.01, 0.01};
  for (auto& s : b.g.bc) s.type = flow::BoundaryType::periodic;
  b.ph.rho_paste = 1843.0;
  b.ph.paste = std::make_shared<flow::Newtonian>(eta);
  b.fs.max_time_step = 0.02;
  b.fs.viscous_tolerance = 1e-14;
  b.fs.pressure_tolerance = 1e-10;
  return b;
}

Vec total(const coupling::CoupledParticles& p, const coupling::CoupledFlow& cf) {
  Vec P = cf.fluid_momentum();
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int c = 0; c < 3; ++c) P[c] += p.m[i] * p.v[i][c] + cf.pending_impulse()[i][c];
  return P;
}

}  // namespace

TEST_CASE("coupling momentum: particles + fluid gain the gravity impulse through the whole coupled step") {
  const double eta = 0.7;
  Box b = periodic_paste(eta);
  b.fs.gravity = {0.0, 0.0, -9.81};
  flow::FlowSolver flow(b.g, b.ph, b.fs);
  flow.add_paste_box({0, 0, 0}, {0.06, 0.05, 0.08});
  coupling::CouplingSettings cs;
  cs.gravity = b.fs.gravity;
  coupling::CoupledFlow cf(flow, cs);

  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  coupling::CoupledParticles p;
  const model::NewtonianStokes::Params newtonian{1843.0, eta};
  const model::BinghamDedegil::Params bingham{1843.0, 2.0, eta};
  for (int i = 0; i < 16; ++i) {
    const double d = 0.0015 * std::pow(25.0 / 1.5, U(rng));  // 1.5-25 mm, log-uniform
    p.x.push_back({0.06 * U(rng), 0.05 * U(rng), 0.08 * U(rng)});
    p.v.push_back({0.05 * (U(rng) - 0.5), 0.05 * (U(rng) - 0.5), 0.05 * (U(rng) - 0.5)});
    p.d.push_back(d);
    p.m.push_back(2760.0 * std::numbers::pi * d * d * d / 6.0);
    p.drag.push_back(i % 3 == 0 ? law_drag<model::BinghamDedegil>(bingham, d, 2.0, eta)
                                : law_drag<model::NewtonianStokes>(newtonian, d, 0.0, eta));
  }
  cf.start(p);
  double mass = 0.0;
  for (double m : p.m) mass += m;
  const flow::Faces fm = flow.fluid_mass();
  double fluid_mass = 0.0;
  for (double m : fm[2]) fluid_mass += m;
  mass += fluid_mass;
  const Vec P0 = total(p, cf);
  double worst = 0.0, worst_pair = 0.0;
  int stuck = 0;
  const int steps = 20, cycles = 10;
  const double dt = 1e-3;
  for (int n = 1; n <= cycles; ++n) {
    // The drag impulse on the particles against the fluid's momentum change it caused: measured around the
    // cycle with gravity and pressure accounted for (total), and per cycle from the pieces.
    const coupling::CycleStats st = cf.cycle(p, steps, dt);
    stuck += st.stuck_steps;
    for (int c = 0; c < 3; ++c)
      worst_pair = std::max(worst_pair, std::abs(st.particle_exchange[c] + st.fluid_exchange[c]) / st.exchange_scale);
    const Vec P = total(p, cf);
    const double t = n * steps * dt;
    for (int c = 0; c < 3; ++c) {
      const double expected = P0[c] + mass * b.fs.gravity[c] * t;
      worst = std::max(worst, std::abs(P[c] - expected) / (mass * 9.81 * t));
    }
  }
  std::printf("coupling momentum: %zu particles, %d cycles of %d DEM steps (dt %.0e s), %g kg, 6 x 5 x 8 periodic "
              "cells: gravity impulse relative error %.3g, |drag on particles + force on fluid| / sum |J| %.3g, %d "
              "stuck particle-steps\n",
              p.size(), cycles, steps, dt, mass, worst, worst_pair, stuck);
  CHECK(worst < 1e-10);
  CHECK(worst_pair < 1e-12);
  CHECK(stuck > 0);  // the yield sub-cycle took part
}
