// SPDX-License-Identifier: MIT
// FlowSolver: incompressible two-phase (paste and air) flow on a MAC box grid. Knows nothing of particles.
//
// One step of dt (chosen by next_time_step(): the CFL number per sweep, a gravity bound, a cap):
//   1. advect alpha and the momentum together (model/flow/advection.h: Weymouth & Yue VOF, Rudman-consistent
//      momentum), with the divergence-free velocity of the last step;
//   2. cell viscosities from the paste's Rheology at the start-of-step strain rate (mixture by alpha); a
//      shear-dependent law is evaluated on each shear edge at the edge's own rate (EdgeLaw, linear.h);
//   3. gravity g dt on every face that is not a wall, and the last step's pressure gradient (incremental
//      pressure correction: a steady flow is then exact at any dt);
//   4. implicit viscous step, components coupled (model/flow/linear.h), face densities from the new alpha;
//   5. projection to a divergence-free velocity (relative divergence recomputed from the faces <=
//      pressure_tolerance), the last gradient given back first, so that it solves for the whole new pressure
//      with the last as its guess.
// Walls inside the box (set_blocked_faces, model/flow/obstacle.h) are honoured by every stage: no flux, no
// gravity or pressure gradient on their faces, a Neumann wall for the projection, u = 0 and no shear (free
// slip) in the viscous step. Without them (the default) every stage is what it was, bit for bit.
// The step is the flow's own: a DEM loop can call advance_to(t) with its own times and sub-cycle.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "model/flow/advection.h"
#include "model/flow/grid.h"
#include "model/flow/linear.h"
#include "model/flow/obstacle.h"
#include "model/flow/rheology.h"

namespace pastemix::flow {

struct FlowSettings {
  double cfl = 0.3;                            // max |u_d| dt / h_d per sweep; (0, 0.5] (VOF boundedness)
  double max_time_step = 1e-2;                 // s
  std::array<double, 3> gravity{0.0, 0.0, -9.81};  // m/s2
  double pressure_tolerance = 1e-10;           // ||div u_new|| / ||div u*|| (relative divergence)
  double viscous_tolerance = 1e-10;            // relative residual of the viscous solve
  int max_iterations = 50000;                  // per linear solve
};

struct StepStats {
  double dt = 0.0;  // s
  AdvectionStats advection;
  SolveStats viscous;
  ProjectionStats projection;
};

struct CostTotals {
  long steps = 0;
  long pressure_iterations = 0, viscous_iterations = 0;
  double seconds = 0.0;  // wall time inside step()
};

class FlowSolver {
 public:
  FlowSolver(const Grid& grid, Phases phases, FlowSettings settings);

  // Paste fraction = the exact share of each cell inside the box [lo, hi] (m) (additive over calls, capped at 1).
  void add_paste_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi);
  void set_alpha(std::vector<double> alpha);
  // Walls inside the box from the next step on (an empty mask: none); their faces' velocity is set to 0. Only
  // unblock faces during a run: a newly blocked face that carried a flow leaves a divergence for the next
  // advection (lost or created paste).
  void set_blocked_faces(FaceMask mask);
  const FaceMask& blocked_faces() const { return blocked_; }

  // Particles sharing the cells (model/coupling): the fluid's volume fraction eps_f = 1 - eps_s per cell, each
  // in (0, 1] (std::invalid_argument otherwise). set_fluid_fraction sets it now (no motion implied: call it
  // once before the first step); set_next_fluid_fraction sets it for the end of the next step, which then
  // solves the volume-averaged equations (Kloss et al. 2012 model A; model/coupling/README.md):
  //   d(eps_f alpha)/dt + div(eps_f alpha u) = 0,  div(eps_f u) = -d eps_f/dt,
  //   u_new = u* - (dt / rho_f) grad p (the eps_f of model A's -eps_f grad p cancels with the mass's),
  // u the interstitial velocity, d eps_f/dt = (eps_end - eps_now) / dt. Before advecting, the step projects u
  // for the new continuity, so that the paste's transport and its fluid volume agree. Never called: eps_f = 1,
  // the plain solver bit for bit. with_rate = false drops d eps_f/dt from the projection: a toy coupling, kept
  // only to show (the `piston` test) that it displaces no paste.
  void set_fluid_fraction(std::vector<double> eps_now);
  void set_next_fluid_fraction(std::vector<double> eps_end, bool with_rate = true);
  const std::vector<double>& fluid_fraction() const { return eps_; }  // empty: 1 everywhere

