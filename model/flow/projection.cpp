// SPDX-License-Identifier: MIT
// Pressure projection on the MAC grid. Gravity was added to the faces before this (u* = ... + g dt), and the
// same face density rho_f enters both the gravity-free face update and this operator, so a flat interface at
// rest has the exact discrete hydrostatic pressure as its solution: the projection removes g dt on every face
// and nothing is left to drive a spurious current (the `still` validation).
#include <algorithm>
#include <cmath>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include "base/error.h"
#include "model/flow/linear.h"
#include "model/flow/preconditioner.h"

namespace pastemix::flow {

std::vector<double> divergence(const Grid& g, const Faces& u) {
  std::vector<double> div(g.cell_count(), 0.0);
#pragma omp parallel for schedule(static)
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const std::array<int, 3> q{i, j, k};
        double s = 0.0;
        for (int c = 0; c < 3; ++c) {
          std::array<int, 3> hi = q;
          hi[c] = g.periodic(c) ? (q[c] + 1) % g.n[c] : q[c] + 1;
          s += (u[c][g.face(c, hi)] - u[c][g.face(c, q)]) / g.h[c];
        }
        div[g.cell(q)] = s;
      }
  return div;
}

namespace {

double norm2(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

// Calls f(c, face, cell_lo, cell_hi) for every face of every component; a missing cell is -1.
template <class F>
void each_face(const Grid& g, F&& f) {
  for (int c = 0; c < 3; ++c) {
    const auto fd = g.face_dims(c);
    for (int k = 0; k < fd[2]; ++k)
      for (int j = 0; j < fd[1]; ++j)
        for (int i = 0; i < fd[0]; ++i) {
          const std::array<int, 3> q{i, j, k};
          std::array<int, 3> a = q, b = q;
          a[c] = g.wrap_cell(c, q[c] - 1);
          b[c] = g.wrap_cell(c, q[c]);
          f(c, g.face(c, q), a[c] >= 0 ? g.cell(a) : -1L, b[c] >= 0 ? g.cell(b) : -1L, q[c]);
        }
  }
}

}  // namespace

PressureOperator::PressureOperator(const Grid& g) : g_(g) {
  const long n = g.cell_count();
  for (const Boundary& b : g.bc) open_ |= b.type == BoundaryType::open;
  std::vector<Eigen::Triplet<double, long>> trip;
  each_face(g, [&](int c, long f, long a, long b, int index) {
    if (a >= 0 && b >= 0) {
      links_.push_back({c, f, a, b, 0, 0, 0, 0});
      trip.emplace_back(a, a, 1.0);
      trip.emplace_back(b, b, 1.0);
      trip.emplace_back(a, b, 1.0);
      trip.emplace_back(b, a, 1.0);
    } else if (g.side(c, index == 0 ? 0 : 1).type == BoundaryType::open) {
      const long x = a >= 0 ? a : b;
      links_.push_back({c, f, a, b, 0, 0, 0, 0});
      trip.emplace_back(x, x, 1.0);
    }
  });
  trip.emplace_back(0, 0, 1.0);
  A_.resize(n, n);
  A_.setFromTriplets(trip.begin(), trip.end());
  A_.makeCompressed();
  auto position = [&](long row, long col) {
    const long* begin = A_.innerIndexPtr() + A_.outerIndexPtr()[row];
    const long* end = A_.innerIndexPtr() + A_.outerIndexPtr()[row + 1];
    return static_cast<long>(std::lower_bound(begin, end, col) - A_.innerIndexPtr());
  };
  for (Link& l : links_) {
    if (l.a >= 0 && l.b >= 0) {
      l.paa = position(l.a, l.a);
      l.pbb = position(l.b, l.b);
      l.pab = position(l.a, l.b);
      l.pba = position(l.b, l.a);
    } else {
      const long x = l.a >= 0 ? l.a : l.b;
      l.paa = position(x, x);
    }
  }
  pin_ = position(0, 0);
}

// CG preconditioned by MIC(0) (model/flow/preconditioner.h). Jacobi needed O(n) iterations (459 per solve on
// the 64 x 64 cavity); Eigen's IncompleteCholesky (threshold fill) cut them 3x but cost as much to refactor
// every step as it saved. MIC(0) is refactored every step too, in one pass, and only when CG iterates.
ProjectionStats PressureOperator::project(double dt, const Faces& rho_face, Faces& u, std::vector<double>& p, double tol,
                                          int max_iterations) {
  const Grid& g = g_;
  const long n = g.cell_count();
  double* val = A_.valuePtr();
  std::fill(val, val + A_.nonZeros(), 0.0);
  for (const Link& l : links_) {
    const double k = dt / (rho_face[l.c][l.face] * g.h[l.c] * g.h[l.c]);
    if (l.a >= 0 && l.b >= 0) {
      val[l.paa] += k;
      val[l.pbb] += k;
      val[l.pab] -= k;
      val[l.pba] -= k;
    } else {
      val[l.paa] += 2.0 * k;  // p = 0 on the open face, half a cell away
    }
  }
  const std::vector<double> div0 = divergence(g, u);
  ProjectionStats st;
  st.divergence_before = norm2(div0);
  Eigen::VectorXd rhs(n), x(n);
  for (long i = 0; i < n; ++i) rhs[i] = -div0[i], x[i] = p[i];
  if (!open_) {
    // Closed box: the operator is singular (constants). Remove the round-off mean of the right side and pin
    // cell 0 by doubling its diagonal: with sum(rhs) = 0 the pinned system's solution is the singular one's
    // with p_0 = 0 (sum the rows), and it is definite, as CG wants.
    rhs.array() -= rhs.mean();
    val[pin_] *= 2.0;
  }
  if (rhs.squaredNorm() > 0.0) {
    Eigen::ConjugateGradient<Matrix, Eigen::Lower | Eigen::Upper, MicPreconditioner> cg;
    // Half the stated tolerance: CG's recursive residual and the divergence recomputed after the face update
    // differ by round-off, and the stated bound is on the latter.
    cg.setTolerance(0.5 * tol);
    cg.setMaxIterations(max_iterations);
    cg.compute(A_);
    x = cg.solveWithGuess(rhs, x);
    st.solve.iterations = static_cast<int>(cg.iterations());
    // CG's recursive residual drifts from the true one by round-off times the condition number (a density
    // ratio of 830 on a 400 x 100 grid: the true relative divergence was up to 4e-10 when CG reported 5e-11).
    // A restart from the current solution starts the recursion again from the true residual.
    const double rhs_norm = rhs.norm();
    double true_residual = (rhs - A_ * x).norm() / rhs_norm;
    for (int restart = 0; restart < 5 && true_residual > 0.5 * tol && cg.info() == Eigen::Success; ++restart) {
      x = cg.solveWithGuess(rhs, x);
      st.solve.iterations += static_cast<int>(cg.iterations());
      true_residual = (rhs - A_ * x).norm() / rhs_norm;
    }
    st.solve.relative_residual = true_residual;
    if (!(true_residual <= tol))  // the stated bound; the restarts aim at half of it
      throw RuntimeFailure(fmt::format("flow: the pressure solve did not converge ({} iterations, residual {:.3g})",
                                       st.solve.iterations, st.solve.relative_residual));
  }
  for (long i = 0; i < n; ++i) p[i] = x[i];
  subtract_gradient(dt, rho_face, p, u);
  const std::vector<double> div1 = divergence(g, u);
  st.divergence_after = norm2(div1);
  for (double d : div1) st.max_volume_loss = std::max(st.max_volume_loss, std::abs(d) * dt);
  return st;
}

void PressureOperator::subtract_gradient(double dt, const Faces& rho_face, const std::vector<double>& p, Faces& u) const {
  const Grid& g = g_;
  for (const Link& l : links_) {
    const double k = dt / (rho_face[l.c][l.face] * g.h[l.c]);
    double& v = u[l.c][l.face];
    if (l.a >= 0 && l.b >= 0) v -= k * (p[l.b] - p[l.a]);
    else v -= l.a >= 0 ? k * (0.0 - p[l.a]) * 2.0 : k * (p[l.b] - 0.0) * 2.0;
  }
}

ProjectionStats project(const Grid& g, double dt, const Faces& rho_face, Faces& u, std::vector<double>& p, double tol,
                        int max_iterations) {
  PressureOperator op(g);
  return op.project(dt, rho_face, u, p, tol, max_iterations);
}

}  // namespace pastemix::flow
