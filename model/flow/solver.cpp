// SPDX-License-Identifier: MIT
#include "model/flow/solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "base/error.h"
#include "model/flow/finite_check.h"
#include "model/flow/step_guard.h"

namespace pastemix::flow {

FlowSolver::FlowSolver(const Grid& grid, Phases phases, FlowSettings settings)
    : g_((grid.check(), grid)), ph_(std::move(phases)), s_(settings), viscous_(g_), pressure_(g_) {
  if (!(s_.cfl > 0.0 && s_.cfl <= 0.5)) throw std::invalid_argument("flow: cfl must be in (0, 0.5]");
  for (int c = 0; c < 3; ++c) u_[c].assign(g_.face_count(c), 0.0);
  p_.assign(g_.cell_count(), 0.0);
  alpha_.assign(g_.cell_count(), 0.0);
  mu_.assign(g_.cell_count(), ph_.eta_air);
  pressure_.set_inflow_density(ph_.rho_air);  // an open side lets air in (advection.cpp)
}

void FlowSolver::add_paste_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  for (int k = 0; k < g_.n[2]; ++k)
    for (int j = 0; j < g_.n[1]; ++j)
      for (int i = 0; i < g_.n[0]; ++i) {
        const std::array<int, 3> q{i, j, k};
        double f = 1.0;
        for (int d = 0; d < 3; ++d) {
          const double a = g_.origin[d] + q[d] * g_.h[d], b = a + g_.h[d];
          f *= std::max(0.0, std::min(b, hi[d]) - std::max(a, lo[d])) / g_.h[d];
        }
        double& al = alpha_[g_.cell(q)];
        al = std::min(1.0, al + f);
      }
  pressure_ready_ = false;
  update_viscosity({});
}

void FlowSolver::set_alpha(std::vector<double> alpha) {
  if (alpha.size() != alpha_.size()) throw std::invalid_argument("flow: alpha has the wrong size");
  alpha_ = std::move(alpha);
  pressure_ready_ = false;
  update_viscosity({});
}

void FlowSolver::set_blocked_faces(FaceMask mask) {
  for (int c = 0; c < 3; ++c) {
    if (mask[c].empty()) continue;
    if (mask[c].size() != u_[c].size()) throw std::invalid_argument("flow: the blocked-face mask has the wrong size");
    for (std::size_t f = 0; f < u_[c].size(); ++f)
      if (mask[c][f]) u_[c][f] = 0.0;
  }
  blocked_ = std::move(mask);
}

namespace {
void check_fraction(const Grid& g, const std::vector<double>& eps) {
  if (static_cast<long>(eps.size()) != g.cell_count())
    throw std::invalid_argument(fmt::format("flow: fluid fraction has {} values for {} cells", eps.size(), g.cell_count()));
  for (std::size_t i = 0; i < eps.size(); ++i)
    if (!(eps[i] > 0.0 && eps[i] <= 1.0))
      throw std::invalid_argument(fmt::format("flow: fluid fraction {} in cell {} is outside (0, 1]", eps[i], i));
}
}  // namespace

void FlowSolver::set_fluid_fraction(std::vector<double> eps_now) {
  check_fraction(g_, eps_now);
  eps_ = std::move(eps_now);
  eps_next_ = eps_;
  pressure_ready_ = false;
}

void FlowSolver::set_next_fluid_fraction(std::vector<double> eps_end, bool with_rate) {
  check_fraction(g_, eps_end);
  if (eps_.empty()) eps_.assign(g_.cell_count(), 1.0);
  eps_next_ = std::move(eps_end);
  with_rate_ = with_rate;
}

void FlowSolver::project_continuity(double dt, const FluidFraction& vf) {
  // The residual is measured against the larger of itself, the step's source and the last projection's start:
  // once the solid stops, u already meets the new continuity to the last tolerance, and solving that round-off
  // to 1e-10 of itself cannot be done (nor is it needed).
  double r0 = 0.0, source = 0.0;
  for (double r : continuity_residual(g_, u_, &vf)) r0 += r * r;
  for (double r : *vf.rate) source += r * r;
  r0 = std::sqrt(r0);
  const double reference = std::max(std::sqrt(source), last_.projection.divergence_before);
  for (int c = 0; c < 3; ++c) continuity_impulse_[c].assign(u_[c].size(), 0.0);
  if (!(r0 > s_.pressure_tolerance * reference)) return;
  std::vector<double> phi(g_.cell_count(), 0.0);  // a pressure (Pa) over dt, not kept: the pressure is p_
  try {
    pressure_.project(dt, face_densities(g_, ph_, alpha_), u_, phi, s_.pressure_tolerance * std::max(reference, r0) / r0,
                      s_.max_iterations, &vf, false);
  } catch (const RuntimeFailure& e) {
    throw RuntimeFailure(fmt::format("{} (the continuity projection before advection) in the step from t = {:.9g} s",
                                     e.what(), t_));
  }
  pressure_.gradient_impulse(dt, phi, continuity_impulse_);
}

