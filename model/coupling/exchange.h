// SPDX-License-Identifier: MIT
// The momentum exchange between particles and the fluid's MAC faces over one coupling step (issue 18, layer 3):
// the drag law's yield part against a frozen fluid velocity, then its velocity-dependent part implicit in both
// phases. Every impulse a particle gets, the faces get with the opposite sign through the same weights, so
// particles + fluid keep their momentum to round-off whatever the step (test).
//
// Weights. A particle's velocity of the fluid is u_p = sum_f W_pf u_f, W the kernel's face weights
// (kernel.h: interpolate_velocity) restricted to the faces that may take a reaction, renormalised to sum 1:
// not a wall face (its velocity is fixed), a positive fluid mass, and with a paste mask (the faces' paste
// fraction) multiplying the weights, so that air faces are masked from the paste drag (an explicit reaction on a
// near-empty face would kick it by many times its mass). A face whose paste fraction is below
// kMinPasteFraction counts as air (weight 0): its mass is then mostly the air's (1.2 kg/m3 against 1.8e3, i.e.
// below ~1e-3 paste the face is lighter than its paste share says), and a dense stream entering the surface
// put its paste drag on faces of paste fraction 1e-7..1e-4 and kicked them to 5-65 m/s at coupling interval 50
// (VALIDATION.md "Dense stream"). A particle whose support holds no such face gets no paste drag (its W row
// is 0). The reaction on the faces is W^T J: adjoint, so sum_f (W^T J)_f = J.
//
// 1. Yield part (bounded, static-friction-like), against the fluid velocity at the start u^n:
//    w = v_p - u_p(u^n); J_y = -m w if m |w| <= F_y dt (the particle sticks to the paste: v_p = u_p(u^n)),
//    else J_y = -F_y dt w / |w|. The faces take -W^T J_y.
// 2. Velocity-dependent part, F = beta (u_p - v_p) (beta in kg/s: the drag law's linear coefficient at the
//    current relative speed), implicit in both phases: with v_p' = (m v_p* + dt beta u_p') / (m + dt beta)
//    eliminated (the exact elimination through the kernel, not per cell), the faces solve
//      (M + dt W^T B W) u' = M u* + dt W^T B v*,   B = diag(beta m / (m + dt beta)),
//    per component by CG (Jacobi; SPD: M > 0 on every face that takes a reaction). Then
//    J_d = dt B (W u' - v*) on each particle, and the faces are set to u* - M^{-1} W^T J_d: the CG solution
//    only decides J_d, the momentum bookkeeping is exact. Stable for any dt beta / m and dt beta / M (test:
//    1e6).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "model/coupling/kernel.h"
#include "model/flow/advection.h"
#include "model/flow/grid.h"

