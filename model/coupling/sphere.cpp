// SPDX-License-Identifier: MIT
#include "model/coupling/sphere.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "model/coupling/coupled_flow.h"
#include "model/flow/bingham.h"

namespace pastemix::coupling {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;  // m/s2

// The velocity factor of a simple cubic array at solid fraction phi (Sangani & Acrivos 1982).
double hasimoto(double phi) {
  const double c = std::cbrt(phi);
  return 1.0 - 1.7601 * c + phi - 1.5593 * phi * phi + 3.9799 * std::pow(c, 8) - 3.0734 * std::pow(c, 10);
}

// Dedegil's drag on the Stokes curve (fluid/laws' Bingham-Dedegil with Cd = 24/Re'), written out: the case
// must not depend on the engine's law tables, and the coupling's drag test checks the law's own split against
// this closed form. D(s) = (pi^2/4 + 3 pi) d^2 tau_y + 3 pi eta d s.
SphereDrag stokes_dedegil(double d, double tau_y, double eta, double rho_f) {
  SphereDrag law;
  const double rest = (kPi * kPi / 4.0 + 3.0 * kPi) * d * d * tau_y, slope = 3.0 * kPi * eta * d;
  law.magnitude = [=](double s) { return rest + slope * s; };
  law.reynolds = [=](double s) { return rho_f * s * s / (tau_y + eta * s / d); };
  law.rest = rest;
  return law;
}

}  // namespace

SphereResult run_sphere(const SphereSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  const double d = s.diameter, h = s.cell_over_diameter * d;
  const int n = static_cast<int>(std::lround(s.box_over_diameter / s.cell_over_diameter));
  if (n < 2 || std::abs(n * h - s.box_over_diameter * d) > 1e-9 * d)
    throw std::invalid_argument("sphere: the box must be a whole number (>= 2) of cells");
  flow::Grid g;
  g.n = {n, n, n};
  g.h = {h, h, h};
  for (auto& b : g.bc) b.type = flow::BoundaryType::periodic;
  const double L = n * h, V_box = L * L * L, V_p = kPi * d * d * d / 6.0;
  const double m_p = s.rho_particle * V_p, M = m_p + s.rho_fluid * (V_box - V_p);
  const double G = M * kG / V_box;  // Pa/m, the mean pressure gradient (upward) that holds the mixture
  const double tau_y = s.yield_number * kG * d * (s.rho_particle - s.rho_fluid);
  flow::Phases ph;
  ph.rho_paste = s.rho_fluid;
  if (tau_y > 0.0) ph.paste = std::make_shared<flow::Bingham>(tau_y, s.viscosity, s.regularisation);
  else ph.paste = std::make_shared<flow::Newtonian>(s.viscosity);
  flow::FlowSettings fs;
  fs.gravity = {0.0, 0.0, -kG + G / s.rho_fluid};
  fs.max_time_step = s.coupling_interval;
  flow::FlowSolver flow(g, ph, fs);
  flow.add_paste_box({0, 0, 0}, {L, L, L});
  CouplingSettings cs;
  cs.width_factor = s.width_factor;
  cs.closure.disturbance = s.disturbance;
  cs.gravity = {0.0, 0.0, -kG};
  CoupledFlow cf(flow, cs);
  CoupledParticles p;
  p.x = {{s.start[0] * L, s.start[1] * L, s.start[2] * L}};
  p.v = {{0.0, 0.0, 0.0}};
  p.d = {d};
  p.m = {m_p};
  p.drag = {stokes_dedegil(d, tau_y, s.viscosity, s.rho_fluid)};
  cf.start(p);
  const CoupledFlow::ExtraForce pressure = [&](std::size_t, const CoupledParticles&) {
    return std::array<double, 3>{0.0, 0.0, V_p * G};  // -V_p grad p of the mean gradient
  };
  SphereResult r;
  r.cells = static_cast<int>(g.cell_count());
  const double F = V_p * (s.rho_particle - M / V_box) * kG;  // N, the drag at the terminal state
  r.stokes = F / (3.0 * kPi * s.viscosity * d);
  r.reference = r.stokes * hasimoto(V_p / V_box);
  const double nu = s.viscosity / s.rho_fluid, tau_p = m_p / (3.0 * kPi * s.viscosity * d);  // m2/s, s
  const double settle = s.settle_time > 0.0 ? s.settle_time : 3.0 * std::max(tau_p, L * L / (4.0 * kPi * kPi * nu));
  const double window = tau_y > 0.0 ? settle : h / r.reference;
  const int settle_cycles = static_cast<int>(std::ceil(settle / s.coupling_interval));
  const int cycles = settle_cycles + static_cast<int>(std::ceil(window / s.coupling_interval));
  double sum = 0.0, z0 = 0.0, pressure_sum = 0.0;
  r.slip_min = INFINITY, r.slip_max = -INFINITY;
  const double fluid_mass = M - m_p;
  double z_unwrapped = p.x[0][2];
  for (int k = 1; k <= cycles; ++k) {
    const double z_before = p.x[0][2];
    cf.cycle(p, 1, s.coupling_interval, pressure);
    double dz = p.x[0][2] - z_before;
    if (dz > 0.5 * L) dz -= L;  // a wrap through the bottom
    z_unwrapped += dz;
    if (k == settle_cycles) z0 = z_unwrapped;
    if (k <= settle_cycles) continue;
    const double fluid_mean = cf.fluid_momentum()[2] / fluid_mass;
    const double slip = -(p.v[0][2] - fluid_mean);  // m/s, downward positive
    r.max_speed_late = std::max(r.max_speed_late, std::hypot(p.v[0][0], p.v[0][1], p.v[0][2]));
    sum += slip;
    pressure_sum += cf.pending_impulse()[0][2] / s.coupling_interval;  // N, upward positive
    r.slip_min = std::min(r.slip_min, slip);
    r.slip_max = std::max(r.slip_max, slip);
  }
  r.cycles = cycles;
  r.velocity = sum / (cycles - settle_cycles);
  r.travel = z0 - z_unwrapped;
  r.pressure_share = pressure_sum / (cycles - settle_cycles) / F;
  r.error = r.reference > 0.0 ? r.velocity / r.reference - 1.0 : 0.0;
  r.reynolds = s.rho_fluid * std::abs(r.velocity) * d / s.viscosity;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace pastemix::coupling
