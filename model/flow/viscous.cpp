// SPDX-License-Identifier: MIT
// The viscous operator as the gradient of a discrete dissipation:
//   Phi(u) = sum_cells 2 mu_cell sum_c e_cc^2 + sum_edges mu_edge gamma_cd^2,
//   e_cc = du_c/dx_c (cell centre), gamma_cd = du_c/dx_d + du_d/dx_c (on the edge between faces),
// and the force on face a is -1/2 dPhi/du_a. Each term is w (g . u + b)^2, so the matrix is sum w g g^T:
// symmetric positive semi-definite by construction, with the components coupled through gamma_cd, and the
// same stencil as div(2 mu D) on the MAC grid. (All terms carry the same cell volume, which cancels.)
//
// The terms' stencils depend on the grid only, so they are built once (ViscousOperator's constructor) with
// the position of every product in the matrix's value array; a step only refills the values from the new
// viscosities and densities. (Assembling from triplets each step took a third of a step.)
#include <algorithm>
#include <cmath>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include "base/error.h"
#include "model/flow/linear.h"

namespace pastemix::flow {

namespace {

struct Entry {
  int c;        // component
  long face;    // Grid::face index
  double coef;  // 1/m
};

// How a term's weight follows from the cell viscosities.
struct Weight {
  long cells[4];
  int count = 0;
  double scale = 1.0;     // 2 for a normal stress; the edge's volume share for a shear stress
  bool harmonic = false;  // shear: the harmonic mean of the cells; normal: the one cell's viscosity
  int pair = -1;          // shear: 0 xy, 1 xz, 2 yz
};

// Calls term(weight, entries, n, b) for every normal-stress term (one per cell and component).
template <class T>
void normal_terms(const Grid& g, T&& term) {
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const std::array<int, 3> q{i, j, k};
        Weight w;
        w.cells[0] = g.cell(q);
        w.count = 1;
        w.scale = 2.0;
        for (int c = 0; c < 3; ++c) {
          std::array<int, 3> hi = q;
          hi[c] = g.periodic(c) ? (q[c] + 1) % g.n[c] : q[c] + 1;
          const Entry e[2] = {{c, g.face(c, hi), 1.0 / g.h[c]}, {c, g.face(c, q), -1.0 / g.h[c]}};
          term(w, e, 2, 0.0);
        }
      }
}

// One half of gamma_cd on an edge: du_a/dx_b from the two u_a faces either side of the edge along b.
// Returns the share of a full edge volume the term stands for: 1 inside, 1/2 on a no-slip wall (its control
// volume is the half cell between the wall and the first face), 0 on a free-slip or open side (no shear).
double half_gradient(const Grid& g, int a, int b, std::array<int, 3> q, Entry* e, int& n, double& bconst) {
  const int lo = g.wrap_cell(b, q[b] - 1), hi = g.wrap_cell(b, q[b]);
  const double ih = 1.0 / g.h[b];
  if (lo >= 0 && hi >= 0) {
    q[b] = hi;
    e[n++] = {a, g.face(a, q), ih};
    q[b] = lo;
    e[n++] = {a, g.face(a, q), -ih};
    return 1.0;
  }
  const Boundary& wall = g.side(b, lo < 0 ? 0 : 1);
  if (wall.type != BoundaryType::no_slip) return 0.0;
  // Ghost u = 2 U_wall - u_inside: the wall's velocity holds at the wall, half a cell from the face.
  const double uw = wall.wall_velocity[a];
  if (lo < 0) {
    q[b] = hi;
    e[n++] = {a, g.face(a, q), 2.0 * ih};
    bconst -= 2.0 * uw * ih;
  } else {
    q[b] = lo;
    e[n++] = {a, g.face(a, q), -2.0 * ih};
    bconst += 2.0 * uw * ih;
  }
  return 0.5;
}

template <class T>
void shear_terms(const Grid& g, T&& term) {
  for (int c = 0; c < 3; ++c)
    for (int d = c + 1; d < 3; ++d) {
      const int e = 3 - c - d;
      const int nc = g.periodic(c) ? g.n[c] : g.n[c] + 1, nd = g.periodic(d) ? g.n[d] : g.n[d] + 1;
      for (int ke = 0; ke < g.n[e]; ++ke)
        for (int id = 0; id < nd; ++id)
          for (int ic = 0; ic < nc; ++ic) {
            std::array<int, 3> q{};
            q[c] = ic;
            q[d] = id;
            q[e] = ke;
            Entry en[4];
            int n = 0;
            double b = 0.0;
            const double s1 = half_gradient(g, c, d, q, en, n, b);
            const double s2 = half_gradient(g, d, c, q, en, n, b);
            if (s1 * s2 == 0.0) continue;
            Weight w;
            w.scale = s1 * s2;
            w.harmonic = true;
            w.pair = c + d - 1;
            for (int sc = -1; sc <= 0; ++sc)
              for (int sd = -1; sd <= 0; ++sd) {
                std::array<int, 3> r = q;
                r[c] = g.wrap_cell(c, ic + sc);
                r[d] = g.wrap_cell(d, id + sd);
                if (r[c] >= 0 && r[d] >= 0) w.cells[w.count++] = g.cell(r);
              }
            term(w, en, n, b);
          }
    }
}

}  // namespace