Faces FlowSolver::fluid_mass() const {
  Faces m = face_densities(g_, ph_, alpha_);
  const Faces eps = eps_.empty() ? Faces{} : face_means(g_, eps_);
  for (int c = 0; c < 3; ++c)
    for (std::size_t f = 0; f < m[c].size(); ++f) m[c][f] *= (eps_.empty() ? 1.0 : eps[c][f]) * g_.cell_volume();
  return m;
}

double FlowSolver::next_time_step() const {
  double rate = 0.0;  // max |u_d| / h_d, 1/s
  for (int c = 0; c < 3; ++c)
    for (double v : u_[c]) rate = std::max(rate, std::abs(v) / g_.h[c]);
  double dt = s_.max_time_step;
  if (rate > 0.0) dt = std::min(dt, s_.cfl / rate);
  // From rest, gravity alone brings a face to the CFL bound in sqrt(cfl h / g): the step after is limited again.
  const double gmag = std::hypot(s_.gravity[0], s_.gravity[1], s_.gravity[2]);
  if (gmag > 0.0) dt = std::min(dt, std::sqrt(s_.cfl * std::min({g_.h[0], g_.h[1], g_.h[2]}) / gmag));
  // A step that has collapsed (a velocity runaway) stops the run with its diagnosis (model/flow/step_guard.h).
  require_time_step_above_floor(g_, StepControl{s_.cfl, s_.max_time_step, s_.gravity}, u_, alpha_, dt, t_, totals_.steps, &eps_);
  return dt;
}

double FlowSolver::neighbour(const std::vector<double>& uc, int c, int d, const std::array<int, 3>& q, int side) const {
  const int w = g_.wrap_cell(d, q[d] + side);
  const double in = uc[3 * g_.cell(q) + c];
  // A wall inside the box between the two cells: free slip, no gradient across it (as on a free-slip side).
  if (w >= 0 && !blocked_[d].empty()) {
    std::array<int, 3> f = q;
    f[d] = side > 0 ? (g_.periodic(d) ? w : q[d] + 1) : q[d];
    if (blocked(blocked_, d, g_.face(d, f))) return in;
  }
  if (w >= 0) {
    std::array<int, 3> r = q;
    r[d] = w;
    return uc[3 * g_.cell(r) + c];
  }
  // Outside the box: the ghost value of the viscous operator (2 U_wall - u at a no-slip wall; no gradient on a
  // free-slip or open side), so that the first cell's strain rate is the wall's, not the next cell's.
  const Boundary& b = g_.side(d, side > 0 ? 1 : 0);
  return b.type == BoundaryType::no_slip ? 2.0 * b.wall_velocity[c] - in : in;
}

std::vector<double> FlowSolver::strain_rate() const {
  const std::vector<double> parts = strain_parts();
  std::vector<double> out(g_.cell_count());
  for (long c = 0; c < g_.cell_count(); ++c) out[c] = std::sqrt(parts[4 * c]);
  return out;
}

