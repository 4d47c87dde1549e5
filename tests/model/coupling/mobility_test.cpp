// SPDX-License-Identifier: MIT
// The place-aware self-mobility (model/coupling/mobility.h): the MAC grid's Stokes Green's function against
// Watson's integral and Oseen's far field, Hasimoto's image term (two periodic boxes agree after it), the
// continuum limit (a kernel over many cells gives the place-averaged table drag.h's g0 uses), the place
// dependence at h/d = 2 and 4 against what `sphere` measured with the table (VALIDATION.md), and where the
// drag falls back to the table.
#include "model/coupling/mobility.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "model/coupling/drag.h"

using namespace pastemix;
using coupling::LatticeStokes;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double kD = 0.01, kC = 2.0, kMu = 5.0;  // m, -, Pa s

flow::Grid periodic_grid(int n, double h) {
  flow::Grid g;
  g.n = {n, n, n};
  g.h = {h, h, h};
  for (auto& b : g.bc) b.type = flow::BoundaryType::periodic;
  return g;
}

// M_cc of a sphere at fractional place f (of a cell, per axis) in cell (8, 8, 8).
std::array<double, 3> at(const flow::Grid& g, const std::array<double, 3>& f, const LatticeStokes& t) {
  const double h = g.h[0];
  const std::array<double, 3> x{(8.0 + f[0]) * h, (8.0 + f[1]) * h, (8.0 + f[2]) * h};
  const auto m = coupling::place_mobility(g, coupling::stencil(g, x, kD, kC), kMu, t);
  REQUIRE(m.has_value());
  return *m;
}

// M_zz at (fx, fy) averaged over z across the cell (the `sphere` window settles one cell).
double zz_over_z(const flow::Grid& g, double fx, double fy, const LatticeStokes& t) {
  constexpr int kSteps = 32;
  double sum = 0.0;
  for (int k = 0; k < kSteps; ++k) sum += at(g, {fx, fy, (k + 0.5) / kSteps}, t)[2];
  return sum / kSteps;
}

}  // namespace

TEST_CASE("coupling mobility: the MAC grid's Stokes Green's function, Watson's value at 0 and Oseen's far field") {
  const LatticeStokes t(64, 6);
  // (2/3) W / 2, W = 0.5054620197 (Watson's simple-cubic integral).
  CHECK(t.component(0, {0, 0, 0}) == doctest::Approx(0.5054620197 / 3.0).epsilon(2e-5));
  // Permuted axes: G_yy(0, 1, 0) = G_zz(0, 0, 1) = G_xx(1, 0, 0); G even.
  CHECK(t.component(1, {0, -1, 0}) == t.component(0, {1, 0, 0}));
  CHECK(t.component(2, {0, 0, 1}) == t.component(0, {1, 0, 0}));
  CHECK(t.component(2, {2, 1, 0}) == t.component(0, {0, 1, 2}));
  // Oseen, (1 + cos^2) / (8 pi r), where the lattice no longer shows: the diagonal r = (6, 6, 6).
  const double r = 6.0 * std::sqrt(3.0), oseen = (1.0 + 1.0 / 3.0) / (8.0 * pi * r);
  const LatticeStokes fine(128, 6);
  CHECK(fine.component(0, {6, 6, 6}) == doctest::Approx(oseen).epsilon(2e-3));
  CHECK_THROWS_AS(t.component(0, {7, 0, 0}), std::invalid_argument);
  CHECK_THROWS_AS(LatticeStokes(12, 6), std::invalid_argument);
}

TEST_CASE("coupling mobility: Hasimoto's image term makes two periodic boxes the same unbounded grid") {
  const LatticeStokes a(32, 3), b(64, 3), a_periodic(32, 3, false), b_periodic(64, 3, false);
  // Over G(0), the scale of a particle's g0 (its weights sit within a few cells).
  const double g00 = b.component(0, {0, 0, 0});
  double worst = 0.0, worst_periodic = 0.0;
  for (int x = 0; x <= 3; ++x)
    for (int y = 0; y <= 3; ++y)
      for (int z = 0; z <= 3; ++z) {
        const std::array<int, 3> q{x, y, z};
        worst = std::max(worst, std::abs(a.component(0, q) - b.component(0, q)) / g00);
        worst_periodic = std::max(worst_periodic, std::abs(a_periodic.component(0, q) - b_periodic.component(0, q)) / g00);
      }
  std::printf("lattice Stokes G_xx, offsets 0-3: N = 32 against 64 differ by %.2e of G(0) with Hasimoto's image term, "
              "%.2e without\n", worst, worst_periodic);
  CHECK(worst < 1e-3);            // O(r^2 / L^3) left
  CHECK(worst_periodic > 1e-2);   // the image term itself: 2.8373 (1/32 - 1/64) / (6 pi) = 0.0024, 1.4 % of G(0)
  CHECK(a.component(0, {0, 0, 0}) == doctest::Approx(g00).epsilon(1e-5));
}