ViscousOperator::ViscousOperator(const Grid& g) : g_(g) {
  long next = 0;
  for (int c = 0; c < 3; ++c) {
    dof_[c].assign(g.face_count(c), -1);
    const auto fd = g.face_dims(c);
    for (int k = 0; k < fd[2]; ++k)
      for (int j = 0; j < fd[1]; ++j)
        for (int i = 0; i < fd[0]; ++i) {
          const std::array<int, 3> q{i, j, k};
          if (!g.boundary_face(c, q[c])) dof_[c][g.face(c, q)] = next++;
        }
  }
  size_ = next;
  dof_face_.resize(size_);
  for (int c = 0; c < 3; ++c)
    for (long f = 0; f < static_cast<long>(dof_[c].size()); ++f)
      if (dof_[c][f] >= 0) dof_face_[dof_[c][f]] = {c, f};
  std::vector<Eigen::Triplet<double, long>> trip;
  auto collect = [&](const Weight& w, const Entry* e, int n, double b) {
    terms_.push_back({static_cast<long>(wcells_.size()), w.count, w.scale, w.harmonic, static_cast<long>(dofs_.size()),
                      0, static_cast<long>(fixed_.size()), 0, b, w.pair});
    Term& t = terms_.back();
    for (int a = 0; a < w.count; ++a) wcells_.push_back(w.cells[a]);
    for (int a = 0; a < n; ++a) {
      const long d = dof_[e[a].c][e[a].face];
      if (d < 0) {
        fixed_.push_back({e[a].c, e[a].face, e[a].coef});
        ++t.fixed_count;
      } else {
        dofs_.push_back(d);
        coefs_.push_back(e[a].coef);
        ++t.dof_count;
      }
    }
    for (int a = 0; a < t.dof_count; ++a)
      for (int c = 0; c < t.dof_count; ++c) trip.emplace_back(dofs_[t.dof_begin + a], dofs_[t.dof_begin + c], 1.0);
  };
  normal_terms(g, collect);
  shear_terms(g, collect);
  for (long d = 0; d < size_; ++d) trip.emplace_back(d, d, 1.0);
  M_.resize(size_, size_);
  M_.setFromTriplets(trip.begin(), trip.end());
  M_.makeCompressed();
  // The value index of each product, in the order the solve visits them.
  auto position = [&](long row, long col) {
    const long* begin = M_.innerIndexPtr() + M_.outerIndexPtr()[row];
    const long* end = M_.innerIndexPtr() + M_.outerIndexPtr()[row + 1];
    return static_cast<long>(std::lower_bound(begin, end, col) - M_.innerIndexPtr());
  };
  for (const Term& t : terms_)
    for (int a = 0; a < t.dof_count; ++a)
      for (int c = 0; c < t.dof_count; ++c) positions_.push_back(position(dofs_[t.dof_begin + a], dofs_[t.dof_begin + c]));
  diagonal_.resize(size_);
  for (long d = 0; d < size_; ++d) diagonal_[d] = position(d, d);
}

namespace {

template <class Pre>
SolveStats run_cg(const Matrix& M, const Eigen::VectorXd& rhs, Eigen::VectorXd& x, double tol, int max_iterations) {
  Eigen::ConjugateGradient<Matrix, Eigen::Lower | Eigen::Upper, Pre> cg;
  cg.setTolerance(tol);
  cg.setMaxIterations(max_iterations);
  cg.compute(M);
  x = cg.solveWithGuess(rhs, x);
  SolveStats st;
  st.iterations = static_cast<int>(cg.iterations());
  st.relative_residual = cg.error();
  if (cg.info() != Eigen::Success && !(st.relative_residual <= tol))
    throw RuntimeFailure(fmt::format("flow: the viscous solve did not converge ({} iterations, residual {:.3g})",
                                     st.iterations, st.relative_residual));
  return st;
}

}  // namespace

double ViscousOperator::edge_viscosity(const Term& t, const EdgeLaw& e) const {
  const Faces& u = *e.u;
  double gam = t.b;  // gamma_cd on the edge, 1/s
  for (int a = 0; a < t.dof_count; ++a) {
    const auto& [c, f] = dof_face_[dofs_[t.dof_begin + a]];
    gam += coefs_[t.dof_begin + a] * u[c][f];
  }
  for (int a = 0; a < t.fixed_count; ++a) {
    const Fixed& f = fixed_[t.fixed_begin + a];
    gam += f.coef * u[f.c][f.face];
  }
  double rest = 0.0;
  for (int a = 0; a < t.cell_count; ++a) {
    const double* p = &(*e.cell_parts)[4 * wcells_[t.cell_begin + a]];
    rest += std::max(0.0, p[0] - p[1 + t.pair] * p[1 + t.pair]);
  }
  const double eta = e.paste->viscosity(std::sqrt(gam * gam + rest / t.cell_count));
  double inv = 0.0;
  for (int a = 0; a < t.cell_count; ++a) {
    const double al = std::clamp((*e.alpha)[wcells_[t.cell_begin + a]], 0.0, 1.0);
    inv += 1.0 / (al * eta + (1.0 - al) * e.eta_air);
  }
  return t.cell_count / inv;
}

