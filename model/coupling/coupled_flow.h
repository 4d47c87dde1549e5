// SPDX-License-Identifier: MIT
// Particles and the paste flow coupled both ways over one coupling interval (issue 18, layer 3): what the
// engine's `dynamics = "flow"` runs, and what the coupling's validations drive without the engine (particles as
// plain arrays; contacts, if any, come in as an extra force).
//
// One cycle of `steps` DEM steps of dt (the coupling interval T = steps dt):
//   1. DEM sub-cycle, each step (symplectic Euler): v += (m g + f_extra + P / steps... ) dt / m where P is the
//      particle's pending pressure impulse (below), spread evenly over the sub-cycle; then the drag's bounded
//      yield part sticks the particle to the fluid velocity u_p frozen at the cycle's start (W u^n, the
//      exchange's masked weights): J = -m w if m |w| <= F_y dt, else -F_y dt w / |w| (w = v - u_p), summed
//      over the sub-cycle as J_y; then x += v dt.
//   2. Flow, over T in k equal sub-steps (k from the flow's CFL bound at the start): eps_f from the particles'
//      new positions (kernel.h; linear in time between the cycle's start and end within the sub-steps), and in
//      each sub-step, after its viscous solve and before its projection (FlowSolver::set_exchange), the
//      exchange (exchange.h): the faces take -W^T J_y (the whole sub-cycle's yield reaction, first sub-step),
//      then the velocity-dependent drag, beta from drag.h at the slip v - W u^n, implicit in both phases.
//   3. Model A's pressure-gradient force on the particles, -V_p grad p (buoyancy counted once, no separate
//      rho_f V g): each sub-step's pressure impulses (FlowSolver::continuity_impulse / pressure_impulse, dt grad p
//      per face) acted on the fluid's mass eps_f at known times; the particles get the complement,
//      -V_p (kernel mean of the impulses) with the kernel at the matching positions (the start and end
//      positions, mixed as eps_f was), so that in a periodic box the pressure exerts no net force on the
//      mixture. That impulse is pending: it is given over the next sub-cycle (step 1).
// Momentum: gravity is the only external force in a periodic box; particles + fluid + pending impulses gain
// exactly M g t (momentum_test.cpp).
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "model/coupling/drag.h"
#include "model/coupling/exchange.h"
#include "model/coupling/kernel.h"
#include "model/flow/solver.h"

namespace pastemix::coupling {

struct CoupledParticles {
  std::vector<std::array<double, 3>> x, v;  // m, m/s
  std::vector<double> d, m;                 // m, kg
  std::vector<SphereDrag> drag;             // each particle's drag law in the paste (drag.h)
  std::size_t size() const { return x.size(); }
};

struct CouplingSettings {
  double width_factor = kDefaultWidthFactor;  // kernel width c (kernel.h)
  DragClosure closure;                        // voidage and disturbance corrections (drag.h)
  std::array<double, 3> gravity{0.0, 0.0, -9.81};  // m/s2, on the particles (the flow has its own)
};

struct CycleStats {
  int flow_steps = 0;
  int stuck_steps = 0;          // particle-steps the yield part held
  int exchange_iterations = 0;  // CG, summed
  double dropped_yield = 0.0;   // N s (exchange.h)
  // The exchange's books (N s): what the particles got from the paste's drag over the cycle (the sub-cycle's
  // yield impulses and the implicit drag's), what the faces' momentum changed by inside the exchange, and
  // sum |J| over particles and components (the scale of the first two).
  std::array<double, 3> particle_exchange{}, fluid_exchange{};
  double exchange_scale = 0.0;
};

class CoupledFlow {
 public:
  // The flow must be the particles' box: one grid, its paste already set. extra(i, x, v) -> N: a force besides
  // gravity and the fluid's (contacts), or empty.
  using ExtraForce = std::function<std::array<double, 3>(std::size_t, const CoupledParticles&)>;
  CoupledFlow(flow::FlowSolver& flow, CouplingSettings settings);

  // The particles' fluid fraction into the flow, at their current positions (call once, before the first cycle).
  void start(const CoupledParticles& p);
  CycleStats cycle(CoupledParticles& p, int steps, double dt, const ExtraForce& extra = {});

  const std::vector<std::array<double, 3>>& pending_impulse() const { return pending_; }  // N s per particle
  // N s: sum over faces of eps_f rho_f V u (the fluid's momentum, the masses the flow step ends with).
  std::array<double, 3> fluid_momentum() const;
  const flow::FlowSolver& flow() const { return flow_; }

 private:
  std::vector<double> fluid_fraction(const CoupledParticles& p) const;  // eps_f = 1 - eps_s per cell
  // Kernel mean of face impulses at a position, over the faces that are not box walls (renormalised there).
  std::array<double, 3> face_mean(const Stencil& s, const flow::Faces& f) const;
  flow::FlowSolver& flow_;
  CouplingSettings s_;
  Exchange exchange_;
  std::vector<std::array<double, 3>> x_flow_;  // m: positions at the last flow step (its eps_f)
  std::vector<std::array<double, 3>> pending_;
};

}  // namespace pastemix::coupling
