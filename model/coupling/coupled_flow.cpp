// SPDX-License-Identifier: MIT
#include "model/coupling/coupled_flow.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "base/error.h"
#include "model/coupling/mobility.h"
#include "model/flow/step_guard.h"

namespace pastemix::coupling {

namespace {
using Vec = std::array<double, 3>;

double sphere_volume(double d) { return std::numbers::pi * d * d * d / 6.0; }  // m3

// Re-splits of one flow interval for a flux that outran its sub-step (flow::FluxStepTooLong): each makes the
// sub-steps at least 0.5 / 0.3 times shorter, so 8 reach 1/60 of them; a flux still too fast after that is not
// a matter of the step, and its diagnosis ends the run.
constexpr int kMaxResplits = 8;

// A face of component c on one of the box's walls or open sides (its impulse is not a pressure gradient).
bool box_face(const flow::Grid& g, int c, const std::array<int, 3>& q) { return g.boundary_face(c, q[c]); }
}  // namespace

CoupledFlow::CoupledFlow(flow::FlowSolver& flow, CouplingSettings settings)
    : flow_(flow), s_(settings), exchange_(flow.grid(), settings.width_factor) {}

const CoupledFlow::Weights& CoupledFlow::weights_at(std::span<const Vec> x, std::span<const double> d) const {
  ++clock_;
  for (Weights& w : weights_)
    if (w.x.size() == x.size() && w.d.size() == d.size() && std::equal(x.begin(), x.end(), w.x.begin()) &&
        std::equal(d.begin(), d.end(), w.d.begin())) {
      w.used = clock_;
      return w;
    }
  Weights& w = weights_[0].used <= weights_[1].used ? weights_[0] : weights_[1];  // the one used longest ago
  w.x.assign(x.begin(), x.end());
  w.d.assign(d.begin(), d.end());
  w.stencil.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) w.stencil[i] = stencil(flow_.grid(), x[i], d[i], s_.width_factor);
  w.faces = exchange_.face_weights(w.stencil);
  w.used = clock_;
  return w;
}

std::vector<double> CoupledFlow::fluid_fraction(const CoupledParticles& p) const {
  std::vector<double> eps = solid_fraction(flow_.grid(), weights_at(p.x, p.d).stencil, p.d);
  for (std::size_t c = 0; c < eps.size(); ++c) {
    eps[c] = 1.0 - eps[c];
    if (!(eps[c] > 0.0)) {
      const flow::Grid& g = flow_.grid();
      const auto [i, j, k] = g.cell_at(static_cast<long>(c));
      throw RuntimeFailure(fmt::format(
          "coupling: the particles fill cell {} ({}, {}, {}) at ({:.4g}, {:.4g}, {:.4g}) m (fluid fraction {:.4g}) "
          "at t = {:.9g} s of the flow: the kernel width c = {} is too narrow for this packing", c, i, j, k,
          g.origin[0] + (i + 0.5) * g.h[0], g.origin[1] + (j + 0.5) * g.h[1], g.origin[2] + (k + 0.5) * g.h[2], eps[c],
          flow_.time(), s_.width_factor));
    }
  }
  return eps;
}

void CoupledFlow::start(const CoupledParticles& p) {
  flow_.set_fluid_fraction(fluid_fraction(p));
  x_flow_ = p.x;
  pending_.assign(p.size(), {0.0, 0.0, 0.0});
  pending_interval_ = 0.0;
  drag_.assign(p.size(), {0.0, 0.0, 0.0});
}

Vec CoupledFlow::face_mean(const Stencil& s, const flow::Faces& f) const {
  const flow::Grid& g = flow_.grid();
  Vec out{};
  if (s.empty()) return out;
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0, weight = 0.0;
    for (const auto& [k, wk] : s.axis[2])
      for (const auto& [j, wj] : s.axis[1])
        for (const auto& [i, wi] : s.axis[0]) {
          const std::array<int, 3> q{i, j, k};
          std::array<int, 3> hi = q;
          hi[c] = g.periodic(c) ? (q[c] + 1) % g.n[c] : q[c] + 1;
          const double half = 0.5 * wi * wj * wk;
          for (const auto& face : {q, hi}) {
            if (box_face(g, c, face)) continue;
            sum += half * f[c][g.face(c, face)];
            weight += half;
          }
        }
    out[c] = weight > 0.0 ? sum / weight : 0.0;
  }
  return out;
}

std::array<double, 3> CoupledFlow::fluid_momentum() const {
  const flow::Faces m = flow_.fluid_mass();
  Vec out{};
  for (int c = 0; c < 3; ++c)
    for (std::size_t f = 0; f < m[c].size(); ++f) out[c] += m[c][f] * flow_.velocity()[c][f];
  return out;
}

