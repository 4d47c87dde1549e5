// SPDX-License-Identifier: MIT
// Particles and the paste flow coupled both ways over one coupling interval (issue 18, layer 3): what the
// engine's `dynamics = "flow"` runs, and what the coupling's validations drive without the engine (particles as
// plain arrays; contacts, if any, come in as an extra force).
//
// One cycle of `steps` DEM steps of dt (the coupling interval T = steps dt):
//   1. Drag coefficients at the cycle's start (drag.h: the particle's law on the slip v - W u^n, the voidage the
//      others leave, the disturbance correction), u_p = W u^n frozen (the exchange's masked weights, scaled by
//      the particle's paste share). With the disturbance correction u_p also loses what the particle's own
//      displaced fluid induces at it, g0 f_hole with f_hole = -V_p (rho_f g - grad p) (model A gives the fluid
//      its body and pressure forces on eps_f only, so the particle's volume is a hole in them; the undisturbed
//      flow of Maxey & Riley 1983 is the flow with fluid in the particle's place). It is 0 in a paste at rest
//      (grad p = rho_f g) and V_p (rho_mix - rho_f) g downward in a uniform suspension (its Stokeslet is then
//      the buoyant weight V_p (rho_p - rho_f) g, Batchelor 1972, of which the drag is eps); grad p is the
//      undisturbed one: the pending pressure force of the last interval less the particle's own part k F_d
//      (drag.h), F_d its drag over the last sub-cycle (however the DEM ran it: cycle() or the engine's kicks),
//      and rho_f g the faces' (the same kernel faces and weights as grad p: 0 at rest across a free surface
//      too). g0 is the one the drag's correction used (DragCoefficients::mobility: none where it is held).
//   2. DEM sub-cycle, each step: v += (m g + P / T + f_extra) dt / m (P: the pending pressure impulse, below);
//      the velocity-dependent drag implicit against u_p (backward Euler, stable at any beta dt / m); the yield
//      part in the same update (it removes at most F_y dt / (1 + beta dt / m) of momentum, never reversing the
//      slip: the terminal slip is (F - F_y) / beta, and a particle sticks exactly when F <= F_y); x += v dt.
//      The drag impulses are summed, J_sub.
//   3. Flow over T, in k equal sub-steps (k from the flow's CFL bound at the start), eps_f from the particles'
//      new positions (kernel.h; linear in time between the cycle's start and end within the sub-steps). In the
//      first sub-step the faces take -W^T J_sub before the viscous solve (FlowSolver::set_exchange `before`:
//      the implicit viscous step spreads it within the step, so a steady state does not depend on dt), each
//      face the share of it its fluid mass since the cycle's start allows (exchange.h, react's start_mass; the
//      rest goes back to the particles); between that viscous solve and the projection (`viscous`) a thin
//      face kicked past its particles is brought back to their hull (exchange.h, bound_reaction); after each
//      sub-step's projection (`after`), the fluid's own change at the particles is exchanged with the
//      velocity-dependent drag implicit in both phases (exchange.h, correct).
//   4. Model A's pressure-gradient force on the particles, -V_p grad p (buoyancy counted once, no separate
//      rho_f V g): each sub-step's pressure impulses (FlowSolver::continuity_impulse / pressure_impulse, dt grad p
//      per face) acted on the fluid's mass eps_f at known times; the particles get the complement,
//      -V_p (kernel mean of the impulses) with the kernel at the matching positions (the start and end
//      positions, mixed as eps_f was), so that in a periodic box the pressure exerts no net force on the
//      mixture. That impulse is pending: it is given over the next sub-cycle (step 2).
// Momentum: gravity is the only external force in a periodic box; particles + fluid + pending impulses gain
// exactly M g t (momentum_test.cpp). Serial over the particles, in their order: independent of the threads.
#pragma once

