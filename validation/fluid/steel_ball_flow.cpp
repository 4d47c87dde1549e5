// SPDX-License-Identifier: MIT
#include "validation/fluid/steel_ball_flow.h"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "base/units.h"
#include "model/fluid/buoyancy.h"
#include "model/fluid/flow_coupling.h"
#include "model/scene.h"
#include "validation/fluid/single_sphere.h"

namespace pastemix::validation {

using namespace model;

namespace {

constexpr double kG = 9.81;  // m/s2

// The at-rest harness's ball and mould, its fluid box resized to whole cells, with the flow keys.
std::string flow_ball_scene(const SphereRun& r, double end_time, double cell, const FlowBallSettings& f) {
  std::string s = single_sphere_scene(r, end_time);
  const double top = std::ceil((r.depth + f.air) / cell - 1e-9) * cell;  // m, whole cells from the bottom (z = 0)
  s += fmt::format("dynamics = \"flow\"\ncell = {:.17g}\ntop = {:.17g}\ncoupling_interval = {}\nregularisation = {:.17g}\n",
                   cell, top, f.coupling_interval, f.regularisation);
  return s;
}

}  // namespace

FlowBallDrop steel_ball_drop_flow(const SteelBallPaste& p, double d, double height, double eta_B,
                                  const FlowBallSettings& f) {
  const auto t0 = std::chrono::steady_clock::now();
  const double side = std::sqrt(units::pi / 4.0) * p.mould_diameter;  // m, the mould's equal-area square
  const double n = std::max(1.0, std::round(side / f.cell));
  FlowBallDrop out;
  out.cell = side / n;
  const SphereRun r = steel_ball_run(p, d, height, eta_B);  // its box: the square of side above
  const double t_fall = std::sqrt(2.0 * std::max(height, 0.0) / kG);  // s
  const double end = t_fall + f.settle;
  const Scene scene = parse_scene(flow_ball_scene(r, end, out.cell, f), "steel_ball_flow.toml");
  World w = make_world(scene);
  const long steps = std::lround(end / r.dt), rest_steps = std::lround(f.rest_time / r.dt);
  const double rad = 0.5 * d, volume = units::pi * d * d * d / 6.0;
  long slow = 0;
  bool entered = false;
  double v_entry = 0.0, t_entry = 0.0;
  auto& J = out.split;
  for (long k = 0; k < steps; ++k) {
    w.step();
    const auto& q = w.particles();
    if (!entered && q.x[0].z - rad < r.depth) entered = true, v_entry = q.v[0].z, t_entry = w.time();
    if (entered) {
      J.pressure += w.flow()->pressure_force(0).z * r.dt;
      J.hydrostatic += p.rho_paste * kG * fluid::submerged_volume(q.x[0].z, rad, r.depth) * r.dt;
    }
    if (q.x[0].z < rad + 1e-3) {
      out.drop.reached_bottom = true;
      break;
    }
    // Slow and below the surface: resting (the fall through air is never slow for this long).
    slow = std::sqrt(norm2(q.v[0])) < f.rest_speed && q.x[0].z < r.depth + rad ? slow + 1 : 0;
    if (slow >= rest_steps) {
      out.at_rest = true;
      break;
    }
  }
  w.check();
  const auto& q = w.particles();
  out.drop.distance = r.depth - (q.x[0].z - rad);
  out.drop.time_to_rest = w.time() - (out.at_rest ? f.rest_time : 0.0);
  out.speed_end = std::sqrt(norm2(q.v[0]));
  out.cycles = w.flow()->cycles();
  if (entered) {
    const double m = p.rho_ball * volume;
    J.momentum = m * (q.v[0].z - v_entry);
    J.gravity = -m * kG * (w.time() - t_entry);
    J.drag = J.momentum - J.gravity - J.pressure;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace pastemix::validation
