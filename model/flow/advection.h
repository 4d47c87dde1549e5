// SPDX-License-Identifier: MIT
// Transport of the paste fraction and of the momentum: conservative, bounded, and consistent with each other.
//
// The paste fraction alpha is advected by the operator-split geometric VOF of Weymouth & Yue (2010, J. Comput.
// Phys. 229, 2853-2865): one 1-D sweep per axis (order rotated every step), PLIC fluxes from a Youngs normal,
// and the dilatation term c (div_d u) dt with c = 1 in cells that were more than half paste at the start of
// the step. The sweeps telescope, so the paste volume changes only by the leftover divergence of the velocity
// (the projection's tolerance), and with CFL <= 1/2 per sweep alpha stays in [0, 1] up to round-off.
//
// The momentum rho u of each face's control volume is advected in the same sweeps with the mass fluxes of the
// VOF sweep (rho_air V + (rho_paste - rho_air) F, averaged onto the control volume's faces) and the same
// dilatation term, together with the control volume's own density (Rudman 1998; Arrufat et al. 2021). A
// heavy fluid crossing into a light one then carries its momentum with its mass, instead of a light cell
// receiving a heavy cell's velocity jump. The face value of u is an upwind-biased, Koren-limited (TVD)
// interpolation: second order where the flow is smooth, no new extrema at the interface. In a control volume
// holding both phases the averaged mass fluxes need not match its content, so there the new velocity is
// bounded by the old ones it depends on (the face and its neighbours along the sweep) and the momentum set
// to match; single-phase volumes are transported untouched.
#pragma once

#include <array>
#include <vector>

#include "model/flow/grid.h"
#include "model/flow/obstacle.h"
#include "model/flow/rheology.h"

namespace pastemix::flow {

using Faces = std::array<std::vector<double>, 3>;  // one array per velocity component, Grid::face indexing

// The largest |u_d| dt / h_d (with particles, of the volume flux eps_f u) a sweep of advect() takes: the split
// VOF sweeps stay bounded up to 1/2 (1e-12 for the round-off of a step chosen at the bound).
inline constexpr double kMaxSweepCfl = 0.5 + 1e-12;

struct AdvectionStats {
  double alpha_min = 0.0, alpha_max = 0.0;  // after the step (round-off below 0 / above 1 is not clipped)
  double max_cfl = 0.0;                     // max over faces of |u_d| dt / h_d
};

// The fluid's volume fraction over a step, when particles share the cells (model/coupling). alpha is then the
// paste's share of the fluid, and what is transported is the paste's share of the cell, eps_f alpha:
//   d(eps_f alpha)/dt + div(eps_f alpha u) = 0,
// with the fluid's volume flux eps_f u through the faces, u the interstitial velocity, whose fluid continuity
// div(eps_f u) = -(eps_new - eps_old) / dt holds over the step (the solver projects u for it before advecting).
struct FluidFractionStep {
  const std::vector<double>* old_cell = nullptr;  // eps_f per cell at the start of the step
  const std::vector<double>* new_cell = nullptr;  // at the end
  const Faces* new_face = nullptr;                // at the end, on the faces (face_fractions of new_cell)
};

// Advances alpha and the face velocities over dt. The advecting velocity is u as given (divergence-free,
// from the last projection); on return u holds the advected velocity. `step` picks the sweep order.
// Blocked faces (obstacle.h; u = 0 there) carry no flux and, like the box's walls, keep their velocity.
// With eps (not nullptr): the volume-averaged transport above; the sweeps are Weymouth & Yue's on
// eps_old alpha with the fluxes of eps_f u, their dilatation terms taken back at the end, so that the paste
// volume sum eps_f alpha V changes only by what crosses the box's sides (to round-off, whatever the
// continuity residual) and a full cell ends full to the projection's tolerance. Without eps: bit for bit the
// plain transport.
AdvectionStats advect(const Grid& g, const Phases& ph, double dt, long step, std::vector<double>& alpha, Faces& u,
                      const FaceMask* blocked_faces = nullptr, const FluidFractionStep* eps = nullptr);

// Face values of a cell field: the mean of the face's two cells; a boundary face takes its one cell's.
Faces face_means(const Grid& g, const std::vector<double>& cells);

// Face densities (kg/m3) from the cell fractions: the mean of the two cells' densities; a boundary face
// takes its one cell's.
Faces face_densities(const Grid& g, const Phases& ph, const std::vector<double>& alpha);

}  // namespace pastemix::flow
