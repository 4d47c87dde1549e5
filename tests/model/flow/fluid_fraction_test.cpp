// SPDX-License-Identifier: MIT
// The volume-averaged parts of the flow solver (particles sharing the cells, FluidFraction and
// FluidFractionStep): eps_f = 1 given explicitly is the plain path bit for bit, the projection meets the
// fluid's continuity div(eps_f u) = -d eps_f/dt, the transport keeps a full cell full and the paste volume to
// round-off, and a paste at rest around a fixed porous block stays at rest.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "model/flow/advection.h"
#include "model/flow/linear.h"
#include "model/flow/solver.h"
#include "tests/model/flow/flow_fixture.h"

using namespace pastemix::flow;

namespace {

Grid closed_box() { return pastemix::test::cube_box({8, 6, 10}, 0.01, false); }

using pastemix::test::porous_ball;

Faces random_faces(const Grid& g, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Faces u;
  for (int c = 0; c < 3; ++c) u[c].assign(g.face_count(c), 0.0);
  g.for_each_face([&](int c, const std::array<int, 3>& q) {
    if (!g.boundary_face(c, q[c])) u[c][g.face(c, q)] = 0.01 * U(rng);
  });
  return u;
}

Faces uniform(const Grid& g, double v) {
  Faces f;
  for (int c = 0; c < 3; ++c) f[c].assign(g.face_count(c), v);
  return f;
}

double norm(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

}  // namespace

TEST_CASE("fluid fraction: eps_f = 1 given explicitly projects to the same bits as the plain projection") {
  const Grid g = closed_box();
  const Faces rho = uniform(g, 1843.0), ones = uniform(g, 1.0);
  const std::vector<double> zero(g.cell_count(), 0.0);
  Faces a = random_faces(g, 1), b = a;
  std::vector<double> pa(g.cell_count(), 0.0), pb = pa;
  project(g, 1e-3, rho, a, pa, 1e-10, 10000);
  PressureOperator op(g);
  const FluidFraction vf{&ones, &zero};
  op.project(1e-3, rho, b, pb, 1e-10, 10000, &vf);
  CHECK(pa == pb);
  for (int c = 0; c < 3; ++c) CHECK(a[c] == b[c]);
}

TEST_CASE("fluid fraction: the projection meets div(eps_f u) = -d eps_f/dt, with eps_f cancelling in the update") {
  const Grid g = closed_box();
  // The ball moves down by one cell: in a closed box the solid volume must not change (the sum of the rate is
  // then 0 to round-off; a source that does not sum to 0 has no solution there).
  const std::vector<double> e0 = porous_ball(g, {0.04, 0.03, 0.06}, 0.03), e1 = porous_ball(g, {0.04, 0.03, 0.05}, 0.03);
  const double dt = 1e-3;
  std::vector<double> rate(g.cell_count());
  for (long c = 0; c < g.cell_count(); ++c) rate[c] = (e1[c] - e0[c]) / dt;
  const Faces face = face_means(g, e1), rho = uniform(g, 1843.0);
  const FluidFraction vf{&face, &rate};
  Faces u = random_faces(g, 2);
  std::vector<double> p(g.cell_count(), 0.0);
  PressureOperator op(g);
  const ProjectionStats st = op.project(dt, rho, u, p, 1e-10, 10000, &vf);
  CHECK(st.divergence_after / st.divergence_before <= 1e-10);
  CHECK(norm(continuity_residual(g, u, &vf)) <= 1e-10 * st.divergence_before);
  CHECK(norm(divergence(g, u)) > 1e3 * st.divergence_after);  // the plain divergence is not what was removed
}

TEST_CASE("fluid fraction: a paste-filled box with a moving porous ball keeps full cells full and its volume to round-off") {
  Grid g = closed_box();
  g.bc[5].type = BoundaryType::open;
  const double dt = 2e-3;
  std::vector<double> e0 = porous_ball(g, {0.04, 0.03, 0.05}, 0.03), e1 = porous_ball(g, {0.041, 0.03, 0.047}, 0.03);
  std::vector<double> rate(g.cell_count());
  for (long c = 0; c < g.cell_count(); ++c) rate[c] = (e1[c] - e0[c]) / dt;
  const Faces face = face_means(g, e1), rho = uniform(g, 1843.0);
  const FluidFraction vf{&face, &rate};
  Faces u = random_faces(g, 3);
  std::vector<double> p(g.cell_count(), 0.0);
  PressureOperator(g).project(dt, rho, u, p, 1e-10, 10000, &vf);
  Phases ph;
  std::vector<double> alpha(g.cell_count(), 1.0);
  // The top layer half full: the paste's surface, away from the ball.
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i) alpha[g.cell(i, j, g.n[2] - 1)] = 0.5;
  auto volume = [&](const std::vector<double>& e) {
    double s = 0.0;
    for (long c = 0; c < g.cell_count(); ++c) s += e[c] * alpha[c];
    return s;
  };
  const double v0 = volume(e0);
  const FluidFractionStep fs{&e0, &e1, &face};
  advect(g, ph, dt, 0, alpha, u, nullptr, &fs);
  double worst = 0.0;
  for (int k = 0; k < g.n[2] - 2; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) worst = std::max(worst, std::abs(alpha[g.cell(i, j, k)] - 1.0));
  CHECK(worst <= 1e-9);  // full to the continuity residual (1e-10 of the source, over eps_f ~ 0.5)
  // Only the open top can change the volume; the paste stays below it, so nothing may.
  CHECK(std::abs(volume(e1) - v0) <= 1e-14 * v0);
}

