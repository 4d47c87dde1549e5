// SPDX-License-Identifier: MIT
#include "model/fluid/flow_raft.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "base/units.h"
#include "model/fluid/flow_coupling.h"
#include "model/scene.h"

namespace pastemix::model::fluid {

namespace {

// m: a 10 x 10 cm box of 6 cm of paste (the raft's 5 cm width leaves 2.5 cm of paste each side; a footing's
// failure wedge reaches ~1 width out, so the walls stiffen it a little), flow up to 12 cm.
constexpr double kWidth = 0.1, kHeight = 0.12, kDepth = 0.06, kBall = 0.005;
constexpr int kSide = 10;  // spheres per side: 5 cm
constexpr double kRock = 2700.0;  // kg/m3

std::string raft_scene(const RaftSettings& s) {
  std::string text = fmt::format(
      "seed = 1\ntime_step = {}\nend_time = {}\n[domain]\nmin = [-0.01, -0.01, -0.01]\nmax = [0.11, 0.11, 0.13]\n"
      "[physics]\nrotation = false\n[contact]\nlaw = \"hertz_mindlin\"\n[[material]]\nname = \"rock\"\n"
      "density = {}\nyoungs_modulus = 4.68e7\npoisson_ratio = 0.19\n[[interaction]]\nmaterials = \"rock/rock\"\n"
      "restitution = 0.5\nfriction = 0.5\n"
      "[[fluid]]\nname = \"paste\"\nx = [0.0, {w}]\ny = [0.0, {w}]\nbottom = 0.0\nsurface = {d}\ndensity = 1789.4\n"
      "rheology = \"bingham\"\nyield_stress = {}\nplastic_viscosity = {}\ncurve = \"published_4_19\"\n"
      "regularisation = {}\ndynamics = \"flow\"\ncell = {}\ntop = {h}\ncoupling_interval = {}\n",
      s.time_step, s.time, kRock, s.yield_stress, s.viscosity, s.regularisation, s.cell, s.coupling_interval,
      fmt::arg("w", kWidth), fmt::arg("d", kDepth), fmt::arg("h", kHeight));
  // Touching: centres one diameter apart (zero overlap, so no contact force), bottoms on the surface.
  const double x0 = 0.5 * kWidth - 0.5 * (kSide - 1) * kBall;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i)
      text += fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = {}\nposition = [{}, {}, {}]\n", 0.5 * kBall,
                          x0 + i * kBall, x0 + j * kBall, kDepth + 0.5 * kBall);
  return text;
}

}  // namespace

RaftResult run_raft(const RaftSettings& s) {
  const OneThread one;
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene = parse_scene(raft_scene(s), "raft (model/fluid/flow_raft.cpp)");
  World w = make_world(scene);
  const std::vector<Vec3> x0 = w.particles().x;
  const double dt = scene.config.dt, g = 9.81;  // s, m/s2
  const double area = (kSide * kBall) * (kSide * kBall);  // m2
  double mass = 0.0;  // kg, the raft
  for (double m : w.particles().mass) mass += m;
  RaftResult r;
  r.force = s.load * s.yield_stress * area - mass * g;  // N, on top of the raft's weight
  const long steps = std::lround(s.time / dt);
  double sink = 0.0, vz = 0.0;  // m, m/s (downwards negative)
  for (long n = 1; n <= steps; ++n) {
    w.advance(1);
    Particles& p = w.particles();
    // The rigid raft: the layer's mean vertical velocity (the paste's and gravity's kicks), plus the load's.
    double mean = 0.0;
    for (std::size_t a = 0; a < p.size(); ++a) mean += p.v[a].z;
    vz = mean / static_cast<double>(p.size()) - r.force * dt / mass;
    sink += vz * dt;
    for (std::size_t a = 0; a < p.size(); ++a) p.x[a] = x0[a] + Vec3{0.0, 0.0, sink}, p.v[a] = Vec3{0.0, 0.0, vz};
  }
  r.penetration = -sink;
  r.speed_end = -vz;
  r.punched = r.penetration > 0.5 * kSide * kBall || r.speed_end > s.hold_speed;
  r.cycles = w.flow()->cycles();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace pastemix::model::fluid
