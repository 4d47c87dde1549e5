// SPDX-License-Identifier: MIT
#include "model/coupling/piston.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include "model/coupling/kernel.h"
#include "model/flow/solver.h"

namespace pastemix::coupling {

namespace {

constexpr double kWidth = 0.1, kHeight = 0.12;  // m, the box
constexpr double kDepth = 0.06;                 // m, the paste at the start
constexpr double kBall = 0.01;                  // m, the glued spheres

// The block's sphere centres when it has gone down by `drop` (m).
std::vector<std::array<double, 3>> block(double drop) {
  std::vector<std::array<double, 3>> x;
  const double bottom = kDepth + 0.01 - drop;
  for (int k = 0; k < 3; ++k)
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i)
        x.push_back({0.5 * kWidth + i * kBall, 0.5 * kWidth + j * kBall, bottom + (k + 0.5) * kBall});
  return x;
}

}  // namespace

// The right side grows slower than the left (eps_s < 1): one root.
double piston_level(const flow::Grid& g, const std::vector<double>& eps_s, double paste_volume, double height) {
  const double area = g.n[0] * g.h[0] * g.n[1] * g.h[1];
  auto excess = [&](double H) {
    double solid = 0.0;
    for (int k = 0; k < g.n[2]; ++k) {
      const double share = std::clamp((H - g.origin[2] - k * g.h[2]) / g.h[2], 0.0, 1.0);
      if (share == 0.0) break;
      for (int j = 0; j < g.n[1]; ++j)
        for (int i = 0; i < g.n[0]; ++i) solid += eps_s[g.cell(i, j, k)] * share * g.cell_volume();
    }
    return area * H - paste_volume - solid;
  };
  double lo = 0.0, hi = height;
  for (int it = 0; it < 200 && hi - lo > 1e-14; ++it) (excess(0.5 * (lo + hi)) > 0.0 ? hi : lo) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

FreeColumns free_columns(const flow::Grid& g, const std::vector<double>& eps_s, const std::vector<double>& eps_f,
                         const std::vector<double>& alpha) {
  double sum = 0.0, lo = 1e9, hi = -1e9;
  FreeColumns out;
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i) {
      double column = 0.0, solid = 0.0;
      for (int k = 0; k < g.n[2]; ++k) {
        column += eps_f[g.cell(i, j, k)] * alpha[g.cell(i, j, k)] * g.h[2];
        solid += eps_s[g.cell(i, j, k)];
      }
      if (solid != 0.0) continue;
      sum += column;
      lo = std::min(lo, column);
      hi = std::max(hi, column);
      ++out.count;
    }
  out.mean = sum / out.count;
  out.spread = hi - lo;
  return out;
}

PistonResult run_piston(const PistonSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  flow::Grid g;
  const int nx = static_cast<int>(std::lround(kWidth / s.cell)), nz = static_cast<int>(std::lround(kHeight / s.cell));
  g.n = {nx, nx, nz};
  g.h = {kWidth / nx, kWidth / nx, kHeight / nz};
  g.bc[5].type = flow::BoundaryType::open;
  flow::Phases ph;
  ph.rho_paste = 1843.0;
  ph.paste = std::make_shared<flow::Newtonian>(s.eta);
  flow::FlowSettings fs;
  fs.max_time_step = s.max_time_step;
  flow::FlowSolver solver(g, ph, fs);
  solver.add_paste_box({0, 0, 0}, {kWidth, kWidth, kDepth});

  const std::vector<double> diameters(27, kBall);
  auto solid_at = [&](double t) { return solid_fraction(g, block(s.speed * std::min(t, s.push_time)), diameters, s.width_factor); };
  auto fluid = [](std::vector<double> eps_s) {
    for (double& e : eps_s) e = 1.0 - e;
    return eps_s;
  };
  solver.set_fluid_fraction(fluid(solid_at(0.0)));
  const double v0 = solver.paste_volume();
  PistonResult r;
  r.alpha_min = 1.0;
  const double end = s.push_time + s.settle_time;
  while (solver.time() < end * (1.0 - 1e-14)) {
    const double t = solver.time();
    double dt = solver.next_time_step();
    if (t < s.push_time && t + dt > s.push_time) dt = s.push_time - t;  // the block stops on a step
    if (t + dt > end) dt = end - t;
    solver.set_next_fluid_fraction(fluid(solid_at(t + dt)), s.with_rate);
    const flow::StepStats st = solver.step(dt);
    r.alpha_min = std::min(r.alpha_min, st.advection.alpha_min);
    r.alpha_max = std::max(r.alpha_max, st.advection.alpha_max);
    const auto& pr = st.projection;
    if (pr.divergence_before > 0.0)
      r.max_relative_divergence = std::max(r.max_relative_divergence, pr.divergence_after / pr.divergence_before);
    ++r.steps;
  }
  const std::vector<double> eps_s = solid_at(end);
  r.rise_expected = piston_level(g, eps_s, v0, kHeight) - kDepth;
  const FreeColumns free = free_columns(g, eps_s, solver.fluid_fraction(), solver.alpha());
  r.rise_measured = free.mean - kDepth;
  r.relative_error = std::abs(r.rise_measured - r.rise_expected) / r.rise_expected;
  r.surface_spread = free.spread;
  r.volume_error = std::abs(solver.paste_volume() - v0) / v0;
  r.max_speed_end = solver.max_speed();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace pastemix::coupling