bool ViscousOperator::touches_wall(const Term& t) const {
  for (int a = 0; a < t.dof_count; ++a) {
    const auto& [c, f] = dof_face_[dofs_[t.dof_begin + a]];
    if (blocked(*blocked_, c, f)) return true;
  }
  for (int a = 0; a < t.fixed_count; ++a) {
    const Fixed& f = fixed_[t.fixed_begin + a];
    if (blocked(*blocked_, f.c, f.face)) return true;
  }
  return false;
}

SolveStats ViscousOperator::solve(double dt, const Faces& rho_face, const std::vector<double>& mu, Faces& u, double tol,
                                  int max_iterations, const EdgeLaw* edge, double force_floor) {
  double* val = M_.valuePtr();
  std::fill(val, val + M_.nonZeros(), 0.0);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size_), x(size_);
  // A wall inside the box (obstacle.h): its faces are unknowns held at 0 (their rows and columns keep only
  // the diagonal), and a shear term with one of them among its faces carries nothing (free slip).
  std::vector<unsigned char> wall;
  if (blocked_ && any_blocked(*blocked_)) {
    wall.assign(size_, 0);
    for (long d = 0; d < size_; ++d) wall[d] = blocked(*blocked_, dof_face_[d].first, dof_face_[d].second);
  }
  long pos = 0;
  for (const Term& t : terms_) {
    if (!wall.empty() && t.harmonic && touches_wall(t)) {
      pos += static_cast<long>(t.dof_count) * t.dof_count;
      continue;
    }
    double w;
    if (t.harmonic && edge) {
      w = t.scale * edge_viscosity(t, *edge);
    } else if (t.harmonic) {
      double inv = 0.0;
      for (int a = 0; a < t.cell_count; ++a) inv += 1.0 / mu[wcells_[t.cell_begin + a]];
      w = t.scale * t.cell_count / inv;
    } else {
      w = t.scale * mu[wcells_[t.cell_begin]];
    }
    double b = t.b;
    for (int a = 0; a < t.fixed_count; ++a) {
      const Fixed& f = fixed_[t.fixed_begin + a];
      b += f.coef * u[f.c][f.face];
    }
    if (!wall.empty()) {  // a blocked unknown is a fixed 0: no row, no column, nothing to b
      for (int a = 0; a < t.dof_count; ++a) {
        const long da = dofs_[t.dof_begin + a];
        const double ca = coefs_[t.dof_begin + a];
        if (!wall[da]) rhs[da] -= w * b * ca;
        for (int c = 0; c < t.dof_count; ++c, ++pos)
          if (!wall[da] && !wall[dofs_[t.dof_begin + c]]) val[positions_[pos]] += w * ca * coefs_[t.dof_begin + c];
      }
      continue;
    }
    for (int a = 0; a < t.dof_count; ++a) {
      const double ca = coefs_[t.dof_begin + a];
      rhs[dofs_[t.dof_begin + a]] -= w * b * ca;
      for (int c = 0; c < t.dof_count; ++c) val[positions_[pos++]] += w * ca * coefs_[t.dof_begin + c];
    }
  }
  for (int c = 0; c < 3; ++c)
    for (long f = 0; f < static_cast<long>(u[c].size()); ++f) {
      const long d = dof_[c][f];
      if (d < 0) continue;
      const double m = rho_face[c][f] / dt;
      const double v = !wall.empty() && wall[d] ? 0.0 : u[c][f];
      val[diagonal_[d]] += m;
      rhs[d] += m * v;
      x[d] = v;
    }
  SolveStats st;
  const double norm = rhs.norm();
  if (norm == 0.0) {
    x.setZero();
  } else {
    // The residual is a force density (N/m3): small against the rhs or against `force_floor` (the weight).
    // Without the floor, a paste at rest (velocities of 1e-10 m/s, rhs = rho u / dt of round-off) was solved
    // to 1e-10 of its round-off: 204 CG iterations per step on the 1 cm mixing box with a Bingham paste.
    // (MIC(0), model/flow/preconditioner.h, was tried for the yield-stress laws: half the iterations on the
    // 16-cell cliff at twice the CPU time, and the same time on the 1 cm Bingham box. Jacobi stays.)
    if (force_floor > norm) tol *= force_floor / norm;
    st = run_cg<Eigen::DiagonalPreconditioner<double>>(M_, rhs, x, tol, max_iterations);
  }
  for (int c = 0; c < 3; ++c)
    for (long f = 0; f < static_cast<long>(u[c].size()); ++f) {
      const long d = dof_[c][f];
      if (d >= 0) u[c][f] = x[d];
    }
  return st;
}

SolveStats viscous_step(const Grid& g, double dt, const Faces& rho_face, const std::vector<double>& mu_cell,
                        Faces& u, double tol, int max_iterations) {
  ViscousOperator op(g);
  return op.solve(dt, rho_face, mu_cell, u, tol, max_iterations);
}

}  // namespace pastemix::flow
