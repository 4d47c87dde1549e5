// SPDX-License-Identifier: MIT
#include "model/fluid/flow_raft.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "base/units.h"
#include "model/coupling/exchange.h"
#include "model/flow/bingham.h"
#include "model/flow/solver.h"
#include "model/fluid/flow_coupling.h"
#include "model/scene.h"

namespace pastemix::model::fluid {

namespace {

// m: 6 cm of paste, flow up to 12 cm; 5 mm spheres, 10 a side (5 cm).
constexpr double kHeight = 0.12, kDepth = 0.06, kBall = 0.005;
constexpr int kSide = 10;
constexpr double kPitch = kBall * (1.0 + 1e-6);  // m: touching within 5 nm (the scene refuses an overlap)
constexpr double kSeat = kBall;                   // m, the base's depth at the start (tops level with the surface)
constexpr double kGravity = 9.81;                 // m/s2, the scene's default

double raft_area() { return (kSide * kBall) * (kSide * kBall); }                              // m2, 25 cm2
double raft_volume() { return kSide * kSide * units::pi * kBall * kBall * kBall / 6.0; }  // m3

// The spheres' density that makes the raft's weight q A (kg/m3).
double raft_density(const RaftSettings& s) { return s.load * s.yield_stress * raft_area() / (kGravity * raft_volume()); }

std::string raft_scene(const RaftSettings& s, double density) {
  // The drag law's curve (published_4_19) does not read the yield number, so the spheres' density changes their
  // weight and inertia only, not their drag. Walls: the flow box's (no-slip sides and floor, open top).
  std::string text = fmt::format(
      "seed = 1\ntime_step = {}\nend_time = {}\n[domain]\nmin = [-0.01, -0.01, -0.01]\nmax = [{m}, {m}, 0.13]\n"
      "[physics]\nrotation = false\n[contact]\nlaw = \"hertz_mindlin\"\n[[material]]\nname = \"rock\"\n"
      "density = {}\nyoungs_modulus = 4.68e7\npoisson_ratio = 0.19\n[[interaction]]\nmaterials = \"rock/rock\"\n"
      "restitution = 0.5\nfriction = 0.5\n"
      "[[fluid]]\nname = \"paste\"\nx = [0.0, {w}]\ny = [0.0, {w}]\nbottom = 0.0\nsurface = {d}\ndensity = {}\n"
      "rheology = \"bingham\"\nyield_stress = {}\nplastic_viscosity = {}\ncurve = \"published_4_19\"\n"
      "regularisation = {}\ndynamics = \"flow\"\ncell = {}\ntop = {h}\ncoupling_interval = {}\n",
      s.time_step, s.time, density, s.paste_density, s.yield_stress, s.viscosity, s.regularisation, s.cell,
      s.coupling_interval, fmt::arg("w", s.box), fmt::arg("m", s.box + 0.01), fmt::arg("d", kDepth),
      fmt::arg("h", kHeight));
  if (s.flow_time_step > 0.0) text += fmt::format("flow_time_step = {}\n", s.flow_time_step);
  if (s.implicit_stick) text += "implicit_stick = true\n";
  const double x0 = 0.5 * s.box - 0.5 * (kSide - 1) * kPitch;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i)
      text += fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = {}\nposition = [{}, {}, {}]\n", 0.5 * kBall,
                          x0 + i * kPitch, x0 + j * kPitch, kDepth - kSeat + 0.5 * kBall);
  return text;
}

// The raft's shape: every sphere back on the layer's mean vertical displacement from its start, in x and y at
// its start. Returns that displacement (m, downwards negative).
//
// Only the positions. A velocity reset (to the layer's mean) is a constraint impulse the coupling cannot
// see: a sphere held off its paste's velocity sticks again, at every half kick, to the paste velocity frozen at
// the cycle's start, and the sub-cycle hands the paste the summed stick impulses, up to m |v - W u| per half
// kick (100 per 5 ms cycle), against its stale velocity once per cycle (coupled_flow.h: explicit over the
// interval). Every mode of the paste under the raft that the reset holds then grows by overshoot:
//  - all three components reset (the draft, which also zeroed the horizontal velocities): a swirl of the paste
//    about the raft's axis (a mode whose mean velocity is zero) grew from 1e-8 m/s at 0.05 s to 14 mm/s at
//    0.4 s (5 mm cells, q = 3, the raft on the surface as the draft set it), and took the yield part's
//    strength with it (the part is bounded in |v - W u|): the raft slid through the paste at 7 mm/s at 1 s;
//  - the vertical component only: a tilt of the paste's vertical velocity under the raft changed sign every
//    cycle and grew fourfold per cycle from 0.06 s to +-18 mm/s (1 cm cells, seated, q = 7): the raft slid
//    7.2 mm through the paste where it holds at 0.93 mm (the last test of tests/model/fluid/flow_raft_test.cpp).
// With the positions alone the velocities stay the engine's (each sphere's momentum exchange with the paste is
// exact) and both modes stay at round-off (swirl below 1e-6 m/s); the raft's mean velocity is still its rate of
// settlement.
double keep_shape(Particles& p, const std::vector<Vec3>& x0) {
  double dz = 0.0;
  for (std::size_t a = 0; a < p.size(); ++a) dz += p.x[a].z - x0[a].z;
  dz /= static_cast<double>(p.size());
  for (std::size_t a = 0; a < p.size(); ++a) p.x[a] = {x0[a].x, x0[a].y, x0[a].z + dz};
  return dz;
}