std::vector<double> FlowSolver::strain_parts() const {
  // Cell-centred velocity gradient: diagonal from the cell's faces, off-diagonal by central differences of the
  // face-averaged cell velocities (ghost values outside the box). Enough for a lagged viscosity; the stresses
  // themselves use the exact MAC stencils of the viscous operator.
  const std::vector<double> uc = cell_velocity();
  std::vector<double> out(4 * g_.cell_count(), 0.0);
#pragma omp parallel for schedule(static)
  for (int k = 0; k < g_.n[2]; ++k)
    for (int j = 0; j < g_.n[1]; ++j)
      for (int i = 0; i < g_.n[0]; ++i) {
        const std::array<int, 3> q{i, j, k};
        double G[3][3];
        for (int c = 0; c < 3; ++c)
          for (int d = 0; d < 3; ++d) {
            if (c == d) {
              std::array<int, 3> hi = q;
              hi[c] = g_.periodic(c) ? (q[c] + 1) % g_.n[c] : q[c] + 1;
              G[c][c] = (u_[c][g_.face(c, hi)] - u_[c][g_.face(c, q)]) / g_.h[c];
              continue;
            }
            G[c][d] = (neighbour(uc, c, d, q, 1) - neighbour(uc, c, d, q, -1)) / (2.0 * g_.h[d]);
          }
        double dd = 0.0;  // 2 D:D
        for (int c = 0; c < 3; ++c)
          for (int d = 0; d < 3; ++d) {
            const double e = 0.5 * (G[c][d] + G[d][c]);
            dd += 2.0 * e * e;
          }
        double* o = &out[4 * g_.cell(q)];
        o[0] = dd;
        o[1] = G[0][1] + G[1][0];
        o[2] = G[0][2] + G[2][0];
        o[3] = G[1][2] + G[2][1];
      }
  return out;
}

void FlowSolver::update_viscosity(const std::vector<double>& gamma) {
  const Rheology& law = *ph_.paste;
  for (long c = 0; c < g_.cell_count(); ++c) {
    const double a = std::clamp(alpha_[c], 0.0, 1.0);
    const double eta = law.viscosity(gamma.empty() ? 0.0 : gamma[c]);
    mu_[c] = a * eta + (1.0 - a) * ph_.eta_air;
  }
}

Faces FlowSolver::gravity_kick(double dt) const {
  Faces kick;
  for (int c = 0; c < 3; ++c) {
    kick[c].assign(u_[c].size(), 0.0);
    if (s_.gravity[c] == 0.0) continue;
    const auto fd = g_.face_dims(c);
    for (int k = 0; k < fd[2]; ++k)
      for (int j = 0; j < fd[1]; ++j)
        for (int i = 0; i < fd[0]; ++i) {
          const std::array<int, 3> q{i, j, k};
          if (g_.boundary_face(c, q[c]) && g_.side(c, q[c] == 0 ? 0 : 1).type != BoundaryType::open) continue;
          if (blocked(blocked_, c, g_.face(c, q))) continue;
          kick[c][g_.face(c, q)] = s_.gravity[c] * dt;
        }
  }
  return kick;
}

