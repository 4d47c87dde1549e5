// SPDX-License-Identifier: MIT
// The implicit viscous step against exact solutions of the discrete steady state: plane Couette flow (linear
// profile), and a two-layer Couette flow with a viscosity contrast of 1e8, whose stress continuity the harmonic
// face viscosity makes exact when the layers meet on a face.
#include "model/flow/linear.h"

#include <doctest/doctest.h>

#include <cmath>

using namespace pastemix::flow;

namespace {
Grid couette_grid(int nz, double lid) {
  Grid g;
  g.n = {3, 2, nz};
  g.h = {0.1, 0.1, 1.0 / nz};
  g.bc[0].type = g.bc[1].type = g.bc[2].type = g.bc[3].type = BoundaryType::periodic;
  g.bc[5].wall_velocity = {lid, 0.0, 0.0};
  return g;
}
Faces zero(const Grid& g) {
  Faces u;
  for (int c = 0; c < 3; ++c) u[c].assign(g.face_count(c), 0.0);
  return u;
}
Faces uniform_rho(const Grid& g, double rho) {
  Faces r;
  for (int c = 0; c < 3; ++c) r[c].assign(g.face_count(c), rho);
  return r;
}
}  // namespace

TEST_CASE("viscous: one implicit step of dt >> H^2 rho / mu gives plane Couette flow u = U z / H") {
  const Grid g = couette_grid(16, 2.0);
  Faces u = zero(g);
  const std::vector<double> mu(g.cell_count(), 1.0);
  const SolveStats st = viscous_step(g, 1e9, uniform_rho(g, 1.0), mu, u, 1e-13, 10000);
  CHECK(st.relative_residual <= 1e-13);
  for (int k = 0; k < g.n[2]; ++k) {
    const double z = (k + 0.5) * g.h[2];
    CHECK(u[0][g.face(0, {1, 1, k})] == doctest::Approx(2.0 * z).epsilon(1e-7));
    CHECK(std::abs(u[1][g.face(1, {1, 1, k})]) < 1e-12);
  }
}

TEST_CASE("viscous: two-layer Couette flow with a viscosity contrast of 1e8 (harmonic faces, exact stresses)") {
  const int nz = 20;
  const Grid g = couette_grid(nz, 1.0);
  const double mu_lo = 1e3, mu_hi = 1e-5;  // a plug under air
  std::vector<double> mu(g.cell_count());
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) mu[g.cell(i, j, k)] = k < nz / 2 ? mu_lo : mu_hi;
  Faces u = zero(g);
  viscous_step(g, 1e12, uniform_rho(g, 1.0), mu, u, 1e-14, 20000);
  // Exact: one shear stress tau through both layers; u(z) piecewise linear, u(0) = 0, u(1) = 1.
  const double tau = 1.0 / (0.5 / mu_lo + 0.5 / mu_hi);
  for (int k = 0; k < nz; ++k) {
    const double z = (k + 0.5) * g.h[2];
    const double exact = z < 0.5 ? tau * z / mu_lo : tau * 0.5 / mu_lo + tau * (z - 0.5) / mu_hi;
    CHECK(u[0][g.face(0, {0, 0, k})] == doctest::Approx(exact).epsilon(1e-6).scale(1e-9));
  }
}

TEST_CASE("viscous: the components are solved together: a diagonal lid drives u and v alike (x <-> y symmetry)") {
  // A rotating-lid box: the lid moves diagonally, so u and v are both driven and must be solved together.
  Grid g;
  g.n = {6, 6, 6};
  g.h = {1.0 / 6, 1.0 / 6, 1.0 / 6};
  g.bc[5].wall_velocity = {1.0, 1.0, 0.0};
  Faces u = zero(g);
  const std::vector<double> mu(g.cell_count(), 0.1);
  viscous_step(g, 0.05, uniform_rho(g, 1.0), mu, u, 1e-13, 10000);
  // The box and lid are symmetric under x <-> y: u(i, j, k) == v(j, i, k).
  double worst = 0.0;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 1; i < 6; ++i) worst = std::max(worst, std::abs(u[0][g.face(0, {i, j, k})] - u[1][g.face(1, {j, i, k})]));
  CHECK(worst < 1e-12);
  CHECK(u[0][g.face(0, {3, 3, 5})] > 0.0);
}
