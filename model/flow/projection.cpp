// SPDX-License-Identifier: MIT
// Pressure projection on the MAC grid. Gravity was added to the faces before this (u* = ... + g dt), and the
// same face density rho_f enters both the gravity-free face update and this operator, so a flat interface at
// rest has the exact discrete hydrostatic pressure as its solution: the projection removes g dt on every face
// and nothing is left to drive a spurious current (the `still` validation).
#include <cmath>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include "base/error.h"
#include "model/flow/linear.h"

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

ProjectionStats project(const Grid& g, double dt, const Faces& rho_face, Faces& u, std::vector<double>& p, double tol,
                        int max_iterations) {
  const long n = g.cell_count();
  bool open = false;
  for (const Boundary& b : g.bc) open |= b.type == BoundaryType::open;
  auto side_open = [&](int c, int index) { return g.side(c, index == 0 ? 0 : 1).type == BoundaryType::open; };

  std::vector<Eigen::Triplet<double, long>> trip;
  trip.reserve(7 * n);
  each_face(g, [&](int c, long f, long a, long b, int index) {
    const double k = dt / (rho_face[c][f] * g.h[c] * g.h[c]);
    if (a >= 0 && b >= 0) {
      trip.emplace_back(a, a, k);
      trip.emplace_back(b, b, k);
      trip.emplace_back(a, b, -k);
      trip.emplace_back(b, a, -k);
    } else if (side_open(c, index)) {
      trip.emplace_back(a >= 0 ? a : b, a >= 0 ? a : b, 2.0 * k);  // p = 0 on the face, half a cell away
    }
  });
  const std::vector<double> div0 = divergence(g, u);
  ProjectionStats st;
  st.divergence_before = norm2(div0);
  Eigen::VectorXd rhs(n), x(n);
  for (long i = 0; i < n; ++i) rhs[i] = -div0[i], x[i] = p[i];
  if (!open) {
    // Closed box: the operator is singular (constants). Remove the round-off mean of the right side and pin
    // cell 0 by doubling its diagonal: with sum(rhs) = 0 the pinned system's solution is the singular one's
    // with p_0 = 0 exactly (sum the rows), and it is definite, as CG wants.
    const double mean = rhs.mean();
    rhs.array() -= mean;
    double diag0 = 0.0;
    for (const auto& t : trip)
      if (t.row() == 0 && t.col() == 0) diag0 += t.value();
    trip.emplace_back(0, 0, diag0);
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor, long> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  if (rhs.squaredNorm() > 0.0) {
    Eigen::ConjugateGradient<decltype(A), Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>> cg;
    // Half the stated tolerance: CG's recursive residual and the divergence recomputed after the face update
    // differ by round-off, and the stated bound is on the latter.
    cg.setTolerance(0.5 * tol);
    cg.setMaxIterations(max_iterations);
    cg.compute(A);
    x = cg.solveWithGuess(rhs, x);
    st.solve.iterations = static_cast<int>(cg.iterations());
    st.solve.relative_residual = cg.error();
    if (cg.info() != Eigen::Success && !(st.solve.relative_residual <= 0.5 * tol))
      throw RuntimeFailure(fmt::format("flow: the pressure solve did not converge ({} iterations, residual {:.3g})",
                                       st.solve.iterations, st.solve.relative_residual));
  }
  for (long i = 0; i < n; ++i) p[i] = x[i];
  each_face(g, [&](int c, long f, long a, long b, int index) {
    const double k = dt / (rho_face[c][f] * g.h[c]);
    if (a >= 0 && b >= 0) {
      u[c][f] -= k * (p[b] - p[a]);
    } else if (side_open(c, index)) {
      u[c][f] -= a >= 0 ? k * (0.0 - p[a]) * 2.0 : k * (p[b] - 0.0) * 2.0;
    }
  });
  const std::vector<double> div1 = divergence(g, u);
  st.divergence_after = norm2(div1);
  for (double d : div1) st.max_volume_loss = std::max(st.max_volume_loss, std::abs(d) * dt);
  return st;
}

}  // namespace pastemix::flow