StepStats FlowSolver::step(double dt) {
  const auto t0 = std::chrono::steady_clock::now();
  StepStats st;
  st.dt = dt;
  // Every stage checks what it made (model/flow/finite_check.h): a run stops at the first non-finite value.
  auto at = [&](const char* stage) { return CheckPoint{stage, t_, totals_.steps}; };
  if (!(dt > 0.0 && std::isfinite(dt)))
    throw RuntimeFailure(fmt::format("flow: time step {} s is not positive and finite at t = {:.9g} s (step {})", dt,
                                     t_, totals_.steps));
  // The strain rate of the start of the step (a shear-dependent law is lagged by one step), the paste fraction
  // after transport.
  require_finite_faces(g_, u_, "velocity", at("on entry to the step"));
  const bool lagged = ph_.paste->shear_dependent();
  const std::vector<double> parts = lagged ? strain_parts() : std::vector<double>{};
  std::vector<double> gamma;
  for (std::size_t c = 0; c < parts.size(); c += 4) gamma.push_back(std::sqrt(parts[c]));
  viscous_.set_blocked(&blocked_);
  pressure_.set_blocked(&blocked_);
  // With particles: the fluid's continuity over this step, and u projected for it before it advects anything.
  const bool coupled = !eps_next_.empty();
  Faces eps_face;
  std::vector<double> rate;
  if (coupled) {
    eps_face = face_means(g_, eps_next_);
    rate.assign(g_.cell_count(), 0.0);
    if (with_rate_)
      for (long c = 0; c < g_.cell_count(); ++c) rate[c] = (eps_next_[c] - eps_[c]) / dt;
    const Faces u_entry = u_;
    project_continuity(dt, FluidFraction{&eps_face, &rate});
    // Nothing else has changed yet: the step can be retried in shorter parts from u_entry (FluxStepTooLong).
    const double cfl = flux_cfl(g_, u_, eps_face, dt);
    if (cfl > kMaxSweepCfl) {
      const std::string why = flux_cfl_diagnosis(g_, u_, eps_face, alpha_, eps_, eps_next_, dt, t_, totals_.steps);
      u_ = u_entry;
      throw FluxStepTooLong(why, cfl);
    }
  }
  const FluidFraction vf_rest{&eps_face, nullptr}, vf_step{&eps_face, &rate};
  const FluidFraction* vf0 = coupled ? &vf_rest : nullptr;
  const FluidFraction* vf1 = coupled ? &vf_step : nullptr;
  const Faces u_lag = lagged ? u_ : Faces{};  // the velocity the shear edges' strain rates come from
  const FluidFractionStep fs{&eps_, &eps_next_, &eps_face};
  st.advection = advect(g_, ph_, dt, totals_.steps, alpha_, u_, &blocked_, coupled ? &fs : nullptr);
  require_finite_cells(g_, alpha_, "paste fraction", at("after advection"));
  require_finite_faces(g_, u_, "velocity", at("after advection"));
  const Faces rho = face_densities(g_, ph_, alpha_);
  require_finite_faces(g_, rho, "face density", at("after the face densities"), true);
  pressure_.set_inflow_velocity(u_, rho);  // the open side's inflow pressure from u^n (its faces are not advected)
  update_viscosity(gamma);
  require_finite_cells(g_, mu_, "viscosity", at("after the viscosities"), true);
  const EdgeLaw edge{ph_.paste.get(), &alpha_, ph_.eta_air, &u_lag, &parts};
  // Incremental pressure correction: gravity and the last pressure gradient enter the viscous solve, the
  // projection finds the new pressure. A steady state is then the exact discrete balance of gravity, pressure
  // and the viscous stresses at any dt (with gravity added after the viscous solve, a flow held by shear
  // stresses, such as a plug or a film, carried an extra g dt on every face). The first step starts from the
  // pressure that balances as much of gravity as a pressure can, so a paste at rest is at rest from step 1.
  if (!pressure_ready_) {
    Faces kick = gravity_kick(dt);
    pressure_.project(dt, rho, kick, p_, s_.pressure_tolerance, s_.max_iterations, vf0);
    pressure_ready_ = true;
  }
  const Faces kick = gravity_kick(dt);
  double weight = 0.0;  // ||rho_f g|| over the kicked faces, N/m3: the viscous solve's force scale
  for (int c = 0; c < 3; ++c)
    for (std::size_t f = 0; f < u_[c].size(); ++f) {
      u_[c][f] += kick[c][f];
      const double w = rho[c][f] * kick[c][f] / dt;
      weight += w * w;
    }
  pressure_.subtract_gradient(dt, rho, p_, u_);
  // A failed solve (its inputs were checked above) says in which step it failed.
  auto when = [&](const RuntimeFailure& e) {
    return RuntimeFailure(fmt::format("{} in the step from t = {:.9g} s (step {}, dt {:.3g} s)", e.what(), t_,
                                      totals_.steps, dt));
  };
  // With particles the fluid's mass in a face's control volume is eps_f rho_f: the exchange's and the viscous
  // step's mass (the stress stays div(2 mu D(u)) of the interstitial velocity, conservative: the fluid keeps
  // its momentum). The exchange comes before the viscous solve, so that the implicit viscous step spreads the
  // particles' reaction within the same step: a steady Stokes flow around a settling sphere is then the
  // solution of L u = -f whatever dt (after it, each step left the undiffused kick f dt / M at the particle,
  // and the settling velocity grew with the step: +27 % at 10 ms, +3 % at 2 ms in `sphere`, h = d).
  Faces rho_fluid, mass;
  if (coupled) {
    rho_fluid = rho;
    for (int c = 0; c < 3; ++c)
      for (std::size_t f = 0; f < rho_fluid[c].size(); ++f) rho_fluid[c][f] *= eps_face[c][f];
    mass = rho_fluid;
    for (int c = 0; c < 3; ++c)
      for (double& m : mass[c]) m *= g_.cell_volume();
  }
  if (coupled && exchange_) {
    exchange_(dt, u_, mass);
    require_finite_faces(g_, u_, "velocity", at("after the particles' momentum exchange"));
  }
  try {
    st.viscous = viscous_.solve(dt, coupled ? rho_fluid : rho, mu_, u_, s_.viscous_tolerance, s_.max_iterations,
                                lagged ? &edge : nullptr, std::sqrt(weight));
  } catch (const RuntimeFailure& e) {
    throw when(e);
  }
  require_finite_faces(g_, u_, "velocity", at("after the viscous solve"));
  if (coupled && exchange_viscous_) {
    exchange_viscous_(dt, u_, mass);
    require_finite_faces(g_, u_, "velocity", at("after the particles' bounded reaction"));
  }
  // Give the last gradient back and project for the whole pressure, with the last one as the guess: the same
  // result as projecting for the increment, and the same right-hand side (and CG iterations) as before.
  pressure_.subtract_gradient(-dt, rho, p_, u_);
  try {
    st.projection = pressure_.project(dt, rho, u_, p_, s_.pressure_tolerance, s_.max_iterations, vf1);
  } catch (const RuntimeFailure& e) {
    throw when(e);
  }
  require_finite_cells(g_, p_, "pressure", at("after the projection"));
  require_finite_faces(g_, u_, "velocity", at("after the projection"));
  if (coupled && exchange_after_) {
    exchange_after_(dt, u_, mass);
    require_finite_faces(g_, u_, "velocity", at("after the particles' drag on the step's change"));
  }
  if (coupled) {
    pressure_.gradient_impulse(dt, p_, pressure_impulse_);
    eps_ = eps_next_;
  }
  t_ += dt;
  ++totals_.steps;
  totals_.pressure_iterations += st.projection.solve.iterations;
  totals_.viscous_iterations += st.viscous.iterations;
  totals_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  last_ = st;
  return st;
}