CoupledFlow::Start CoupledFlow::drag_at_start(const CoupledParticles& p) const {
  const flow::Grid& g = flow_.grid();
  const std::size_t n = p.size();
  const std::vector<double> none(n, 0.0);
  // The fluid as it is now (weights at the cycle's start): u_p, the paste share, and the drag coefficients at
  // the slip v - W u^n and the fluid fraction the others leave (drag.h), frozen over the sub-cycle.
  Start s0;
  s0.mass = flow_.fluid_mass();
  const flow::Faces& mass0 = s0.mass;
  s0.mask = flow::face_means(g, flow_.alpha());
  const flow::Faces& mask0 = s0.mask;
  s0.beta.assign(n, 0.0);
  s0.shift.assign(n, {0.0, 0.0, 0.0});
  s0.stuck.assign(n, 0);
  const Weights& at = weights_at(p.x, p.d);
  s0.u = exchange_.fluid_velocity({p.x, p.d, p.m, none, none, &at.faces}, flow_.velocity(), mass0, &mask0, s0.share);
  s0.x.assign(p.x.begin(), p.x.end());
  const std::vector<double>& eps_now = flow_.fluid_fraction();
  for (std::size_t i = 0; i < n; ++i) {
    // A share below 0 is the round-off of a folded kernel's weights (~1e-18) on faces the mask leaves: none.
    if (!(s0.share[i] > 0.0)) {
      s0.share[i] = 0.0;
      continue;
    }
    const Stencil& s = at.stencil[i];
    const double seen = eps_now.empty() ? 1.0 : interpolate(g, s, eps_now);
    const double eps = std::min(1.0, seen + own_solid_fraction(g, s, p.d[i]));
    const double mu = interpolate(g, s, flow_.viscosity());
    const Vec& u = s0.u[i];
    const Vec w{p.v[i][0] - u[0], p.v[i][1] - u[1], p.v[i][2] - u[2]};
    const double slip = std::hypot(w[0], w[1], w[2]);
    const double k = own_pressure_share(g, s, p.d[i]);
    // g0 at the particle's place, along its slip (mobility.h); the place-averaged table where it does not apply.
    const std::optional<double> g0 =
        s_.closure.disturbance ? std::optional(disturbance_mobility(g, s, p.d[i], s_.width_factor, mu, w)) : std::nullopt;
    const DragCoefficients dc = drag_coefficients(p.drag[i], p.d[i], s_.width_factor, slip, eps, mu, g.h, s_.closure, k, g0);
    s0.beta[i] = s0.share[i] * dc.beta;
    if (s_.closure.disturbance && pending_interval_ > 0.0 && s0.beta[i] > 0.0) {
      // The particle's own hole in the fluid's body and pressure forces (coupled_flow.h), induced at it with
      // the mobility the drag's correction used (drag.h: g0, none where the correction is held, as where the
      // kernel reaches the air and the local viscosity is the air's): u_undisturbed = u_p - g0 f_hole. The
      // body force's density is averaged over the same faces and weights as the pressure force (face_mean of
      // the faces' paste fraction), so that the hole is 0 in a paste at rest wherever the particle sits, also
      // across the free surface (there the cells' mean density was 1.2 kg/m3 where the faces' pressure held
      // ~80 kg/m3: a hole of 4e-4 N on a 10 mm sphere at rest).
      const Vec alpha = face_mean(s, mask0);
      const double V = sphere_volume(p.d[i]);
      for (int c = 0; c < 3; ++c) {
        const double rho = flow_.phases().density(alpha[c]);                               // kg/m3
        const double undisturbed = pending_[i][c] / pending_interval_ - k * drag_[i][c];  // N, -V_p grad p
        const double hole = -V * rho * flow_.settings().gravity[c] - undisturbed;          // N
        s0.shift[i][c] = -s0.share[i] * dc.mobility * hole;
      }
    }
  }
  return s0;
}