namespace pastemix::coupling {

// A face's paste fraction below this is air for the paste drag (see Weights above): 1 %, where the face's
// paste mass is still ~15 times its air mass.
inline constexpr double kMinPasteFraction = 0.01;

// bound_reaction touches only a face that still holds this share of its reaction's kick after the step's
// stresses had their say: a face that passed most of it on is transmitting a force, not running away.
inline constexpr double kKeptKick = 0.5;
// ... and only a face thin in paste (its paste fraction below this): a paste face carries its reaction on by
// its stresses over the next steps (the raft's faces under its 5 mm spheres, 1 cm cells, keep much of a kick
// within one step and pass it on after).
inline constexpr double kThinPaste = 0.5;

// The kernel's face weights of particles at fixed centres (kernel.h, interpolate_velocity's weights), per
// component: each particle's faces in ascending order, a face reached twice summed, the wall faces left out.
// They depend on the positions alone, so a coupling cycle computes them once per position set
// (Exchange::face_weights) and each exchange call filters them by the faces' mass and paste mask (the rows of
// the Weights note above): the same numbers as computing them in every call, which with the stencils was
// ~25 % of case 3's flow run.
struct FaceWeights {
  std::array<std::vector<std::size_t>, 3> offset;  // n + 1 per component: particle i's entries [offset_i, offset_i+1)
  std::array<std::vector<long>, 3> face;
  std::array<std::vector<double>, 3> w;
  std::size_t size() const { return offset[0].empty() ? 0 : offset[0].size() - 1; }
};

struct ExchangeParticles {
  std::span<const std::array<double, 3>> centre;  // m
  std::span<const double> diameter;               // m
  std::span<const double> mass;                   // kg
  std::span<const double> beta;                   // kg/s, velocity-dependent drag coefficient (>= 0)
  std::span<const double> yield_force;            // N, the bounded yield part of the drag (>= 0)
  const FaceWeights* weights = nullptr;           // the face weights at `centre` (Exchange::face_weights), or
                                                  // null: computed in each call
};

struct ExchangeStats {
  int iterations = 0;              // CG, summed over the components
  double relative_residual = 0.0;  // worst component's, at exit
  int stuck = 0;                   // particles that stuck in the yield part
  double dropped_yield = 0.0;      // N s, |J_sub| of sub-cycle reactions no reacting face could take
  double clipped = 0.0;            // N s, |impulse| bound_reaction gave back to the particles
  int clipped_faces = 0;           // faces bound_reaction brought back to their hull
};

class Exchange {
 public:
  Exchange(const flow::Grid& g, double width_factor);
  // The face weights of particles whose stencils (kernel.h: stencil at their centres) are s.
  FaceWeights face_weights(std::span<const Stencil> s) const;
  // v (m/s, in/out): the particles' velocities; u (m/s, in/out): the faces'; face_mass (kg): the fluid's mass
  // in each face's control volume (eps_f rho_f V); paste_mask: nullptr, or the faces' paste fraction.
  // impulse (out, N s): what each particle received. Throws std::invalid_argument on sizes or negative inputs,
  // RuntimeFailure if CG does not converge.
  ExchangeStats apply(double dt, const ExchangeParticles& p, std::vector<std::array<double, 3>>& v, flow::Faces& u,
                      const flow::Faces& face_mass, const flow::Faces* paste_mask,
                      std::vector<std::array<double, 3>>& impulse) const;
  // After a DEM sub-cycle that ran the drag against the frozen fluid itself (coupled_flow.h: each DEM step
  // applies the velocity-dependent part implicitly per particle and the yield stick against the fluid velocity
  // u_ref that `fluid_velocity` gave, and sums the impulses J_sub), the flow step does two things:
  //  react:   the faces take the sub-cycle's reaction -W^T J_sub (N s per particle), before the viscous solve
  //           (which spreads it in the same step);
  //  correct: after the projection, the fluid's own change since u_ref, with the velocity-dependent part
  //           implicit in both phases: J = dt B (W u' - u_ref), (M + dt W^T B W) u' = M u + dt W^T B u_ref
  //           (0 when the fluid at the particles did not change: the sub-cycle's drag is not applied twice,
  //           and a steady state does not depend on dt). impulse (out): J. p.yield_force is not used.
  // A particle whose support holds no reacting face passes its reaction to none: the sub-cycle gave it no drag
  // then (fluid_velocity's share 0), unless the paste left its faces during the step; that share is dropped
  // and reported (ExchangeStats::dropped_yield).
  // With `start_mass` (kg, the faces' fluid mass when the sub-cycle's drag was computed: the cycle's start) a
  // face takes the share min(1, m_now / m_start) of its reaction and the particles reacting on it get back the
  // rest (`returned`, N s, to add to their momentum; momentum is kept to round-off): the drag ran against the
  // fluid of the cycle's start, and the part of it that left the face (advected away in the sub-step before the
  // reaction, or displaced by the particles' volume) cannot take its momentum. The face's kick is then at most
  // R / m_start, what the drag was computed against. Without it (the flow's advection emptying a face of the
  // cycle's start between drag and reaction) chapter-7 test 3's splash put the reaction of a 50 mm rock on a face
  // of paste fraction 0.016 and kicked it from 7.6 to 326 m/s (docs/mixing_scenes.md).
  ExchangeStats react(const ExchangeParticles& p, flow::Faces& u, const flow::Faces& face_mass,
                      const flow::Faces* paste_mask, const std::vector<std::array<double, 3>>& subcycle_impulse,
                      const flow::Faces* start_mass = nullptr,
                      std::vector<std::array<double, 3>>* returned = nullptr) const;
  // In the step that took the reaction, after its viscous solve (which carries a reaction on through the
  // fluid's stresses) and before its projection (which would spread a face's excess over its neighbours): a face whose reaction left it outside the hull of its velocity before the reaction
  // (`before`) and the velocities of the particles reacting on it (`velocity`, m/s) is brought back to the
  // hull, by at most its reaction, and those particles get back their part of what it gives up (`returned`,
  // N s, to add to their momentum): particles + fluid keep their momentum to round-off. Why: the sub-cycle's
  // drag ran against a frozen fluid, as if its mass were infinite; a face lighter than the particles stuck to
  // it and too thin in paste to pass the force on (a rock pile in air-filled pores beside a paste film of a
  // few %: ~1e-5 kg faces under 1e-4 kg rocks) was kicked past them, and the next cycle kicked it back harder
  // (case 3 at t = 1.305 s: 0.19 -> 16 m/s in one reaction, 60 m/s two cycles later; VALIDATION.md). A face
  // that passes the force on (a yield-held sphere, a settling one) is not touched: only a face beyond the hull
  // that still holds kKeptKick of its reaction's kick is.
  // Same p, face_mass, paste_mask, subcycle_impulse and start_mass as the react call (a face's kick is then the
  // share of its reaction react let it take).
  ExchangeStats bound_reaction(const ExchangeParticles& p, const flow::Faces& before, flow::Faces& u,
                               const flow::Faces& face_mass, const flow::Faces* paste_mask,
                               const std::vector<std::array<double, 3>>& subcycle_impulse,
                               std::span<const std::array<double, 3>> velocity,
                               std::vector<std::array<double, 3>>& returned,
                               const flow::Faces* start_mass = nullptr) const;
  ExchangeStats correct(double dt, const ExchangeParticles& p, std::vector<std::array<double, 3>>& v, flow::Faces& u,
                        const flow::Faces& face_mass, const flow::Faces* paste_mask,
                        const std::vector<std::array<double, 3>>& reference,
                        std::vector<std::array<double, 3>>& impulse) const;
  // The fluid velocity each particle's drag sees, W u (m/s), with the weights above, and its paste share: the
  // masked weights' sum over the unmasked one (mean over the components), 0 where the particle's support holds
  // no face that takes a reaction (no paste drag: u_p = 0 returned). The caller scales the drag by the share
  // (a sphere half in the paste: half its drag, as the at-rest pass's submerged fraction).
  std::vector<std::array<double, 3>> fluid_velocity(const ExchangeParticles& p, const flow::Faces& u,
                                                    const flow::Faces& face_mass, const flow::Faces* paste_mask,
                                                    std::vector<double>& paste_share) const;

