// SPDX-License-Identifier: MIT
#include "model/fluid/flow_piston.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "model/coupling/piston.h"
#include "model/flow/solver.h"
#include "model/fluid/flow_coupling.h"
#include "model/scene.h"

namespace pastemix::model::fluid {

namespace {

constexpr double kWidth = 0.1, kHeight = 0.12, kDepth = 0.06, kBall = 0.01;  // m, as coupling/piston.cpp

// The scene: the box's paste as a flow region, the 27 spheres 1 cm above it (centres on a 1 cm lattice).
std::string piston_scene(const DemPistonSettings& s) {
  std::string text = fmt::format(
      "seed = 1\ntime_step = {}\nend_time = {}\n[domain]\nmin = [-0.01, -0.01, -0.01]\nmax = [0.11, 0.11, 0.13]\n"
      "[physics]\nrotation = false\n[contact]\nlaw = \"hertz_mindlin\"\n[[material]]\nname = \"rock\"\n"
      "density = 1e6\nyoungs_modulus = 4.68e7\npoisson_ratio = 0.19\n[[interaction]]\nmaterials = \"rock/rock\"\n"
      "restitution = 0.5\nfriction = 0.5\n"
      "[[fluid]]\nname = \"paste\"\nx = [0.0, {w}]\ny = [0.0, {w}]\nbottom = 0.0\nsurface = {d}\ndensity = 1843\n"
      "rheology = \"newtonian\"\nviscosity = {}\ncurve = \"stokes\"\ndynamics = \"flow\"\ncell = {}\ntop = {h}\n"
      "coupling_interval = {}\n",
      s.time_step, s.push_time + s.settle_time, s.eta, s.cell, s.coupling_interval, fmt::arg("w", kWidth),
      fmt::arg("d", kDepth), fmt::arg("h", kHeight));
  // 0.2 mm apart: the block is rigid by its driving, and no contact may act (a DEM step of 1 ms is five
  // Rayleigh times of these spheres; touching, the paste's slightly different forces on them made the contacts
  // blow up within 13 steps).
  const double pitch = 1.02 * kBall;
  for (int k = 0; k < 3; ++k)
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i)
        text += fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = {}\nposition = [{}, {}, {}]\n", 0.5 * kBall,
                            0.5 * kWidth + i * pitch, 0.5 * kWidth + j * pitch, kDepth + 0.01 + 0.5 * kBall + k * pitch);
  return text;
}

}  // namespace

DemPistonResult run_dem_piston(const DemPistonSettings& s) {
  const OneThread one;  // a validation case of one thread (flow_coupling.h)
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene = parse_scene(piston_scene(s), "piston (model/fluid/flow_piston.cpp)");
  World w = make_world(scene);
  const std::vector<Vec3> x0 = w.particles().x;
  const double dt = scene.config.dt;
  const long steps = std::lround((s.push_time + s.settle_time) / dt);
  const double v0 = w.flow()->paste_volume();
  for (long n = 1; n <= steps; ++n) {
    w.advance(1);
    // The driven block: back on its path at t = n dt, whatever the step did to it.
    const double t = static_cast<double>(n) * dt;
    const double drop = s.speed * std::min(t, s.push_time);
    const Vec3 v{0.0, 0.0, t < s.push_time ? -s.speed : 0.0};
    Particles& p = w.particles();
    for (std::size_t a = 0; a < p.size(); ++a) p.x[a] = x0[a] - Vec3{0.0, 0.0, drop}, p.v[a] = v;
  }
  const FlowCoupling& c = *w.flow();
  const flow::FlowSolver& f = c.solver();
  const flow::Grid& g = f.grid();
  // The solid where the flow last saw it (the last cycle's end): eps_s = 1 - eps_f.
  std::vector<double> eps_s(f.fluid_fraction());
  for (double& e : eps_s) e = 1.0 - e;
  DemPistonResult r;
  r.rise_expected = coupling::piston_level(g, eps_s, v0, kHeight) - kDepth;
  const coupling::FreeColumns free = coupling::free_columns(g, eps_s, f.fluid_fraction(), f.alpha());
  r.rise_measured = free.mean - kDepth;
  r.relative_error = std::abs(r.rise_measured - r.rise_expected) / r.rise_expected;
  r.surface_spread = free.spread;
  r.volume_error = std::abs(c.paste_volume() - v0) / v0;
  r.max_speed_end = f.max_speed();
  r.steps = w.steps(), r.cycles = c.cycles(), r.flow_steps = c.flow_steps();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace pastemix::model::fluid
