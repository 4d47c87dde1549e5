// SPDX-License-Identifier: MIT
// The viscous operator as the gradient of a discrete dissipation:
//   Phi(u) = sum_cells 2 mu_cell sum_c e_cc^2 + sum_edges mu_edge gamma_cd^2,
//   e_cc = du_c/dx_c (cell centre), gamma_cd = du_c/dx_d + du_d/dx_c (on the edge between faces),
// and the force on face a is -1/2 dPhi/du_a. Each term is w (g . u + b)^2, so the matrix is sum w g g^T:
// symmetric positive semi-definite by construction, with the components coupled through gamma_cd, and the
// same stencil as div(2 mu D) on the MAC grid. (All terms carry the same cell volume, which cancels.)
#include <cmath>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include "base/error.h"
#include "model/flow/linear.h"

namespace pastemix::flow {

namespace {

struct Entry {
  int c;       // component
  long face;   // Grid::face index
  double coef; // 1/m
};

class Assembler {
 public:
  Assembler(const Grid& g, const Faces& u) : g_(g), u_(u) {
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
    rhs_.setZero(size_);
  }
  long size() const { return size_; }
  long dof(int c, long f) const { return dof_[c][f]; }

  // Adds w (sum coef u + b)^2 to Phi; known (boundary) velocities move into b.
  void term(double w, const Entry* e, int n, double b) {
    long idx[4];
    double cf[4];
    int m = 0;
    for (int a = 0; a < n; ++a) {
      const long d = dof_[e[a].c][e[a].face];
      if (d < 0) {
        b += e[a].coef * u_[e[a].c][e[a].face];
      } else {
        idx[m] = d;
        cf[m++] = e[a].coef;
      }
    }
    for (int a = 0; a < m; ++a) {
      rhs_[idx[a]] -= w * b * cf[a];
      for (int c = 0; c < m; ++c) trip_.emplace_back(idx[a], idx[c], w * cf[a] * cf[c]);
    }
  }
  void diagonal(long d, double value, double rhs) {
    trip_.emplace_back(d, d, value);
    rhs_[d] += rhs;
  }
  std::vector<Eigen::Triplet<double, long>>& triplets() { return trip_; }
  Eigen::VectorXd& rhs() { return rhs_; }

 private:
  const Grid& g_;
  const Faces& u_;
  std::array<std::vector<long>, 3> dof_;
  long size_ = 0;
  std::vector<Eigen::Triplet<double, long>> trip_;
  Eigen::VectorXd rhs_;
};

void normal_terms(const Grid& g, const std::vector<double>& mu, Assembler& A) {
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const std::array<int, 3> q{i, j, k};
        const double w = 2.0 * mu[g.cell(q)];
        for (int c = 0; c < 3; ++c) {
          std::array<int, 3> hi = q;
          hi[c] = g.periodic(c) ? (q[c] + 1) % g.n[c] : q[c] + 1;
          const Entry e[2] = {{c, g.face(c, hi), 1.0 / g.h[c]}, {c, g.face(c, q), -1.0 / g.h[c]}};
          A.term(w, e, 2, 0.0);
        }
      }
}

// One half of gamma_cd on an edge: du_a/dx_b from the two u_a faces either side of the edge along b
// (face index fa along a, cells lo/hi along b). Returns the share of a full edge volume the term stands for:
// 1 inside, 1/2 on a no-slip wall (its control volume is the half cell between the wall and the first face),
// 0 on a free-slip or open side (no shear there).
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

void shear_terms(const Grid& g, const std::vector<double>& mu, Assembler& A) {
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
            const double share = half_gradient(g, c, d, q, en, n, b) * half_gradient(g, d, c, q, en, n, b);
            if (share == 0.0) continue;
            // Harmonic mean of the (up to 4) cells around the edge.
            double inv = 0.0;
            int count = 0;
            for (int sc = -1; sc <= 0; ++sc)
              for (int sd = -1; sd <= 0; ++sd) {
                std::array<int, 3> r = q;
                r[c] = g.wrap_cell(c, ic + sc);
                r[d] = g.wrap_cell(d, id + sd);
                if (r[c] < 0 || r[d] < 0) continue;
                inv += 1.0 / mu[g.cell(r)];
                ++count;
              }
            A.term(share * count / inv, en, n, b);
          }
    }
}

}  // namespace

SolveStats viscous_step(const Grid& g, double dt, const Faces& rho_face, const std::vector<double>& mu_cell,
                        Faces& u, double tol, int max_iterations) {
  Assembler A(g, u);
  normal_terms(g, mu_cell, A);
  shear_terms(g, mu_cell, A);
  Eigen::VectorXd x(A.size());
  for (int c = 0; c < 3; ++c)
    for (long f = 0; f < static_cast<long>(u[c].size()); ++f) {
      const long d = A.dof(c, f);
      if (d < 0) continue;
      const double m = rho_face[c][f] / dt;
      A.diagonal(d, m, m * u[c][f]);
      x[d] = u[c][f];
    }
  Eigen::SparseMatrix<double, Eigen::RowMajor, long> M(A.size(), A.size());
  M.setFromTriplets(A.triplets().begin(), A.triplets().end());
  SolveStats st;
  if (A.rhs().squaredNorm() == 0.0) {
    x.setZero();
  } else {
    Eigen::ConjugateGradient<decltype(M), Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>> cg;
    cg.setTolerance(tol);
    cg.setMaxIterations(max_iterations);
    cg.compute(M);
    x = cg.solveWithGuess(A.rhs(), x);
    st.iterations = static_cast<int>(cg.iterations());
    st.relative_residual = cg.error();
    if (cg.info() != Eigen::Success && !(st.relative_residual <= tol))
      throw RuntimeFailure(fmt::format("flow: the viscous solve did not converge ({} iterations, residual {:.3g})",
                                       st.iterations, st.relative_residual));
  }
  for (int c = 0; c < 3; ++c)
    for (long f = 0; f < static_cast<long>(u[c].size()); ++f) {
      const long d = A.dof(c, f);
      if (d >= 0) u[c][f] = x[d];
    }
  return st;
}

}  // namespace pastemix::flow