TEST_CASE("coupling mobility: a kernel over many cells gives the continuum table, at every place") {
  const LatticeStokes t(64, 10);
  for (double hd : {0.25, 0.5}) {  // a = 4 h and 2 h (the place-aware switch)
    const flow::Grid g = periodic_grid(32, hd * kD);
    const double table = coupling::self_mobility(kD, kC, g.h, kMu);
    double worst = 0.0;
    for (double fx : {0.0, 0.3, 0.5})
      for (double fy : {0.1, 0.5, 0.9})
        for (double fz : {0.0, 0.5, 0.7})
          for (double m : at(g, {fx, fy, fz}, t)) worst = std::max(worst, std::abs(m / table - 1.0));
    std::printf("self-mobility h/d %g: every place and component within %.2f %% of the continuum table\n", hd, 100 * worst);
    CHECK(worst < 2.5e-3);
  }
}

TEST_CASE("coupling mobility: at h/d = 2 and 4 the place in the cell moves g0 as `sphere` measured with the table") {
  // What the table misses, beta (M_zz - g0_table), is the error the sphere settled with (VALIDATION.md, session
  // 10): h/d 2 +19.3 % at a cell's centre, -11.3 % on faces, -4.46 % at the default start; h/d 4 -2.09 %.
  const LatticeStokes& t = coupling::lattice_stokes();
  const double beta = 3.0 * pi * kMu * kD;
  const flow::Grid g2 = periodic_grid(16, 2.0 * kD), g4 = periodic_grid(16, 4.0 * kD);
  const double tab2 = coupling::self_mobility(kD, kC, g2.h, kMu), tab4 = coupling::self_mobility(kD, kC, g4.h, kMu);
  const double centre = beta * (zz_over_z(g2, 0.5, 0.5, t) - tab2), faces = beta * (zz_over_z(g2, 0.0, 0.0, t) - tab2);
  const double start = beta * (zz_over_z(g2, 0.96, 0.28, t) - tab2), start4 = beta * (zz_over_z(g4, 0.96, 0.28, t) - tab4);
  const auto c3 = at(g2, {0.5, 0.5, 0.5}, t), f3 = at(g2, {0.0, 0.0, 0.5}, t);
  std::printf("h/d 2: beta (g0_zz - g0_table) %+.3f at a cell's centre, %+.3f on faces, %+.3f at the default start; h/d "
              "4 %+.3f (measured with the table +0.193, -0.113, -0.0446; -0.0209); the components' mean instead: %+.3f, "
              "%+.3f (z in the middle)\n",
              centre, faces, start, start4, beta * ((c3[0] + c3[1] + c3[2]) / 3 - tab2),
              beta * ((f3[0] + f3[1] + f3[2]) / 3 - tab2));
  CHECK(centre == doctest::Approx(0.193).epsilon(0.1));
  CHECK(faces == doctest::Approx(-0.113).epsilon(0.12));
  CHECK(start == doctest::Approx(-0.0446).epsilon(0.1));
  CHECK(start4 == doctest::Approx(-0.0209).epsilon(0.1));
}

TEST_CASE("coupling mobility: the drag's g0 is the place's along the slip, the table where the kernel is wide, "
          "by a wall and on non-cubic cells") {
  const flow::Grid g = periodic_grid(8, 2.0 * kD);
  const std::array<double, 3> x{4.5 * 2.0 * kD, 4.0 * 2.0 * kD, 4.3 * 2.0 * kD};
  const coupling::Stencil s = coupling::stencil(g, x, kD, kC);
  const auto m = *coupling::place_mobility(g, s, kMu);
  CHECK(coupling::disturbance_mobility(g, s, kD, kC, kMu, {0.0, 0.0, -1.0}) == doctest::Approx(m[2]).epsilon(1e-14));
  CHECK(coupling::disturbance_mobility(g, s, kD, kC, kMu, {3.0, 4.0, 0.0}) ==
        doctest::Approx(0.36 * m[0] + 0.64 * m[1]).epsilon(1e-14));
  CHECK(coupling::disturbance_mobility(g, s, kD, kC, kMu, {0.0, 0.0, 0.0}) ==
        doctest::Approx((m[0] + m[1] + m[2]) / 3.0).epsilon(1e-14));
  // A kernel of half-width above two cells: the table.
  const flow::Grid fine = periodic_grid(32, 0.25 * kD);
  const coupling::Stencil sf = coupling::stencil(fine, {0.04, 0.04, 0.04}, kD, kC);
  CHECK(coupling::disturbance_mobility(fine, sf, kD, kC, kMu, {0, 0, 1}) == coupling::self_mobility(kD, kC, fine.h, kMu));
  // By a wall (bounded z, the kernel in the end cell): the table, as before.
  flow::Grid walled = g;
  walled.bc[4].type = walled.bc[5].type = flow::BoundaryType::no_slip;
  const coupling::Stencil sw = coupling::stencil(walled, {x[0], x[1], 0.3 * 2.0 * kD}, kD, kC);
  CHECK_FALSE(coupling::place_mobility(walled, sw, kMu).has_value());
  CHECK(coupling::disturbance_mobility(walled, sw, kD, kC, kMu, {0, 0, 1}) == coupling::self_mobility(kD, kC, g.h, kMu));
  CHECK(coupling::place_mobility(walled, coupling::stencil(walled, x, kD, kC), kMu).has_value());  // mid-box
  flow::Grid flat = g;
  flat.h[2] = 1.5 * kD;
  CHECK_FALSE(coupling::place_mobility(flat, coupling::stencil(flat, x, kD, kC), kMu).has_value());
}
