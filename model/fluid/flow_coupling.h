// SPDX-License-Identifier: MIT
// The engine's side of `[[fluid]] dynamics = "flow"` (issue 18, part 3): the region's paste solved by the flow
// solver (model/flow) on the region's grid, coupled both ways with the World's particles through
// model/coupling's CoupledFlow, every coupling_interval DEM steps (the cycle, coupled_flow.h):
//
//   - at a cycle's start (the pass's prepare(), one thread, positions at t, velocities at t - dt/2): the flow
//     interval of the cycle that ends here (eps_f from the particles' new positions, the sub-cycle's summed
//     drag impulses onto the faces before the viscous solve, the fluid's own change exchanged implicitly in
//     both phases after the projection: this changes the particles' velocities now, and model A's -V_p grad p
//     becomes the pending impulse of the next cycle), then the drag at the new cycle's start (u_p, beta, the
//     paste share, frozen over the cycle);
//   - every half kick of a particle in the flow box: v <- the drag step of coupled_flow.h (implicit against the
//     frozen u_p, the yield stick) under F = contacts + m g + pending / T, T = coupling_interval dt, its drag
//     impulse summed into the cycle's J.
// So the DEM's velocity Verlet keeps its contacts, walls and gravity, and the paste's drag and pressure force
// take the place of the at-rest pass's buoyancy + drag kick. The collective (bearing-capacity) rule is not
// used (fluid_scene.cpp refuses it): the paste's stress carries a pile. Air faces are masked from the paste
// drag (exchange.h): a particle in the air above the paste gets no paste drag.
//
// Which particles: those whose centre is in the flow box (the region's x-y extent, bottom to top) at the
// cycle's start; a particle outside it takes the World's plain kick and puts no solid into the grid (the
// kernel folds a sphere at the box walls, so a member deposits its whole volume).
//
// Everything here runs on one thread in particle order, and the particles' own kicks are per particle: the
// bits do not depend on the thread count. Only the flow scenes pay any of it (the pass is inactive without a
// flow region).
#pragma once

#include <omp.h>

#include <array>
#include <cstdint>
#include <exception>
#include <memory>
#include <vector>

#include "model/fluid/field.h"
#include "model/particles.h"
#include "model/vec3.h"

namespace pastemix::model {
struct CheckpointAccess;
}

namespace pastemix::flow {
class FlowSolver;
}

namespace pastemix::model::fluid {

// What the result file records of the flow at a snapshot (model/output.h), cell arrays [k][j][i].
struct FlowFields {
  std::array<int, 3> n{};          // cells
  std::array<double, 3> h{}, origin{};  // m
  std::vector<double> paste_fraction, fluid_fraction, pressure;  // -, -, Pa
  std::vector<double> velocity;    // m/s, cells x 3 (face means)
};

// The flow and the coupling on the calling thread alone, for the scope: inside the World's team they are serial
// anyway (no nested parallelism), and a World of one thread would otherwise give the flow solver's loops every
// core, whose barriers on a grid of a few thousand cells cost more than the loops (measured: 300 times slower at
// 432 cells on 2 loaded cores), and whose bits would then depend on the thread count. The validation cases
// (flow_piston.h, flow_stability.h) run in one for their own reads of the flow (energies, volumes).
struct OneThread {
  int saved = omp_get_max_threads();
  OneThread() { omp_set_num_threads(1); }
  ~OneThread() { omp_set_num_threads(saved); }
  OneThread(const OneThread&) = delete;
  OneThread& operator=(const OneThread&) = delete;
};

class FlowCoupling {
 public:
  // region: a flow region (FluidRegion::flow); dt and gravity: the World's (s, m/s2).
  FlowCoupling(FluidRegion region, double dt, const Vec3& gravity);
  ~FlowCoupling();
  FlowCoupling(const FlowCoupling&) = delete;
  FlowCoupling& operator=(const FlowCoupling&) = delete;

  // Once per step, before the pair forces (one thread): the first call starts the coupling, every
  // coupling_interval-th closes the cycle and opens the next. Returns the particles whose velocity it changed
  // (the World refreshes their ghost copies), ascending.
  // A failure in there (the flow's RuntimeFailure: a time-step collapse, a non-finite field) cannot leave the
  // World's parallel region: it is kept, later calls do nothing, and rethrow() (the World, after the region)
  // throws it.
  const std::vector<long>& prepare(Particles& p);
  void rethrow() const {
    if (failure_) std::rethrow_exception(failure_);
  }
  bool claims(long a) const { return member_[static_cast<std::size_t>(a)] != 0; }
  const std::vector<long>& members() const { return members_; }
  // A stamp that changes whenever members() may have (a cycle's start, a renumbering, a restore): the flow
  // pass splits the members by thread again only then (forces/flow_forces.h).
  long membership() const { return membership_; }
  // The half kick h (s) of member a under F (N: contacts + m g): the paste's drag and pending pressure force.
  Vec3 kick(long a, const Vec3& v, const Vec3& F, double mass, double h) const;
  // N: the pressure force the kick hands member a in this cycle (model A's -V_p grad p with the hydrostatic
  // part, the pending impulse over the cycle); 0 for a non-member or before the first cycle. For diagnostics
  // (validation/fluid/steel_ball_flow.h: the force split of a settling ball).
  Vec3 pressure_force(long a) const;

  // The whole dynamic state as bytes (model/checkpoint.cpp), and back: the flow solver's fields, the coupling's
  // pending impulses, the cycle's drag and impulses, the members. restore() takes the World's particles as
  // restored (their radii and masses give each one's drag law again, the same values): a resumed run gives the
  // same bits as one that never stopped. A damaged state is an InputError (model/state_bytes.h).
  std::vector<char> save() const;
  void restore(const std::vector<char>& bytes, const Particles& p);

  // The World renumbered its particles (map: old -> new dense index; kGone entries were removed).
  void renumber(const std::vector<std::uint32_t>& map, std::size_t count);

  const FluidRegion& region() const;
  const flow::FlowSolver& solver() const;
  FlowFields fields() const;
  double paste_volume() const;  // m3
  long cycles() const { return cycles_; }
  long flow_steps() const;    // the flow solver's steps so far
  // The flow solver's cost so far: its linear solves' iterations, and its wall time (s).
  long pressure_iterations() const;
  long viscous_iterations() const;
  double solver_seconds() const;
  double solver_time() const;  // s, the flow's time (the last cycle's end)

 private:
  friend struct pastemix::model::CheckpointAccess;  // model/checkpoint.cpp: saves and restores the state
  struct State;  // flow_coupling.cpp: the solver, the coupling, the cycle's arrays
  void start(const Particles& p);
  void cycle(Particles& p);  // prepare()'s work: start, or close the cycle and open the next
  void begin_cycle(const Particles& p);
  std::unique_ptr<State> s_;
  std::vector<char> member_;   // per particle: in the flow box at the cycle's start
  std::vector<long> members_;  // ascending
  std::vector<long> changed_;  // scratch of prepare()
  long step_in_cycle_ = 0, cycles_ = 0, membership_ = 0;
  bool started_ = false;
  std::exception_ptr failure_;
};

}  // namespace pastemix::model::fluid