TEST_CASE("fluid fraction: a paste at rest around a fixed porous ball stays at rest (hydrostatic with eps_f < 1)") {
  FlowSolver s = pastemix::test::paste_column({6, 6, 16}, 0.01, 1843.0, 0.1037);
  const Grid& g = s.grid();
  s.set_fluid_fraction(porous_ball(g, {0.03, 0.03, 0.1}, 0.025));  // through the surface
  const double v0 = s.paste_volume();
  for (int n = 0; n < 50; ++n) {
    s.set_next_fluid_fraction(s.fluid_fraction());
    s.step(s.next_time_step());
  }
  CHECK(s.max_speed() < 1e-8);
  CHECK(std::abs(s.paste_volume() - v0) <= 1e-12 * v0);
}

TEST_CASE("fluid fraction: the first coupled step of a moving paste projects it for the fluid's continuity") {
  // A paste streaming along a periodic x through a fixed porous ball: div(eps_f u) = u . grad eps_f is not 0
  // at the start, and nothing (no source, no earlier projection) gives the residual a scale but itself.
  Grid g;
  g.n = {10, 4, 8};
  g.h = {0.01, 0.01, 0.01};
  g.bc[0].type = g.bc[1].type = BoundaryType::periodic;
  g.bc[2].type = g.bc[3].type = BoundaryType::free_slip;
  g.bc[4].type = g.bc[5].type = BoundaryType::free_slip;
  Phases ph;
  ph.rho_paste = 1843.0;
  FlowSettings fs;
  fs.gravity = {0.0, 0.0, 0.0};
  FlowSolver s(g, ph, fs);
  s.add_paste_box({0, 0, 0}, {0.1, 0.04, 0.08});
  for (double& v : s.velocity()[0]) v = 0.02;
  const std::vector<double> eps = porous_ball(g, {0.05, 0.02, 0.04}, 0.02);
  s.set_fluid_fraction(eps);
  const double v0 = s.paste_volume();
  const Faces face = face_means(g, eps);
  const std::vector<double> zero(g.cell_count(), 0.0);
  const FluidFraction vf{&face, &zero};
  const double r0 = norm(continuity_residual(g, s.velocity(), &vf));  // 1/s
  REQUIRE(r0 > 1e-3);
  s.set_next_fluid_fraction(eps);
  s.step(1e-3);
  CHECK(norm(continuity_residual(g, s.velocity(), &vf)) <= 1e-10 * r0);
  CHECK(std::abs(s.paste_volume() - v0) <= 1e-14 * v0);
  CHECK(s.max_speed() > 0.01);  // it still streams
}