#include <array>
#include <functional>
#include <span>
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
  // A particle the yield part held at its last DEM step of the sub-cycle follows the fluid's own change during
  // the flow interval as part of the paste (the correct exchange with beta -> infinity for it: its mass joins
  // the faces' in the implicit solve), instead of meeting that change as a velocity jump at the next cycle's
  // start, which its yield margin (F_y - weight) takes several steps to absorb, slipping meanwhile (the raft's
  // slip, first order in the cycle T: VALIDATION.md). Off: the stick is against the frozen u_p alone. Not
  // bounded: the impulse that carries a held particle is not capped at its yield part's F_y h (VALIDATION.md).
  bool implicit_stick = false;
};

// K of the implicit stick (CouplingSettings::implicit_stick): a held particle's beta in the correct exchange is
// K m / h, its B = m / h to 1 / K.
inline constexpr double kStickBeta = 1e6;

struct CycleStats {
  int flow_steps = 0;
  int stuck_steps = 0;          // particle-steps the yield part held
  int exchange_iterations = 0;  // CG, summed
  double dropped_yield = 0.0;   // N s (exchange.h)
  double clipped_reaction = 0.0;  // N s the bounded reaction gave back to the particles (exchange.h: bound_reaction)
  double returned_reaction = 0.0;  // N s of reaction faces emptied since the cycle's start gave back (exchange.h: react)
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

  // cycle()'s three parts, for a DEM that runs its own steps (the engine's flow pass, model/fluid/flow_coupling.h):
  // begin() is step 1, drag_step() one particle's drag in step 2, finish() steps 3-4. Per particle at the
  // cycle's start: u_p (m/s), the paste share, beta (kg/s).
  using Vec = std::array<double, 3>;
  struct Start {
    std::vector<Vec> u;
    std::vector<double> share, beta;
    std::vector<Vec> shift;  // m/s, what the particle's own displaced fluid adds to u_p (removed: drag.h)
    // Where the drag was computed: the positions (m) and the faces' paste fraction at the cycle's start. The
    // sub-cycle's reaction goes back through these same weights (adjoint of u_p = W u), not through the end
    // positions': a rock that left the paste during the sub-cycle would otherwise put its whole paste drag on
    // the one near-air face its end support still reaches.
    std::vector<Vec> x;
    flow::Faces mask;
    flow::Faces mass;  // kg, the faces' fluid mass then: what the reaction may land on (Exchange::react)
    // Per particle: 1 if the yield part held it at its last DEM step of the sub-cycle (the DEM writes it:
    // drag_step's result), read by finish() with CouplingSettings::implicit_stick.
    std::vector<char> stuck;
  };
  Start begin(const CoupledParticles& p) const { return drag_at_start(p); }
  // Particle i's velocity v (in/out) after a step dt under the force F (N: every force but the paste's drag,
  // the pending pressure impulse's share included), with the drag against the frozen fluid; J (in/out): its
  // summed drag impulse (N s). Returns whether the yield part held it.
  bool drag_step(const CoupledParticles& p, std::size_t i, Vec& v, const Vec& F, double dt, const Start& s0,
                 Vec& J) const {
    return drag_update(step_record(p, i, s0), v, F, dt, J);
  }
  // What drag_step reads of particle i in a cycle, gathered into one record: the engine's kicks
  // (fluid/flow_coupling.h) keep one per particle for the cycle and read it instead of six arrays on every step
  // (drag_step was 12 % of case 3's flow run to 1.2 s, most of it the gather). The same arithmetic either way.
  struct StepRecord {
    Vec u{};            // m/s, the paste velocity the drag acts against: s0.u + s0.shift
    double beta = 0.0;  // kg/s
    double mass = 0.0;  // kg
    double yield = 0.0; // N, the yield part's bound: the paste share x D(0+)
  };
  StepRecord step_record(const CoupledParticles& p, std::size_t i, const Start& s0) const {
    const Vec u{s0.u[i][0] + s0.shift[i][0], s0.u[i][1] + s0.shift[i][1], s0.u[i][2] + s0.shift[i][2]};
    return {u, s0.beta[i], p.m[i], s0.share[i] * p.drag[i].rest};
  }
  // drag_step on a record (above).
  static bool drag_update(const StepRecord& r, Vec& v, const Vec& F, double dt, Vec& J);
  void finish(CoupledParticles& p, double T, const Start& s0, const std::vector<Vec>& sub, CycleStats& st) {
    flow_interval(p, T, s0, sub, st);
  }
  // What the coupling keeps between cycles (the engine's checkpoint and renumbering): per particle the positions
  // of the last flow step, the pending pressure impulses (N s) and the mean paste drag of the last sub-cycle (N);
  // the interval the impulses were summed over (s; 0 before the first flow step). The next begin() reads all of
  // them (the disturbance correction's own hole, drag_at_start).
  struct State {
    std::vector<Vec> x_flow, pending, drag;
    double interval = 0.0;
  };
  State state() const { return {x_flow_, pending_, drag_, pending_interval_}; }
  void restore(State s) {
    x_flow_ = std::move(s.x_flow), pending_ = std::move(s.pending), drag_ = std::move(s.drag);
    pending_interval_ = s.interval;
  }