bool CoupledFlow::drag_update(const StepRecord& r, Vec& v, const Vec& F, double dt, Vec& J) {
  // r.u: u_p less the particle's own displaced fluid's part (s0.shift, coupled_flow.h; 0 without the correction).
  const Vec& u = r.u;
  const double a = r.beta * dt / r.mass;
  for (int c = 0; c < 3; ++c) {
    const double free = v[c] + F[c] / r.mass * dt;
    const double next = (free + a * u[c]) / (1.0 + a);
    J[c] += r.mass * (next - free);
    v[c] = next;
  }
  // The yield part in the same update (as fluid/drag_kick.h): it removes at most F_y dt / (1 + a) of momentum
  // from the slip the linear part left, so that the terminal slip is (F - F_y) / beta and a particle sticks
  // exactly when its other forces are below F_y.
  const double bound = r.yield * dt / (1.0 + a);  // N s
  if (!(bound > 0.0)) return false;  // no yield part (air, a Newtonian paste): the slip's norm is not needed
  const Vec w{v[0] - u[0], v[1] - u[1], v[2] - u[2]};
  const double speed = std::hypot(w[0], w[1], w[2]);
  if (!(speed > 0.0)) return false;
  const bool stick = r.mass * speed <= bound;
  const double scale = stick ? r.mass : bound / speed;
  for (int c = 0; c < 3; ++c) {
    const double Jc = -scale * w[c];
    J[c] += Jc;
    v[c] += Jc / r.mass;
  }
  return stick;
}

// One DEM step of particle i: the other forces, the velocity-dependent drag implicit against the frozen u_p
// (backward Euler, v' = (v + a dt + (beta dt / m) u_p) / (1 + beta dt / m): stable at any beta dt / m, and it
// lands on the terminal slip), the yield stick, the drift. The drag impulses are summed into sub (J_sub).
void CoupledFlow::dem_step(CoupledParticles& p, std::size_t i, double dt, int steps, const ExtraForce& extra,
                           Start& s0, std::vector<Vec>& sub, CycleStats& st) const {
  const flow::Grid& g = flow_.grid();
  Vec F{};
  const Vec fx = extra ? extra(i, p) : Vec{};
  for (int c = 0; c < 3; ++c) F[c] = p.m[i] * s_.gravity[c] + pending_[i][c] / (steps * dt) + fx[c];
  Vec& v = p.v[i];
  const bool stuck = drag_step(p, i, v, F, dt, s0, sub[i]);
  s0.stuck[i] = stuck ? 1 : 0;
  st.stuck_steps += stuck ? 1 : 0;
  for (int c = 0; c < 3; ++c) {
    double& x = p.x[i][c];
    x += v[c] * dt;
    const double L = g.n[c] * g.h[c];
    if (g.periodic(c) && (x < g.origin[c] || x >= g.origin[c] + L))  // only then: a wrap rounds
      x = g.origin[c] + std::fmod(std::fmod(x - g.origin[c], L) + L, L);
  }
}

namespace {
// The books of the exchange: the faces' momentum change inside the hooks against the particles' impulses J.
void book(CycleStats& st, const flow::Faces& before, const flow::Faces& u, const flow::Faces& mass,
          const std::vector<std::array<double, 3>>& J) {
  for (int c = 0; c < 3; ++c) {
    for (std::size_t f = 0; f < u[c].size(); ++f) st.fluid_exchange[c] += mass[c][f] * (u[c][f] - before[c][f]);
    for (const auto& j : J) st.particle_exchange[c] += j[c], st.exchange_scale += std::abs(j[c]);
  }
}

// Momentum `back` (N s per particle) handed back to the particles' velocities.
void kick_back(CoupledParticles& p, const std::vector<std::array<double, 3>>& back) {
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int c = 0; c < 3; ++c) p.v[i][c] += back[i][c] / p.m[i];
}

// The same, booked as the particles' (the faces' side was booked where they gave it up).
void give_back(CycleStats& st, CoupledParticles& p, const std::vector<std::array<double, 3>>& back) {
  kick_back(p, back);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int c = 0; c < 3; ++c) st.particle_exchange[c] += back[i][c], st.exchange_scale += std::abs(back[i][c]);
}
}  // namespace

// The sub-cycle's reaction -W^T J_sub on the faces (u, in/out), each face the share of it its fluid mass since
// the cycle's start allows; the particles get back the rest (Exchange::react).
void CoupledFlow::react_subcycle(const ExchangeParticles& at_start, const Start& s0, const std::vector<Vec>& sub,
                                 CoupledParticles& p, flow::Faces& u, const flow::Faces& mass, CycleStats& st) const {
  const flow::Faces before = u;
  std::vector<Vec> back;  // what faces emptied since the cycle's start could not take
  const ExchangeStats e = exchange_.react(at_start, u, mass, &s0.mask, sub, &s0.mass, &back);
  st.dropped_yield += e.dropped_yield;
  st.returned_reaction += e.clipped;
  book(st, before, u, mass, sub);
  give_back(st, p, back);
}