  double tolerance = 1e-13;  // CG, relative residual
  int max_iterations = 2000;

 private:
  struct Row {  // one particle's faces and weights for one component (a view into its RowTable)
    std::span<const long> face;
    std::span<const double> w;
    double at(const std::vector<double>& field) const;               // sum_f w_f field_f
    void spread(double amount, std::vector<double>& field) const;    // field_f += w_f amount
  };
  struct RowTable {  // one component's rows of all particles, stored flat (no allocation per particle)
    std::vector<std::size_t> offset{0};
    std::vector<long> face;
    std::vector<double> w;
    Row operator[](std::size_t i) const {
      const std::size_t b = offset[i], n = offset[i + 1] - b;
      return {{face.data() + b, n}, {w.data() + b, n}};
    }
  };
  using Rows = std::array<RowTable, 3>;
  // Component c of each particle's share of what its faces gave up (given_up: per face, the fraction of its
  // reaction -W^T J it did not keep), N s, into returned; |returned| summed into st.clipped.
  static void hand_back(int c, const RowTable& W, const std::vector<double>& given_up,
                        const std::vector<std::array<double, 3>>& subcycle_impulse,
                        std::vector<std::array<double, 3>>& returned, ExchangeStats& st);
  Rows rows(const ExchangeParticles& p, const flow::Faces& face_mass, const flow::Faces* paste_mask,
            std::vector<double>* share = nullptr) const;
  // Stage 1 (yield, against the frozen u) and stage 2 for one component (implicit drag); both update v, u and
  // impulse, and give the faces exactly the opposite of what the particles get.
  void check(const ExchangeParticles& p, const std::vector<std::array<double, 3>>& v) const;
  static void yield_part(double dt, const ExchangeParticles& p, const Rows& W, std::vector<std::array<double, 3>>& v,
                         flow::Faces& u, const flow::Faces& face_mass, std::vector<std::array<double, 3>>& impulse,
                         ExchangeStats& st);
  // reference: nullptr (the particles' own velocities v*), or per particle the fluid velocity the sub-cycle's
  // drag relaxed it to: then only the fluid's change from it is exchanged (apply_after_subcycle).
  void drag_part(int c, double dt, const ExchangeParticles& p, const Rows& W, std::vector<std::array<double, 3>>& v,
                 std::vector<double>& u, const std::vector<double>& M, std::vector<std::array<double, 3>>& impulse,
                 ExchangeStats& st, const std::vector<std::array<double, 3>>* reference = nullptr) const;
  flow::Grid g_;
  double c_;
};

}  // namespace pastemix::coupling