double mean_vz(const Particles& p) {  // m/s
  double vz = 0.0;
  for (const Vec3& v : p.v) vz += v.z;
  return vz / static_cast<double>(p.size());
}

RaftSample sample(const World& w, double box, double t, double penetration) {
  const flow::FlowSolver& f = w.flow()->solver();
  const Particles& p = w.particles();
  std::vector<std::array<double, 3>> x;
  std::vector<double> d, m, share;
  for (std::size_t a = 0; a < p.size(); ++a)
    x.push_back({p.x[a].x, p.x[a].y, p.x[a].z}), d.push_back(2.0 * p.radius[a]), m.push_back(p.mass[a]);
  const std::vector<double> none(p.size(), 0.0);
  const flow::Faces mask = flow::face_means(f.grid(), f.alpha());
  const coupling::Exchange ex(f.grid(), w.flow()->region().kernel_width);
  const auto u = ex.fluid_velocity({x, d, m, none, none}, f.velocity(), f.fluid_mass(), &mask, share);
  RaftSample s{t, penetration, -mean_vz(p), flow::paste_speed(f)};
  for (std::size_t a = 0; a < p.size(); ++a) {
    s.share += share[a], s.slip += u[a][2] - p.v[a].z;
    const double rx = p.x[a].x - 0.5 * box, ry = p.x[a].y - 0.5 * box;  // m, from the raft's axis
    s.swirl += (rx * u[a][1] - ry * u[a][0]) / std::hypot(rx, ry);
  }
  const double n = static_cast<double>(p.size());
  s.share /= n, s.slip /= n, s.swirl /= n;
  return s;
}

void check(const RaftSettings& s, const RaftResult& r) {
  if (!(r.density > s.paste_density))
    throw std::invalid_argument(fmt::format("raft: a load of {:g} tau_y makes spheres of {:.0f} kg/m3, not heavier "
                                            "than the paste ({:g} kg/m3)", s.load, r.density, s.paste_density));
  if (!(s.time > s.speed_window && s.speed_window > 0.0))
    throw std::invalid_argument(fmt::format("raft: {:g} s simulated, not longer than the end window {:g} s", s.time,
                                            s.speed_window));
}

// The run's end: the settlement, its speed over the last window, the net pressure, whether it went.
void conclude(const RaftSettings& s, double sink, double sink_window, double window_time, RaftResult& r) {
  r.penetration = -sink;
  r.speed_end = (sink_window - sink) / window_time;
  r.net_load = s.load - s.paste_density * kGravity * (kSeat + r.penetration) / s.yield_stress;
  r.punched = r.penetration > s.fail_settlement || r.speed_end > s.hold_speed;
}

}  // namespace

RaftResult run_raft(const RaftSettings& s) {
  RaftResult r;
  r.density = raft_density(s);
  r.weight = s.load * s.yield_stress * raft_area();
  check(s, r);
  const OneThread one;  // a validation case of one thread (flow_coupling.h)
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene = parse_scene(raft_scene(s, r.density), "raft (model/fluid/flow_raft.cpp)");
  World w = make_world(scene);
  const std::vector<Vec3> x0 = w.particles().x;
  const double dt = scene.config.dt;  // s
  const long steps = std::lround(s.time / dt), window = std::lround(s.speed_window / dt);
  const long trace = s.trace_every > 0.0 ? std::max(1L, std::lround(s.trace_every / dt)) : 0;
  double sink = 0.0, sink_window = 0.0;  // m (downwards negative): now, and at the window's start
  for (long n = 1; n <= steps; ++n) {
    w.advance(1);
    sink = keep_shape(w.particles(), x0);
    r.max_speed = std::max(r.max_speed, -mean_vz(w.particles()));
    if (n == steps - window) sink_window = sink;
    const bool cycle = n % s.coupling_interval == 0, traced = trace > 0 && n % trace == 0;
    if (!cycle && !traced) continue;
    const RaftSample at = sample(w, s.box, static_cast<double>(n) * dt, -sink);
    if (cycle) r.slid += at.slip * static_cast<double>(s.coupling_interval) * dt;
    if (traced) r.trace.push_back(at);
  }
  conclude(s, sink, sink_window, static_cast<double>(window) * dt, r);
  r.cycles = w.flow()->cycles();
  r.flow_steps = w.flow()->flow_steps();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace pastemix::model::fluid
