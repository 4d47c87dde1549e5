// SPDX-License-Identifier: MIT
// The two linear solves of a flow step (the implicit viscous step and the pressure projection), both
// symmetric positive definite and solved by Eigen's conjugate gradients: the viscous step with a Jacobi
// preconditioner (its matrix is rho/dt-dominated at a step limited by advection: 1-20 iterations), the pressure
// with MIC(0) (model/flow/preconditioner.h: Jacobi needed O(n) iterations on an n-cell-wide grid).
//
// Eigen runs the row-major sparse product of each iteration on all threads; every row is summed by one thread
// in a fixed order, the dot products and MIC(0)'s triangular solves are serial, so the result does not depend
// on the thread count.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

#include "model/flow/advection.h"
#include "model/flow/grid.h"
#include "model/flow/obstacle.h"
#include "model/flow/rheology.h"

namespace pastemix::flow {

struct SolveStats {
  int iterations = 0;
  double relative_residual = 0.0;  // ||b - A x|| / ||b|| at exit (0 for b = 0)
};

using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor, long>;

// Implicit viscous step with the velocity components coupled:
//   rho_f (u_new - u) / dt = div(2 mu D(u_new))
// D the symmetric strain rate; mu per cell (Pa s): normal stresses use the cell's viscosity, shear stresses the
// harmonic mean of the cells around their edge. Walls: no-slip (a ghost value gives the wall velocity at the
// wall), free-slip and open sides carry no shear. Solved in place to `tol`; throws RuntimeFailure if not reached.
SolveStats viscous_step(const Grid& g, double dt, const Faces& rho_face, const std::vector<double>& mu_cell,
                        Faces& u, double tol, int max_iterations);

// The same, with the stencils built once for a grid (the solver keeps one; viscous_step builds one per call).
// A shear-dependent paste law evaluated on each shear edge at the edge's own strain rate (model/flow/bingham.h
// says why: a cell-centred strain rate smears a plug's edge over two cells). The edge's rate is
//   gd_edge^2 = gamma_cd(edge)^2 + mean over its cells of (2 D:D - gamma_cd^2)  (1/s^2),
// gamma_cd = du_c/dx_d + du_d/dx_c from the lagged velocity with the operator's own stencil (exact for a
// layered shear flow), the other components from the cells. Each cell's mixture viscosity at that rate,
// alpha eta(gd_edge) + (1 - alpha) eta_air, enters the harmonic mean as before.
struct EdgeLaw {
  const Rheology* paste = nullptr;
  const std::vector<double>* alpha = nullptr;
  double eta_air = 0.0;                          // Pa s
  const Faces* u = nullptr;                      // the velocity the strain rates come from (start of step)
  const std::vector<double>* cell_parts = nullptr;  // per cell: 2 D:D, gamma_xy, gamma_xz, gamma_yz
};

class ViscousOperator {
 public:
  explicit ViscousOperator(const Grid& g);
  // mu_cell: the cells' viscosities (normal stresses; shear edges too unless `edge` is given). The solve stops
  // when the residual (N/m3, 2-norm over the unknowns) is below tol times the larger of ||rhs|| and
  // force_floor (the solver passes the weight, ||rho_f g||: a paste at rest is not solved to its round-off).
  SolveStats solve(double dt, const Faces& rho_face, const std::vector<double>& mu_cell, Faces& u, double tol,
                   int max_iterations, const EdgeLaw* edge = nullptr, double force_floor = 0.0);
  // Walls inside the box (obstacle.h), or none (nullptr or an empty mask): a blocked face is held at u = 0 and
  // the shear terms of the edges around it carry nothing (free slip on the wall). Kept by pointer: the
  // caller owns the mask and may change it between solves.
  void set_blocked(const FaceMask* m) { blocked_ = m; }