  const std::vector<std::array<double, 3>>& pending_impulse() const { return pending_; }  // N s per particle
  // N s: sum over faces of eps_f rho_f V u (the fluid's momentum, the masses the flow step ends with).
  std::array<double, 3> fluid_momentum() const;
  const flow::FlowSolver& flow() const { return flow_; }

 private:
  Start drag_at_start(const CoupledParticles& p) const;
  void dem_step(CoupledParticles& p, std::size_t i, double dt, int steps, const ExtraForce& extra, Start& s0,
                std::vector<Vec>& sub, CycleStats& st) const;
  void flow_interval(CoupledParticles& p, double T, const Start& s0, const std::vector<Vec>& sub, CycleStats& st);
  void react_subcycle(const ExchangeParticles& at_start, const Start& s0, const std::vector<Vec>& sub,
                      CoupledParticles& p, flow::Faces& u, const flow::Faces& mass, CycleStats& st) const;
  void bound_subcycle(const ExchangeParticles& at_start, const Start& s0, const std::vector<Vec>& sub,
                      const flow::Faces& before, CoupledParticles& p, flow::Faces& u, const flow::Faces& mass,
                      CycleStats& st) const;
  std::vector<double> fluid_fraction(const CoupledParticles& p) const;  // eps_f = 1 - eps_s per cell
  // Kernel mean of face impulses at a position, over the faces that are not box walls (renormalised there).
  std::array<double, 3> face_mean(const Stencil& s, const flow::Faces& f) const;
  // The kernel's stencils and face weights of the particles at one set of positions. A cycle's end positions
  // are the next cycle's start (drag_at_start, the reaction's weights at Start::x, the pending force's x_flow_),
  // so with two of them kept each cycle computes them once instead of seven times per particle (the stencils and
  // the exchange's rows were ~25 % of case 3's flow run at coupling interval 10). A hit needs the very same
  // positions and diameters: the numbers are those of computing them anew.
  struct Weights {
    std::vector<Vec> x;
    std::vector<double> d;
    std::vector<Stencil> stencil;
    FaceWeights faces;
    long used = 0;  // the cache's clock at the last use
  };
  const Weights& weights_at(std::span<const Vec> x, std::span<const double> d) const;
  flow::FlowSolver& flow_;
  CouplingSettings s_;
  Exchange exchange_;
  std::vector<std::array<double, 3>> x_flow_;  // m: positions at the last flow step (its eps_f)
  std::vector<std::array<double, 3>> pending_;
  double pending_interval_ = 0.0;  // s, the interval pending_ was summed over (0: no flow step yet)
  std::vector<std::array<double, 3>> drag_;  // N, each particle's mean paste drag over the last sub-cycle
  mutable std::array<Weights, 2> weights_;     // the two position sets used last (a memo: not state)
  mutable long clock_ = 0;
};

}  // namespace pastemix::coupling