  // The particles' momentum exchange (model/coupling/exchange.h), in a step with particles: called after
  // gravity and the last pressure gradient (so a paste at rest is at rest there) and before the viscous solve
  // and the projection (the viscous step spreads the reaction in the same step), with dt, the faces' velocity
  // (in/out, m/s) and the fluid's mass in each face's control volume (kg, eps_f,end rho_f V: the mass the
  // viscous step uses). The hook must give the faces exactly the opposite of what it gives the particles.
  // Empty: no exchange.
  // A second hook, `after`, is called at the end of the step (after the projection, with the same masses):
  // the particles' drag on the fluid's change over the step (exchange.h, correct); the divergence it leaves
  // is the next step's continuity projection's.
  // A third, `viscous`, is called between the viscous solve and the projection (same masses): where the
  // reaction, once the fluid's stresses have passed it on, is bounded (exchange.h, bound_reaction) before the
  // projection spreads what a face could not pass on over its neighbours.
  using ExchangeHook = std::function<void(double dt, Faces& u, const Faces& fluid_mass)>;
  void set_exchange(ExchangeHook before, ExchangeHook after = {}, ExchangeHook viscous = {}) {
    exchange_ = std::move(before), exchange_after_ = std::move(after), exchange_viscous_ = std::move(viscous);
  }
  // The pressure impulses of the last step with particles, dt grad p per face (N s/m3; 0 on walls and where no
  // gradient acts): the continuity projection's (it acted on the fluid's mass at the step's start, eps_f,start:
  // the particles' share is -V_p times its kernel mean at their start positions) and the projection's (mass at
  // the end: the particles at their end positions). Model A: with both, particles + fluid feel no net
  // pressure force in a periodic box (momentum test, tests/model/coupling/momentum_test.cpp).
  const Faces& continuity_impulse() const { return continuity_impulse_; }
  const Faces& pressure_impulse() const { return pressure_impulse_; }
  // kg per face: eps_f rho_f(alpha) V now (eps_f = 1 without particles).
  Faces fluid_mass() const;

  double next_time_step() const;
  StepStats step(double dt);
  // Steps until time t (the last step shortened to land on it); returns the steps taken.
  long advance_to(double t);

  double time() const { return t_; }
  double paste_volume() const;  // m3, compensated sum of eps_f alpha V (eps_f = 1 without particles)
  double max_speed() const;     // m/s, max over faces of |u_c|
  const Grid& grid() const { return g_; }
  const Phases& phases() const { return ph_; }
  const FlowSettings& settings() const { return s_; }
  const Faces& velocity() const { return u_; }
  Faces& velocity() { return u_; }
  const std::vector<double>& pressure() const { return p_; }
  const std::vector<double>& alpha() const { return alpha_; }
  const std::vector<double>& viscosity() const { return mu_; }  // Pa s per cell, as used by the last step
  std::vector<double> cell_velocity() const;                     // cells x 3, face means, m/s
  std::vector<double> strain_rate() const;                       // per cell, sqrt(2 D:D), 1/s
  std::vector<double> strain_parts() const;  // per cell: 2 D:D (1/s^2), gamma_xy, gamma_xz, gamma_yz (1/s)
  const StepStats& last() const { return last_; }
  const CostTotals& totals() const { return totals_; }

  // The dynamic state, everything a step reads that the constructor does not make (the engine's checkpoint,
  // model/checkpoint.cpp): restored, the next step gives the same bits as in the run that saved it. The
  // operators' matrices are rebuilt by every step from these; the hooks and blocked faces are the caller's.
  struct State {
    Faces u, continuity_impulse, pressure_impulse;
    std::vector<double> p, alpha, mu, eps, eps_next;
    bool with_rate = true, pressure_ready = false;
    double t = 0.0;
    StepStats last;
    CostTotals totals;
  };
  State state() const;
  void restore(State s);  // std::invalid_argument if its sizes do not fit the grid

 private:
  void update_viscosity(const std::vector<double>& gamma);
  // With particles: projects u for the step's continuity div(eps_f u) = -d eps_f/dt before the transport.
  void project_continuity(double dt, const FluidFraction& vf);
  Faces gravity_kick(double dt) const;  // g dt on every face that is not a wall
  // Component c of the cell velocity next to cell q along d (side +-1), a wall's ghost value outside the box.
  double neighbour(const std::vector<double>& uc, int c, int d, const std::array<int, 3>& q, int side) const;  // empty: gamma_dot = 0 (a Newtonian law)
  Grid g_;
  Phases ph_;
  FlowSettings s_;
  ViscousOperator viscous_;
  PressureOperator pressure_;
  Faces u_;
  FaceMask blocked_;                        // walls inside the box; empty: none
  std::vector<double> p_, alpha_, mu_;      // p_: the pressure (Pa)
  std::vector<double> eps_, eps_next_;      // fluid fraction now and at the end of the next step (empty: 1)
  bool with_rate_ = true;
  ExchangeHook exchange_, exchange_after_, exchange_viscous_;
  Faces continuity_impulse_, pressure_impulse_;  // N s/m3, set by a step with particles
  bool pressure_ready_ = false;             // p_ balances gravity (set by the first step after the paste changes)
  double t_ = 0.0;
  StepStats last_;
  CostTotals totals_;
};

}  // namespace pastemix::flow