 private:
  struct Term {
    long cell_begin;
    int cell_count;
    double scale;
    bool harmonic;
    long dof_begin;
    int dof_count;
    long fixed_begin;
    int fixed_count;
    double b;  // 1/s, the wall velocities' part of the strain rate
    int pair;  // shear terms: 0 xy, 1 xz, 2 yz; -1 normal
  };
  struct Fixed {
    int c;
    long face;
    double coef;
  };
  Grid g_;
  std::array<std::vector<long>, 3> dof_;
  long size_ = 0;
  std::vector<Term> terms_;
  std::vector<long> wcells_, dofs_, positions_, diagonal_;
  std::vector<double> coefs_;
  std::vector<Fixed> fixed_;
  std::vector<std::pair<int, long>> dof_face_;  // (component, face) of each unknown
  Matrix M_;
  const FaceMask* blocked_ = nullptr;
  double edge_viscosity(const Term& t, const EdgeLaw& e) const;
  bool touches_wall(const Term& t) const;  // a shear term with a blocked face among its faces
};

// Pressure projection: solves div((dt / rho_f) grad p) = div u (p in Pa; on an open side 0 where the fluid
// leaves and -rho u_n^2 / 2 where it comes in, Dong et al. 2014's energy-stable condition; in a closed box
// defined up to a constant, returned with p = 0 in cell 0) and sets u -= (dt / rho_f) grad p, so that
// ||div u_new|| / ||div u*|| <= tol, recomputed from the updated faces (RuntimeFailure otherwise). `p` is the
// initial guess and the result.
struct ProjectionStats {
  SolveStats solve;
  double divergence_before = 0.0;  // ||div u*||_2 (1/s), before
  double divergence_after = 0.0;   // ||div u||_2 (1/s), after
  double max_volume_loss = 0.0;    // max over cells of |div u| dt: fraction of a cell's volume per step
};
ProjectionStats project(const Grid& g, double dt, const Faces& rho_face, Faces& u, std::vector<double>& p, double tol,
                        int max_iterations);

// The volume-averaged projection (particles in the flow, model/coupling): with the fluid's volume fraction
// eps_f on the faces, the constraint is the fluid's continuity, div(eps_f u) = -d eps_f/dt, and the operator
// div(eps_f (dt / rho_f) grad p). The velocity update u -= (dt / rho_f) grad p is unchanged: in the momentum
// equation eps_f rho_f du/dt = -eps_f grad p + ... (Kloss et al. 2012 model A) the fraction cancels. The
// stopping test is ||div(eps_f u_new) + rate|| / ||div(eps_f u*) + rate||. Absent (nullptr): eps_f = 1, the
// plain projection, bit for bit.
struct FluidFraction {
  const Faces* face = nullptr;               // eps_f on the faces, in (0, 1]
  const std::vector<double>* rate = nullptr;  // d eps_f / dt per cell (1/s); nullptr: 0
};

// The same, with the matrix pattern built once for a grid (the solver keeps one).
class PressureOperator {
 public:
  explicit PressureOperator(const Grid& g);
  // inflow_pressure = false: the outside pressure is 0 on every open face (a correction such as the continuity
  // projection's, whose result is not the pressure); true: set_inflow_velocity's.
  ProjectionStats project(double dt, const Faces& rho_face, Faces& u, std::vector<double>& p, double tol,
                          int max_iterations, const FluidFraction* eps = nullptr, bool inflow_pressure = true);
  // u -= (dt / rho_f) grad p on every face the projection acts on (the same discrete gradient, p = 0 outside an
  // open side): the pressure-gradient part of a step (a negative dt adds it back). Stateless, so a step resumed
  // from a checkpoint predicts with the same bits; the projection then solves for the whole pressure with the
  // open side's inflow pressure.
  void subtract_gradient(double dt, const Faces& rho_face, const std::vector<double>& p, Faces& u) const;
  // The impulse density of that gradient, out = dt grad p (N s/m3) on the same faces (0 elsewhere): the fluid's
  // velocity change is -out / rho_f; a particle's share of it (model A) is -V_p times its kernel mean.
  // Outside an open side: the last project()'s boundary pressure (call it right after that project()).
  void gradient_impulse(double dt, const std::vector<double>& p, Faces& out) const;
  // Walls inside the box (obstacle.h), or none: a blocked face drops out of the operator (no flux: Neumann,
  // the pressure may jump across the wall) and the gradient leaves its velocity alone. Kept by pointer.
  void set_blocked(const FaceMask* m) { blocked_ = m; }
  // The density of the fluid an open side lets in (kg/m3; the solver's air), for the inflow pressure
  // -rho_in u_n^2 / 2; 0 (the default): the face's own density.
  void set_inflow_density(double rho_in) { inflow_density_ = rho_in; }
  // The open side's outside pressure for the next project() calls, from the step's start velocity u (Dong et
  // al. 2014: -rho_in u_n^2 / 2 on a face where u comes in, 0 where it leaves); all 0 until called.
  void set_inflow_velocity(const Faces& u, const Faces& rho_face);

 private:
  struct Link {
    int c;
    long face, a, b;           // the face's cells (-1: outside, an open side)
    long paa, pbb, pab, pba;   // value positions
  };
  // The operator's values (no pin: singular in a closed box), weighted by eps_f on the faces if given.
  void fill(double dt, const Faces& rho_face, const FluidFraction* eps);
  // p = x (shifted to p_0 = 0 in a closed box), u = u_star - (dt / rho_f) grad p, div = div u (or the fluid's
  // continuity residual, with eps); returns ||div||.
  double apply(double dt, const Faces& rho_face, const Faces& u_star, Eigen::VectorXd& x, std::vector<double>& p,
               Faces& u, std::vector<double>& div, const FluidFraction* eps) const;
  void open_side_rhs(double dt, const Faces& rho_face, const FluidFraction* eps, Eigen::VectorXd& rhs) const;
  Grid g_;
  std::vector<Link> links_;
  bool open_ = false;
  const FaceMask* blocked_ = nullptr;
  bool wall(const Link& l) const { return blocked_ && blocked(*blocked_, l.c, l.face); }
  std::vector<double> open_p_;    // Pa, outside pressure of each link in the last project()
  std::vector<double> inflow_p_;  // Pa, the same from set_inflow_velocity (0 but on an inflowing open face)
  double inflow_density_ = 0.0;  // kg/m3
  std::vector<double> zero_;    // 0 per link: subtract_gradient's outside pressure
  void subtract_gradient(double dt, const Faces& rho_face, const std::vector<double>& p, Faces& u,
                         const std::vector<double>& open_p) const;
  long pin_ = 0;  // value position of cell 0's diagonal (pinned in the closed box's preconditioner)
  Matrix A_;
};

// Discrete divergence of u per cell (1/s).
std::vector<double> divergence(const Grid& g, const Faces& u);
// The fluid's continuity residual per cell, div(eps_f u) + d eps_f/dt (1/s); div u for eps = nullptr.
std::vector<double> continuity_residual(const Grid& g, const Faces& u, const FluidFraction* eps);

}  // namespace pastemix::flow
