// SPDX-License-Identifier: MIT
// Walls inside the box (model/flow/obstacle.h): the lifted mould's staircase and its schedule, and each stage of
// the step honouring a blocked face (projection: no flux, Neumann; viscous step: u = 0, free slip; the whole
// step: a column held by the mould stays at rest, and falls without it).
#include "model/flow/obstacle.h"

#include <doctest/doctest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "model/flow/linear.h"
#include "model/flow/solver.h"

using namespace pastemix::flow;

namespace {

// The slump's quarter domain at 20 mm cells: 13 x 13 x 8 cells, symmetry planes x = 0, y = 0, open top.
Grid quarter(double cell = 0.02) {
  Grid g;
  g.n = {static_cast<int>(std::ceil(0.26 / cell)), static_cast<int>(std::ceil(0.26 / cell)),
         static_cast<int>(std::ceil(0.16 / cell))};
  g.h = {cell, cell, cell};
  for (int s = 0; s < 4; ++s) g.bc[s].type = BoundaryType::free_slip;
  g.bc[5].type = BoundaryType::open;
  return g;
}

LiftedMould mould(double speed) {
  LiftedMould m;
  m.speed = speed;  // radius 76 mm, height 152 mm, axis at the corner: the defaults
  return m;
}

long blocked_in_layer(const Grid& g, const FaceMask& m, int c, int k) {
  if (m[c].empty()) return 0;
  long n = 0;
  const auto fd = g.face_dims(c);
  for (int j = 0; j < fd[1]; ++j)
    for (int i = 0; i < fd[0]; ++i) n += m[c][g.face(c, {i, j, k})];
  return n;
}

Faces zero(const Grid& g) {
  Faces u;
  for (int c = 0; c < 3; ++c) u[c].assign(g.face_count(c), 0.0);
  return u;
}

}  // namespace

TEST_CASE("obstacle: the mould's staircase is the ring between inside and outside cells, and lifts on schedule") {
  const Grid g = quarter();
  const LiftedMould m = mould(0.1);  // 100 mm/s
  // At 20 mm cells the rows (and columns) whose centre is inside 76 mm are those at 10, 30, 50, 70 mm: each has one
  // inside-outside face, so a blocked layer has 4 x-faces and 4 y-faces, and no z-face.
  auto expect_layers = [&](double t, int first_blocked, int last_blocked) {
    const FaceMask f = m.faces(g, t);
    for (int k = 0; k < g.n[2]; ++k) {
      const long want = (k >= first_blocked && k <= last_blocked) ? 4 : 0;
      CHECK(blocked_in_layer(g, f, 0, k) == want);
      CHECK(blocked_in_layer(g, f, 1, k) == want);
    }
    CHECK(std::count(f[2].begin(), f[2].end(), 1) == 0);
  };
  // t = 0: edge at the plate, the shell up to the box's top: layers 0-7 (centres 10-150 mm) blocked.
  expect_layers(0.0, 0, 7);
  // t = 0.09 s: edge at 9 mm, below layer 0's centre (10 mm): still closed.
  expect_layers(0.09, 0, 7);
  // t = 0.11 s: edge at 11 mm: layer 0 open.
  expect_layers(0.11, 1, 7);
  // t = 1.0 s: edge at 100 mm: layers with centres 110, 130, 150 mm.
  expect_layers(1.0, 5, 7);
  CHECK(m.lower_edge(1.0) == doctest::Approx(0.1));
  // Layer k opens when the edge reaches its centre, (k + 1/2) h / V: 0.1 s for layer 0, 0.3 s for layer 1.
  CHECK(m.opening_time(g, 0) == doctest::Approx(0.1));
  CHECK(m.opening_time(g, 1) == doctest::Approx(0.3));
  CHECK(m.open_layers(g, 0.0999) == 0);
  CHECK(m.open_layers(g, 0.1 - 1e-13) == 1);  // a step landing an ulp short of the time still opens it
  CHECK(m.open_layers(g, 0.3) == 2);
  // Once the edge has left the box (160 mm) there is no wall at all.
  CHECK(!any_blocked(m.faces(g, 1.61)));
  // The instantaneous release: never a wall.
  CHECK(!any_blocked(mould(std::numeric_limits<double>::infinity()).faces(g, 0.0)));
  // Faces only ever open (a face blocked with flow through it would leave a divergence): at 5 mm cells, each
  // mask is inside the one before.
  const Grid fine = quarter(0.005);
  FaceMask before = m.faces(fine, 0.0);
  for (double t = 0.01; t < 1.7; t += 0.01) {
    const FaceMask now = m.faces(fine, t);
    for (int c = 0; c < 3; ++c)
      for (std::size_t f = 0; f < now[c].size(); ++f) REQUIRE((!now[c][f] || before[c][f]));
    before = now;
  }
  // Each blocked x-face separates an inside cell from an outside one.
  const FaceMask f = m.faces(g, 0.0);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 1; i < g.n[0]; ++i)
        CHECK(static_cast<bool>(f[0][g.face(0, {i, j, k})]) == (m.inside(g, i - 1, j) != m.inside(g, i, j)));
}