long FlowSolver::advance_to(double t) {
  long n = 0;
  while (t_ < t * (1.0 - 1e-14)) {
    double dt = next_time_step();
    // Land on t; avoid leaving a sliver step behind.
    if (t_ + dt >= t) dt = t - t_;
    else if (t_ + 1.5 * dt > t) dt = 0.5 * (t - t_);
    step(dt);
    ++n;
  }
  return n;
}

FlowSolver::State FlowSolver::state() const {
  return {u_, continuity_impulse_, pressure_impulse_, p_, alpha_, mu_, eps_, eps_next_, with_rate_, pressure_ready_,
          t_, last_, totals_};
}

void FlowSolver::restore(State s) {
  const std::size_t cells = g_.cell_count();
  bool fits = s.p.size() == cells && s.alpha.size() == cells && s.mu.size() == cells &&
              (s.eps.empty() || s.eps.size() == cells) && (s.eps_next.empty() || s.eps_next.size() == cells);
  for (int c = 0; c < 3; ++c) fits = fits && static_cast<long>(s.u[c].size()) == g_.face_count(c);
  if (!fits) throw std::invalid_argument("flow: a saved state of another grid");
  u_ = std::move(s.u), continuity_impulse_ = std::move(s.continuity_impulse), pressure_impulse_ = std::move(s.pressure_impulse);
  p_ = std::move(s.p), alpha_ = std::move(s.alpha), mu_ = std::move(s.mu), eps_ = std::move(s.eps);
  eps_next_ = std::move(s.eps_next);
  with_rate_ = s.with_rate, pressure_ready_ = s.pressure_ready, t_ = s.t, last_ = s.last, totals_ = s.totals;
}

double FlowSolver::paste_volume() const {
  double sum = 0.0, comp = 0.0;  // Kahan
  for (std::size_t i = 0; i < alpha_.size(); ++i) {
    const double a = eps_.empty() ? alpha_[i] : eps_[i] * alpha_[i];
    const double y = a - comp, s = sum + y;
    comp = (s - sum) - y;
    sum = s;
  }
  return sum * g_.cell_volume();
}

double FlowSolver::max_speed() const {
  double m = 0.0;
  for (int c = 0; c < 3; ++c)
    for (double v : u_[c]) m = std::max(m, std::abs(v));
  return m;
}

std::vector<double> FlowSolver::cell_velocity() const {
  std::vector<double> out(3 * g_.cell_count());
  for (int k = 0; k < g_.n[2]; ++k)
    for (int j = 0; j < g_.n[1]; ++j)
      for (int i = 0; i < g_.n[0]; ++i) {
        const std::array<int, 3> q{i, j, k};
        for (int c = 0; c < 3; ++c) {
          std::array<int, 3> hi = q;
          hi[c] = g_.periodic(c) ? (q[c] + 1) % g_.n[c] : q[c] + 1;
          out[3 * g_.cell(q) + c] = 0.5 * (u_[c][g_.face(c, q)] + u_[c][g_.face(c, hi)]);
        }
      }
  return out;
}

}  // namespace pastemix::flow