// The reaction bounded to the hull of `before` (the faces before it) and the particles' velocities
// (Exchange::bound_reaction); what the faces give up goes back to the particles.
void CoupledFlow::bound_subcycle(const ExchangeParticles& at_start, const Start& s0, const std::vector<Vec>& sub,
                                 const flow::Faces& before, CoupledParticles& p, flow::Faces& u,
                                 const flow::Faces& mass, CycleStats& st) const {
  const flow::Faces entry = u;
  std::vector<Vec> back;
  const ExchangeStats e = exchange_.bound_reaction(at_start, before, u, mass, &s0.mask, sub, p.v, back, &s0.mass);
  st.clipped_reaction += e.clipped;
  if (e.clipped_faces == 0) return;
  // The books: the faces gave up what the particles got back (u changed here, outside the hooks' own).
  book(st, entry, u, mass, back);
  kick_back(p, back);
}

// The flow over the interval T, eps_f linear in time between the start and the end positions; the exchange's
// hooks in each sub-step; then the particles' pending pressure impulses.
void CoupledFlow::flow_interval(CoupledParticles& p, double T, const Start& s0, const std::vector<Vec>& sub,
                                CycleStats& st) {
  const flow::Grid& g = flow_.grid();
  const std::size_t n = p.size();
  const std::vector<double> none(n, 0.0);
  const std::vector<double> eps_start = flow_.fluid_fraction().empty() ? std::vector<double>(g.cell_count(), 1.0)
                                                                       : flow_.fluid_fraction();
  const std::vector<double> eps_end = fluid_fraction(p);
  // Equal sub-steps from the flow's CFL bound at the start; if the exchange has sped the fluid up so that the
  // next sub-step would break the bound, the rest of the interval is split again from there (f0: the fraction
  // done at that split). Without a split the sub-steps are T / parts, r = j / parts, as they always were.
  auto split = [&](double left) {
    return std::max(1, static_cast<int>(std::ceil(left / flow_.next_time_step() * (1.0 - 1e-12))));
  };
  int parts = split(T);
  double f0 = 0.0;
  int j0 = 0;  // the sub-step index at the last split
  // With the implicit stick, a held particle's beta in the correct exchange is K m / h (h the first sub-step;
  // a later split only shortens it): its B = beta m / (m + h beta) is then m / h to 1e-6, i.e. it moves with
  // the fluid's change at it. (Only a particle with a yield part can be held, so only one in the paste.)
  std::vector<double> beta_correct = s0.beta;
  const double h_first = T / parts;  // s
  if (s_.implicit_stick)
    for (std::size_t i = 0; i < n; ++i)
      if (s0.stuck[i]) beta_correct[i] = std::max(s0.beta[i], kStickBeta * p.m[i] / h_first);
  // The face weights at the end positions (the correct exchange's) and at Start::x (the drag's own, for the
  // reaction); after eps_end's, so both are kept (weights_at).
  const ExchangeParticles view{p.x, p.d, p.m, beta_correct, none, &weights_at(p.x, p.d).faces};
  const ExchangeParticles at_start_view{s0.x, p.d, p.m, s0.beta, none, &weights_at(s0.x, p.d).faces};
  std::vector<Vec> impulse, reference = s0.u;
  flow::Faces at_start, at_end;  // N s/m3: the pressure impulses, split by the positions their fluid mass had
  for (int c = 0; c < 3; ++c) at_start[c].assign(g.face_count(c), 0.0), at_end[c].assign(g.face_count(c), 0.0);
  int resplits = 0;  // FluxStepTooLong retries in this interval
  for (int j = 0; j < j0 + parts; ++j) {
    if (j > 0 && (1.0 - f0) * T / parts > flow_.next_time_step()) {
      f0 = f0 + (1.0 - f0) * (j - j0) / parts;
      j0 = j;
      parts = split((1.0 - f0) * T);
    }
    const double r0 = f0 + (1.0 - f0) * (j - j0) / parts, r1 = f0 + (1.0 - f0) * (j - j0 + 1) / parts;
    std::vector<double> eps(eps_end);
    const bool last = j + 1 == j0 + parts;
    if (!last)
      for (std::size_t c = 0; c < eps.size(); ++c) eps[c] = eps_start[c] + r1 * (eps_end[c] - eps_start[c]);
    flow_.set_next_fluid_fraction(std::move(eps));
    flow::Faces before_reaction;  // the faces before the sub-cycle's reaction (bound_reaction's hull)
    auto react = [&](double, flow::Faces& u, const flow::Faces& mass) {
      if (j != 0) return;  // the sub-cycle's reaction once, in the first sub-step
      before_reaction = u;
      react_subcycle(at_start_view, s0, sub, p, u, mass, st);
    };
    // The reaction of the first sub-step, bounded once the viscous solve has passed it on, and before the
    // projection (which spread a thin face's excess over its neighbours: chapter-7 test 3, a face of 1 % paste
    // kicked to 49 m/s by 117 small rocks' reaction came out of the projection at 38 m/s and its neighbours at
    // up to 31 m/s, past the step guard's floor, docs/mixing_scenes.md).
    auto bound = [&](double, flow::Faces& u, const flow::Faces& mass) {
      if (j == 0) bound_subcycle(at_start_view, s0, sub, before_reaction, p, u, mass, st);
    };
    auto correct = [&](double h, flow::Faces& u, const flow::Faces& mass) {
      const flow::Faces mask = flow::face_means(g, flow_.alpha()), before = u;
      const ExchangeStats e = exchange_.correct(h, view, p.v, u, mass, &mask, reference, impulse);
      st.exchange_iterations += e.iterations;
      book(st, before, u, mass, impulse);
      // The next sub-step's change is measured from where this one left the fluid at the particles.
      std::vector<double> unused;
      if (!last) reference = exchange_.fluid_velocity(view, u, mass, &mask, unused);
    };
    flow_.set_exchange(react, correct, bound);
    try {
      flow_.step((1.0 - f0) * T / parts);
    } catch (const flow::FluxStepTooLong& e) {
      // The particles' volume change outran this sub-step (chapter-7 test 3: a 50 mm rock entering the box took
      // 0.555 of a top cell's fluid fraction in one 1 ms step): the step has left u as it was, so the rest of
      // the interval from r0 on is split again, into parts short enough for the flux it measured at the flow's
      // own CFL target, and this sub-step is retried. A run that never meets it is unchanged bit for bit.
      flow_.set_exchange({});
      const int left = j0 + parts - j;  // sub-steps left, this one included
      if (++resplits > kMaxResplits) throw;
      f0 = r0, j0 = j;
      parts = std::max(left + 1, static_cast<int>(std::ceil(left * e.cfl() / flow_.settings().cfl)));
      --j;
      continue;
    } catch (...) {
      flow_.set_exchange({});
      throw;
    }
    flow_.set_exchange({});
    ++st.flow_steps;
    const flow::Faces& ic = flow_.continuity_impulse();
    const flow::Faces& ip = flow_.pressure_impulse();
    for (int c = 0; c < 3; ++c)
      for (std::size_t f = 0; f < at_start[c].size(); ++f) {
        const double a = ic[c].empty() ? 0.0 : ic[c][f], b = ip[c][f];
        at_start[c][f] += (1.0 - r0) * a + (1.0 - r1) * b;
        at_end[c][f] += r0 * a + r1 * b;
      }
  }
  // Model A's pressure-gradient force, pending for the next sub-cycle.
  const std::vector<Stencil>& from = weights_at(x_flow_, p.d).stencil;
  const std::vector<Stencil>& to = weights_at(p.x, p.d).stencil;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec a = face_mean(from[i], at_start);
    const Vec b = face_mean(to[i], at_end);
    const double V = sphere_volume(p.d[i]);
    for (int c = 0; c < 3; ++c) pending_[i][c] = -V * (a[c] + b[c]);
  }
  // The sub-cycle's mean paste drag (N), whichever DEM ran it (cycle() or the engine's kicks through drag_step):
  // the next drag_at_start takes its own pressure k F_d out of the pending force (the own hole).
  drag_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) drag_[i][c] = sub[i][c] / T;
  pending_interval_ = T;
  x_flow_ = p.x;
}

CycleStats CoupledFlow::cycle(CoupledParticles& p, int steps, double dt, const ExtraForce& extra) {
  const std::size_t n = p.size();
  if (p.v.size() != n || p.d.size() != n || p.m.size() != n || p.drag.size() != n || x_flow_.size() != n)
    throw std::invalid_argument("coupling: particle arrays differ in length (or start() was not called)");
  if (steps < 1 || !(dt > 0.0)) throw std::invalid_argument("coupling: a cycle needs steps >= 1 and dt > 0");
  CycleStats st;
  Start s0 = drag_at_start(p);
  std::vector<Vec> sub(n, {0.0, 0.0, 0.0});
  for (int k = 0; k < steps; ++k)
    for (std::size_t i = 0; i < n; ++i) dem_step(p, i, dt, steps, extra, s0, sub, st);
  flow_interval(p, steps * dt, s0, sub, st);
  return st;
}

}  // namespace pastemix::coupling