TEST_CASE("obstacle: the projection drops a blocked face (no flux, velocity untouched) and still meets its bound") {
  Grid g;
  g.n = {8, 6, 5};
  g.h = {0.1, 0.1, 0.1};
  g.bc[5].type = BoundaryType::open;
  Faces u = zero(g), rho;
  for (int c = 0; c < 3; ++c) {
    rho[c].assign(g.face_count(c), 1000.0);
    for (std::size_t f = 0; f < u[c].size(); ++f) u[c][f] = std::sin(0.37 * static_cast<double>(f) + c);
  }
  // A wall along x = 0.4 m over the lower three layers: x-faces I = 4, k < 3.
  FaceMask wall;
  wall[0].assign(g.face_count(0), 0);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < g.n[1]; ++j) wall[0][g.face(0, {4, j, k})] = 1;
  for (int c = 0; c < 3; ++c)
    for (std::size_t f = 0; f < u[c].size(); ++f)
      if (blocked(wall, c, static_cast<long>(f))) u[c][f] = 0.0;
  // The box's walls carry no normal velocity.
  g.for_each_face([&](int c, const std::array<int, 3>& q) {
    if (g.boundary_face(c, q[c]) && !(c == 2 && q[2] == g.n[2])) u[c][g.face(c, q)] = 0.0;
  });
  const Faces u_start = u;
  PressureOperator op(g);
  op.set_blocked(&wall);
  std::vector<double> p(g.cell_count(), 0.0);
  const ProjectionStats st = op.project(0.01, rho, u, p, 1e-10, 10000);
  CHECK(st.divergence_after / st.divergence_before <= 1e-10);
  for (long f = 0; f < g.face_count(0); ++f)
    if (wall[0][f]) CHECK(u[0][f] == 0.0);
  // Without the wall the same projection puts a flow through those faces.
  PressureOperator free_op(g);
  Faces v = u_start;
  std::vector<double> q(g.cell_count(), 0.0);
  free_op.project(0.01, rho, v, q, 1e-10, 10000);
  double through = 0.0;
  for (long f = 0; f < g.face_count(0); ++f)
    if (wall[0][f]) through = std::max(through, std::abs(v[0][f]));
  CHECK(through > 1e-3);
}

TEST_CASE("obstacle: the viscous step holds a blocked face at 0 and carries no shear across the wall (free slip)") {
  // Periodic along y and z, free-slip x sides, a full wall at x-faces I = 4: u_y = 1 m/s left of it, 0 right.
  Grid g;
  g.n = {8, 3, 3};
  g.h = {0.01, 0.01, 0.01};
  g.bc[0].type = g.bc[1].type = BoundaryType::free_slip;
  for (int s = 2; s < 6; ++s) g.bc[s].type = BoundaryType::periodic;
  Faces rho;
  for (int c = 0; c < 3; ++c) rho[c].assign(g.face_count(c), 1000.0);
  const std::vector<double> mu(g.cell_count(), 10.0);  // Pa s: the diffusion length over dt is ~10 cells
  auto start = [&] {
    Faces u = zero(g);
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 4; ++i) u[1][g.face(1, {i, j, k})] = 1.0;
    return u;
  };
  FaceMask wall;
  wall[0].assign(g.face_count(0), 0);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) wall[0][g.face(0, {4, j, k})] = 1;
  ViscousOperator op(g);
  Faces u = start();
  u[0][g.face(0, {4, 1, 1})] = 0.3;  // a blocked face's value is not used: it comes back 0
  op.set_blocked(&wall);
  op.solve(0.1, rho, mu, u, 1e-13, 10000);
  double left = 0.0, right = 0.0;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 4; ++i) left = std::max(left, std::abs(u[1][g.face(1, {i, j, k})] - 1.0));
      for (int i = 4; i < 8; ++i) right = std::max(right, std::abs(u[1][g.face(1, {i, j, k})]));
    }
  CHECK(left < 1e-12);
  CHECK(right < 1e-12);
  CHECK(u[0][g.face(0, {4, 1, 1})] == 0.0);
  // Without the wall the same step diffuses the shear layer across x = 0.04 m.
  Faces v = start();
  ViscousOperator free_op(g);
  free_op.solve(0.1, rho, mu, v, 1e-13, 10000);
  CHECK(std::abs(v[1][g.face(1, {4, 1, 1})]) > 0.1);
}

TEST_CASE("obstacle: a liquid column in the closed mould stays at rest (max |u| < 1e-8 m/s in 0.5 s) and falls without it") {
  omp_set_num_threads(1);
  const Grid g = quarter();
  const LiftedMould m = mould(0.0);  // never lifted
  Phases ph;
  ph.rho_paste = 1000.0;
  ph.paste = std::make_shared<Newtonian>(1e-3);  // water: nothing but the mould holds it
  std::vector<double> alpha(g.cell_count(), 0.0);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        if (m.inside(g, i, j)) alpha[g.cell(i, j, k)] = std::clamp((m.height - k * g.h[2]) / g.h[2], 0.0, 1.0);
  auto run = [&](bool held) {
    FlowSolver s(g, ph, FlowSettings{});
    s.set_alpha(alpha);
    if (held) s.set_blocked_faces(m.faces(g, 0.0));
    const double v0 = s.paste_volume();
    s.advance_to(0.5);
    if (held) CHECK(std::abs(s.paste_volume() - v0) / v0 <= 1e-12);  // free, the splash leaves by the open top
    return s.max_speed();
  };
  const double held = run(true), fallen = run(false);
  MESSAGE("closed mould: max |u| " << held << " m/s; without it " << fallen << " m/s");  // 1.2e-11, 2.6
  CHECK(held < 1e-8);
  CHECK(fallen > 0.1);
}
