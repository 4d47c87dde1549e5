// SPDX-License-Identifier: MIT
#include "model/flow/step_guard.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "base/error.h"

namespace pastemix::flow {

namespace {

// Paste fraction below which a cell counts as air, above 1 minus which as paste.
constexpr double kPure = 0.01;

struct FaceAt {
  int c = 0;
  std::array<int, 3> q{};
  double speed = 0.0;  // m/s
};

std::array<int, 3> face_index(const Grid& g, int c, long f) {
  const auto fd = g.face_dims(c);
  return {static_cast<int>(f % fd[0]), static_cast<int>((f / fd[0]) % fd[1]),
          static_cast<int>(f / (static_cast<long>(fd[0]) * fd[1]))};
}

// Paste fraction of the cells before (side 0) and after (side 1) face q of component c; a side outside the box
// takes the inside cell's.
std::array<double, 2> sides(const Grid& g, const std::vector<double>& alpha, int c, const std::array<int, 3>& q) {
  std::array<int, 3> lo = q, hi = q;
  lo[c] = g.wrap_cell(c, q[c] - 1);
  hi[c] = g.wrap_cell(c, q[c]);
  if (lo[c] < 0) lo = hi;
  if (hi[c] < 0) hi = lo;
  return {alpha[g.cell(lo)], alpha[g.cell(hi)]};
}

// The face with the largest |u_c| / h_c (the one that sets the CFL step), and the fastest face with paste on
// both sides (alpha >= 1/2).
std::array<FaceAt, 2> fastest(const Grid& g, const Faces& u, const std::vector<double>& alpha) {
  FaceAt any, paste;
  double rate = -1.0;
  for (int c = 0; c < 3; ++c)
    for (long f = 0; f < static_cast<long>(u[c].size()); ++f) {
      const double s = std::abs(u[c][f]);
      if (s / g.h[c] > rate) {
        rate = s / g.h[c];
        any = {c, face_index(g, c, f), s};
      }
      if (s > paste.speed) {
        const auto q = face_index(g, c, f);
        const auto a = sides(g, alpha, c, q);
        if (std::min(a[0], a[1]) >= 0.5) paste = {c, q, s};
      }
    }
  return {any, paste};
}

// m: the centre of face f.
std::array<double, 3> face_centre(const Grid& g, const FaceAt& f) {
  std::array<double, 3> x{};
  for (int d = 0; d < 3; ++d) x[d] = g.origin[d] + (f.q[d] + (d == f.c ? 0.0 : 0.5)) * g.h[d];
  return x;
}

// What the fastest face is (f), from the paste fraction on its two sides (a) and the fastest paste face.
std::string cause(const Grid& g, const FaceAt& f, const std::array<double, 2>& a, double paste_speed) {
  const bool air = std::max(a[0], a[1]) < kPure, in_paste = std::min(a[0], a[1]) > 1.0 - kPure;
  std::string where = air ? "in the air" : in_paste ? "in the paste" : "at the interface";
  // A face of the open side: the flow through it is the pressure condition's, not a wall's (VALIDATION.md).
  if (g.boundary_face(f.c, f.q[f.c]) && g.side(f.c, f.q[f.c] == 0 ? 0 : 1).type == BoundaryType::open)
    where += fmt::format(", through the open {}_{} side", "xyz"[f.c], f.q[f.c] == 0 ? "lo" : "hi");
  // A runaway of the light phase drags the paste only later (VALIDATION.md: 30 m/s of air, 0.15 m/s of paste).
  if (!in_paste && paste_speed < 0.1 * f.speed) return "air velocity runaway " + where;
  return "velocity runaway " + where;
}

}  // namespace

ReferenceStep reference_step(const Grid& g, const StepControl& c) {
  const double h = std::min({g.h[0], g.h[1], g.h[2]});  // m
  ReferenceStep r{c.max_time_step, "step cap"};
  const double gmag = std::hypot(c.gravity[0], c.gravity[1], c.gravity[2]);  // m/s2
  if (gmag > 0.0 && std::sqrt(c.cfl * h / gmag) < r.dt) r = {std::sqrt(c.cfl * h / gmag), "gravity bound sqrt(cfl h / g)"};
  for (const Boundary& b : g.bc) {
    const double w = std::hypot(b.wall_velocity[0], b.wall_velocity[1], b.wall_velocity[2]);  // m/s
    if (w > 0.0 && c.cfl * h / w < r.dt) r = {c.cfl * h / w, "CFL step of the fastest wall"};
  }
  return r;
}

void require_time_step_above_floor(const Grid& g, const StepControl& c, const Faces& u, const std::vector<double>& alpha,
                                   double dt, double time, long step, const std::vector<double>* eps_f) {
  const ReferenceStep ref = reference_step(g, c);
  const double floor = ref.dt / kStepCollapse;
  if (dt >= floor) return;
  const auto [f, paste] = fastest(g, u, alpha);
  const auto a = sides(g, alpha, f.c, f.q);
  const std::array<double, 3> x = face_centre(g, f);
  throw RuntimeFailure(fmt::format(
      "flow: time step collapse at t = {:.9g} s (step {}): the CFL step {:.3g} s is below the floor {:.3g} s (1/{:g} "
      "of the {} {:.3g} s); fastest face: {} face ({}, {}, {}) at ({:.4g}, {:.4g}, {:.4g}) m, |u| = {:.4g} m/s, "
      "paste fraction {:.3f} | {:.3f} on its two sides; fastest paste face {:.3g} m/s: {}",
      time, step, dt, floor, kStepCollapse, ref.what, ref.dt, "xyz"[f.c], f.q[0], f.q[1], f.q[2], x[0], x[1], x[2],
      f.speed, a[0], a[1], paste.speed, cause(g, f, a, paste.speed)) +
      (eps_f && !eps_f->empty() ? fmt::format(" (fluid fraction {:.3f} | {:.3f} on its two sides)", sides(g, *eps_f, f.c, f.q)[0],
                                              sides(g, *eps_f, f.c, f.q)[1])
                                : std::string()));
}

namespace {

// The face with the largest |eps_f u| / h and that ratio (1/s).
std::pair<FaceAt, double> fastest_flux(const Grid& g, const Faces& u, const Faces& eps_face) {
  FaceAt f;
  double rate = -1.0;
  for (int c = 0; c < 3; ++c)
    for (long k = 0; k < static_cast<long>(u[c].size()); ++k) {
      const double r = std::abs(eps_face[c][k] * u[c][k]) / g.h[c];
      if (r > rate) rate = r, f = {c, face_index(g, c, k), std::abs(u[c][k])};
    }
  return {f, rate};
}

}  // namespace

double flux_cfl(const Grid& g, const Faces& u, const Faces& eps_face, double dt) {
  return fastest_flux(g, u, eps_face).second * dt;
}

std::string flux_cfl_diagnosis(const Grid& g, const Faces& u, const Faces& eps_face, const std::vector<double>& alpha,
                               const std::vector<double>& eps_old, const std::vector<double>& eps_new, double dt,
                               double time, long step) {
  const auto [f, rate] = fastest_flux(g, u, eps_face);
  const std::array<double, 3> x = face_centre(g, f);
  const auto a = sides(g, alpha, f.c, f.q), e0 = sides(g, eps_old, f.c, f.q), e1 = sides(g, eps_new, f.c, f.q);
  double change = 0.0;  // the largest |d eps_f| of a cell over the step
  for (std::size_t k = 0; k < eps_old.size(); ++k) change = std::max(change, std::abs(eps_new[k] - eps_old[k]));
  return fmt::format(
      "flow: the particles' volume change outruns the flow step at t = {:.9g} s (step {}): after the continuity "
      "projection the fluid's flux moves {:.3g} cells per sweep (bound {:g}) over the step {:.3g} s; fastest face: {} "
      "face ({}, {}, {}) at ({:.4g}, {:.4g}, {:.4g}) m, |u| = {:.4g} m/s, paste fraction {:.3f} | {:.3f}, fluid "
      "fraction {:.3f} -> {:.3f} | {:.3f} -> {:.3f} on its two sides; largest fluid-fraction change of a cell over "
      "the step {:.3f}",
      time, step, rate * dt, kMaxSweepCfl, dt, "xyz"[f.c], f.q[0], f.q[1], f.q[2], x[0], x[1], x[2], f.speed, a[0],
      a[1], e0[0], e1[0], e0[1], e1[1], change);
}

}  // namespace pastemix::flow
