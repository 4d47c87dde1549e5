// SPDX-License-Identifier: MIT
#include "model/coupling/hindered.h"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>

#include "model/coupling/coupled_flow.h"
#include "model/coupling/drag.h"
#include "model/coupling/exchange.h"
#include "model/coupling/kernel.h"
#include "model/coupling/mobility.h"

namespace pastemix::coupling {

namespace {

// Means over the particles now: the vertical fluid velocity at them (W u, m/s), the drag coefficient the
// coupling gives them (kg/s), the resolved pressure force (N, upward; the pending impulse over the interval).
struct Parts {
  double fluid = 0.0, beta = 0.0, pressure = 0.0;
};

Parts parts(const CoupledFlow& cf, const CoupledParticles& p, const Exchange& ex, const SphereDrag& law,
            const CouplingSettings& cs, double interval) {
  const flow::Grid& g = cf.flow().grid();
  const std::vector<double> none(p.size(), 0.0), &eps_f = cf.flow().fluid_fraction();
  std::vector<double> share;
  const auto at = ex.fluid_velocity({p.x, p.d, p.m, none, none}, cf.flow().velocity(), cf.flow().fluid_mass(), nullptr, share);
  Parts q;
  for (std::size_t i = 0; i < p.size(); ++i) {
    q.fluid += at[i][2];
    q.pressure += cf.pending_impulse()[i][2] / interval;
    const Stencil st = stencil(g, p.x[i], p.d[i], cs.width_factor);
    const double e = std::min(1.0, interpolate(g, st, eps_f) + own_solid_fraction(g, st, p.d[i]));
    const std::array<double, 3> w{p.v[i][0] - at[i][0], p.v[i][1] - at[i][1], p.v[i][2] - at[i][2]};
    const double slip = std::hypot(w[0], w[1], w[2]);
    const double mu = interpolate(g, st, cf.flow().viscosity());
    q.beta += drag_coefficients(law, p.d[i], cs.width_factor, slip, e, mu, g.h, cs.closure,
                                own_pressure_share(g, st, p.d[i]),
                                disturbance_mobility(g, st, p.d[i], cs.width_factor, mu, w)).beta;
  }
  const double n = static_cast<double>(p.size());
  return {q.fluid / n, q.beta / n, q.pressure / n};
}

}  // namespace

HinderedResult run_hindered(const HinderedSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  constexpr double kG = 9.81, kPi = std::numbers::pi;  // m/s2
  const double d = s.diameter, mu = s.viscosity;
  flow::Grid g;
  g.n = {s.cells, s.cells, s.cells};
  g.h = {s.cell, s.cell, s.cell};
  for (auto& b : g.bc) b.type = flow::BoundaryType::periodic;
  const double L = s.cells * s.cell, V_box = L * L * L, V_p = kPi * d * d * d / 6.0;
  const int n = static_cast<int>(std::lround(s.solid_fraction * V_box / V_p));
  const double m_p = s.rho_particle * V_p, M = n * m_p + s.rho_fluid * (V_box - n * V_p);
  const double G = M * kG / V_box;  // Pa/m, the mean gradient that holds the mixture
  flow::Phases ph;
  ph.rho_paste = s.rho_fluid;
  ph.paste = std::make_shared<flow::Newtonian>(mu);
  flow::FlowSettings fs;
  fs.gravity = {0.0, 0.0, -kG + G / s.rho_fluid};
  fs.max_time_step = s.coupling_interval;
  flow::FlowSolver flow(g, ph, fs);
  flow.add_paste_box({0, 0, 0}, {L, L, L});
  CouplingSettings cs;
  cs.closure.voidage = s.voidage;
  cs.closure.disturbance = s.disturbance;
  cs.width_factor = s.width_factor;
  cs.gravity = {0.0, 0.0, -kG};
  CoupledFlow cf(flow, cs);
  SphereDrag stokes;  // Stokes's drag: the law the reference's v_t is of
  stokes.magnitude = [=](double v) { return 3.0 * kPi * mu * d * v; };
  stokes.reynolds = [=, rho = s.rho_fluid](double v) { return rho * v * d / mu; };
  CoupledParticles p;
  std::mt19937_64 rng(s.seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    p.x.push_back({L * U(rng), L * U(rng), L * U(rng)});
    p.v.push_back({0.0, 0.0, 0.0});
    p.d.push_back(d);
    p.m.push_back(m_p);
    p.drag.push_back(stokes);
  }
  cf.start(p);
  const CoupledFlow::ExtraForce pressure = [&](std::size_t, const CoupledParticles&) {
    return std::array<double, 3>{0.0, 0.0, V_p * G};
  };
  const double v_t = (s.rho_particle - s.rho_fluid) * kG * d * d / (18.0 * mu), eps = 1.0 - s.solid_fraction;
  double sum = 0.0, local = 0.0, carried = 0.0, beta_sum = 0.0, resolved = 0.0;
  int count = 0;
  const Exchange ex(g, s.width_factor);
  const double F = V_p * (s.rho_particle - M / V_box) * kG;  // N, the mean drag at the terminal state
  for (int k = 1; k <= s.cycles; ++k) {
    cf.cycle(p, 1, s.coupling_interval, pressure);
    if (2 * k <= s.cycles) continue;
    double vp = 0.0;
    for (const auto& v : p.v) vp += v[2];
    vp /= n;
    const double uf = cf.fluid_momentum()[2] / (M - n * m_p);
    sum += -eps * (vp - uf);  // m/s, downward positive
    ++count;
    const Parts q = parts(cf, p, ex, stokes, cs, s.coupling_interval);
    local += -eps * (vp - q.fluid);
    carried += -(q.fluid - uf);
    beta_sum += q.beta / drag_coefficients(stokes, d, s.width_factor, v_t, eps, mu, g.h, cs.closure, 0.0).beta;
    resolved += q.pressure / F;
  }
  HinderedResult r;
  r.spheres = n;
  r.ratio = sum / count / v_t;
  r.exponent = std::log(r.ratio) / std::log(eps);
  r.reference = std::pow(eps, 4.65);
  r.local_slip = local / count / v_t;
  r.carried = carried / count / v_t;
  r.beta_ratio = beta_sum / count;
  r.pressure_share = resolved / count;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace pastemix::coupling
