// SPDX-License-Identifier: MIT
// The momentum exchange (model/coupling/exchange.h): one particle against the closed form of the implicit
// two-phase step at any stiffness, particles + fluid gaining exactly the gravity impulse in a periodic box (the
// drag on the particles = -(force on the fluid) to round-off), the yield stick, walls and air masked.
#include "model/coupling/exchange.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>
#include <random>

#include "model/coupling/kernel.h"

using namespace pastemix;
using coupling::Exchange;
using coupling::ExchangeParticles;

namespace {

flow::Grid periodic_box() {
  flow::Grid g;
  g.n = {8, 6, 10};
  g.h = {0.01, 0.01, 0.01};
  for (auto& b : g.bc) b.type = flow::BoundaryType::periodic;
  return g;
}

flow::Faces faces(const flow::Grid& g, double value) {
  flow::Faces f;
  for (int c = 0; c < 3; ++c) f[c].assign(g.face_count(c), value);
  return f;
}

struct Cloud {
  std::vector<std::array<double, 3>> x, v;
  std::vector<double> d, m, beta, yield;
  ExchangeParticles view() const { return {x, d, m, beta, yield}; }
};

double momentum(const Cloud& p, const flow::Faces& u, const flow::Faces& M, int c) {
  double s = 0.0;
  for (std::size_t i = 0; i < p.m.size(); ++i) s += p.m[i] * p.v[i][c];
  for (std::size_t f = 0; f < u[c].size(); ++f) s += M[c][f] * u[c][f];
  return s;
}

// One 5 mm rock of 0.18 g with a unit drag coefficient and no yield part, off the cells' centres.
Cloud one_rock(const std::array<double, 3>& v) {
  Cloud p;
  p.x = {{0.033, 0.027, 0.051}};
  p.d = {0.005};
  p.m = {1.8e-4};
  p.beta = {1.0};
  p.yield = {0.0};
  p.v = {v};
  return p;
}

}  // namespace

TEST_CASE("exchange: one particle's drag impulse is the implicit two-phase closed form, for dt beta / m from 1e-2 to 1e6") {
  const flow::Grid g = periodic_box();
  const double dt = 1e-3, rho = 1.2;  // a light fluid (air): its faces are lighter than the particle
  const flow::Faces M = faces(g, rho * g.cell_volume());
  for (double stiff : {1e-2, 1.0, 1e6}) {
    Cloud p;
    p.x = {{0.033, 0.027, 0.051}};
    p.d = {0.012};
    p.m = {2760.0 * 3.14159 / 6.0 * 1.728e-6};
    p.beta = {stiff * p.m[0] / dt};
    p.yield = {0.0};
    p.v = {{0.3, -0.2, -1.0}};
    flow::Faces u = faces(g, 0.0);
    for (std::size_t f = 0; f < u[0].size(); ++f) u[0][f] = 0.05;
    // s = sum_f W_pf^2 / M_f from the kernel's own face spread (deposit_faces of a unit amount).
    const coupling::Stencil st = coupling::stencil(g, p.x[0], p.d[0], 2.0);
    std::array<double, 3> s{};
    for (int c = 0; c < 3; ++c) {
      flow::Faces w = faces(g, 0.0);
      std::array<double, 3> unit{};
      unit[c] = 1.0;
      coupling::deposit_faces(g, st, unit, w);
      for (std::size_t f = 0; f < w[c].size(); ++f) s[c] += w[c][f] * w[c][f] / M[c][f];
    }
    const std::array<double, 3> up = coupling::interpolate_velocity(g, st, u), v0 = p.v[0];
    std::vector<std::array<double, 3>> J;
    std::array<double, 3> before{};
    for (int c = 0; c < 3; ++c) before[c] = momentum(p, u, M, c);
    Exchange ex(g, 2.0);
    ex.apply(dt, p.view(), p.v, u, M, nullptr, J);
    for (int c = 0; c < 3; ++c) {
      const double b = p.beta[0];
      const double expected = dt * b * (up[c] - v0[c]) / (1.0 + dt * b * (1.0 / p.m[0] + s[c]));
      INFO("dt beta / m = " << stiff << ", component " << c);
      CHECK(J[0][c] == doctest::Approx(expected).epsilon(1e-10));
      CHECK(std::abs(momentum(p, u, M, c) - before[c]) <= 1e-15 * (std::abs(before[c]) + p.m[0]));
      // No overshoot: the relative velocity keeps its sign and shrinks (implicit: any stiffness is stable).
      const double w0 = v0[c] - up[c], w1 = p.v[0][c] - coupling::interpolate_velocity(g, st, u)[c];
      CHECK(w1 * w0 >= 0.0);
      CHECK(std::abs(w1) <= std::abs(w0));
    }
  }
}

TEST_CASE("exchange: in a periodic box particles + fluid gain exactly the gravity impulse, drag = -(force on the fluid)") {
  const flow::Grid g = periodic_box();
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Cloud p;
  for (int i = 0; i < 40; ++i) {
    const double d = 1.18e-3 * std::pow(30.0 / 1.18, U(rng));
    p.x.push_back({0.08 * U(rng), 0.06 * U(rng), 0.1 * U(rng)});
    p.d.push_back(d);
    p.m.push_back(2760.0 * 3.14159265358979 / 6.0 * d * d * d);
    p.beta.push_back(p.m.back() * std::pow(10.0, 8.0 * U(rng) - 1.0));  // relaxation times 1e-7 to 10 s
    p.yield.push_back(i % 3 == 0 ? 0.0 : 50.0 * d * d);                 // ~ (pi d / 2)^2 tau_y at tau_y ~ 20 Pa
    p.v.push_back({U(rng) - 0.5, U(rng) - 0.5, -U(rng)});
  }
  flow::Faces M = faces(g, 0.0), u = faces(g, 0.0);
  for (int c = 0; c < 3; ++c)
    for (std::size_t f = 0; f < M[c].size(); ++f) M[c][f] = (U(rng) < 0.2 ? 1.2 : 1843.0) * g.cell_volume();
  const double dt = 1e-3, gz = -9.81;
  double total_mass = 0.0;
  for (double m : p.m) total_mass += m;
  for (double m : M[2]) total_mass += m;
  const double p0 = momentum(p, u, M, 2), px0 = momentum(p, u, M, 0);
  Exchange ex(g, 2.0);
  std::vector<std::array<double, 3>> J;
  double worst_balance = 0.0;
  int stuck = 0;
  long iterations = 0;
  const int steps = 30;
  for (int n = 0; n < steps; ++n) {
    for (auto& v : p.v) v[2] += gz * dt;
    for (double& w : u[2]) w += gz * dt;
    const flow::Faces u_before = u;
    const coupling::ExchangeStats st = ex.apply(dt, p.view(), p.v, u, M, nullptr, J);
    stuck += st.stuck;
    iterations += st.iterations;
    // The particles' impulse against the fluid's momentum change, per component.
    for (int c = 0; c < 3; ++c) {
      double particles = 0.0, fluid = 0.0, scale = 0.0;
      for (const auto& j : J) particles += j[c], scale += std::abs(j[c]);
      for (std::size_t f = 0; f < u[c].size(); ++f) fluid += M[c][f] * (u[c][f] - u_before[c][f]);
      if (scale > 0.0) worst_balance = std::max(worst_balance, std::abs(particles + fluid) / scale);
    }
  }
  const double gained = momentum(p, u, M, 2) - p0, expected = total_mass * gz * dt * steps;
  const double err = std::abs(gained - expected) / std::abs(expected);
  std::printf("exchange momentum: 40 particles (dt / tau 1e-4 to 1e4), %d steps: gravity impulse relative error %.3g, "
              "|drag on particles + force on fluid| / sum |drag| <= %.3g, x momentum drift %.3g N s, %d stick events, "
              "%.1f CG iterations per component solve\n",
              steps, err, worst_balance, momentum(p, u, M, 0) - px0, stuck, static_cast<double>(iterations) / (3.0 * steps));
  CHECK(err <= 1e-10);
  CHECK(worst_balance <= 1e-12);
  CHECK(std::abs(momentum(p, u, M, 0) - px0) <= 1e-14 * total_mass);
  CHECK(stuck > 0);  // the yield part was exercised
}

TEST_CASE("exchange: the yield part sticks a slow particle to the frozen fluid and takes exactly F_y dt from a fast one") {
  const flow::Grid g = periodic_box();
  const flow::Faces M = faces(g, 1843.0 * g.cell_volume());
  flow::Faces u = faces(g, 0.0);
  for (std::size_t f = 0; f < u[2].size(); ++f) u[2][f] = -0.01 * (1.0 + 0.1 * static_cast<double>(f % 7));
  const double dt = 1e-4, m = 0.01, Fy = 2.0;  // F_y dt / m = 0.02 m/s
  Cloud p;
  p.x = {{0.041, 0.03, 0.05}, {0.02, 0.02, 0.02}};
  p.d = {0.01, 0.01};
  p.m = {m, m};
  p.beta = {0.0, 0.0};
  p.yield = {Fy, Fy};
  const auto s0 = coupling::stencil(g, p.x[0], 0.01, 2.0), s1 = coupling::stencil(g, p.x[1], 0.01, 2.0);
  const auto u0 = coupling::interpolate_velocity(g, s0, u), u1 = coupling::interpolate_velocity(g, s1, u);
  p.v = {{u0[0] + 0.006, u0[1], u0[2] - 0.008}, {u1[0], u1[1] + 1.0, u1[2]}};  // |w| = 0.01 < 0.02; 1 m/s
  std::vector<std::array<double, 3>> J;
  const auto st = Exchange(g, 2.0).apply(dt, p.view(), p.v, u, M, nullptr, J);
  CHECK(st.stuck == 1);
  for (int c = 0; c < 3; ++c) CHECK(p.v[0][c] == doctest::Approx(u0[c]).epsilon(1e-13));
  CHECK(J[1][1] == doctest::Approx(-Fy * dt).epsilon(1e-13));
  CHECK(p.v[1][1] == doctest::Approx(u1[1] + 1.0 - Fy * dt / m).epsilon(1e-13));
}

TEST_CASE("exchange: wall faces and masked (air) faces take no reaction, a particle in air gets no paste drag") {
  flow::Grid g = periodic_box();
  for (auto& b : g.bc) b.type = flow::BoundaryType::no_slip;
  const flow::Faces M = faces(g, 1843.0 * g.cell_volume());
  flow::Faces mask = faces(g, 1.0);
  for (int c = 0; c < 3; ++c) {
    const auto fd = g.face_dims(c);
    for (int k = 0; k < fd[2]; ++k)
      for (int j = 0; j < fd[1]; ++j)
        for (int i = 0; i < fd[0]; ++i)
          if (k >= (c == 2 ? 6 : 5)) mask[c][g.face(c, {i, j, k})] = 0.0;  // air above z = 5 cm
  }
  Cloud p;
  p.x = {{0.005, 0.005, 0.005}, {0.04, 0.03, 0.085}};  // touching three walls; in the air
  p.d = {0.01, 0.01};
  p.m = {0.001, 0.001};
  p.beta = {5.0, 5.0};
  p.yield = {1.0, 1.0};
  p.v = {{1.0, 1.0, -1.0}, {0.0, 0.0, -1.0}};
  flow::Faces u = faces(g, 0.0);
  std::vector<std::array<double, 3>> J;
  Exchange(g, 2.0).apply(1e-3, p.view(), p.v, u, M, &mask, J);
  for (int c = 0; c < 3; ++c) {
    double fluid = 0.0;
    const auto fd = g.face_dims(c);
    for (int k = 0; k < fd[2]; ++k)
      for (int j = 0; j < fd[1]; ++j)
        for (int i = 0; i < fd[0]; ++i) {
          const long f = g.face(c, {i, j, k});
          const std::array<int, 3> q{i, j, k};
          if (q[c] == 0 || q[c] == g.n[c] || mask[c][f] == 0.0) CHECK(u[c][f] == 0.0);
          fluid += M[c][f] * u[c][f];
        }
    CHECK(J[0][c] != 0.0);
    CHECK(std::abs(fluid + J[0][c]) <= 1e-15);  // the corner particle's reaction stays in the paste
    CHECK(J[1][c] == 0.0);                      // no paste face in its support
  }
}

// Faces below kMinPasteFraction are air for the paste drag: a particle whose whole support holds paste fraction
// 0.5 % has no paste share and passes no reaction; at 2 % it has a 2 % share and its reaction stays on the faces.
TEST_CASE("exchange: faces of paste fraction below 1 % are air for the paste drag (no share, no reaction)") {
  const flow::Grid g = periodic_box();
  const flow::Faces M = faces(g, 1.2 * g.cell_volume() + 0.01 * 1843.0 * g.cell_volume());
  for (const double a : {0.005, 0.02}) {
    CAPTURE(a);
    const flow::Faces mask = faces(g, a);
    Cloud p = one_rock({0.0, 0.0, -1.0});
    std::vector<double> share;
    const Exchange ex(g, 2.0);
    ex.fluid_velocity(p.view(), faces(g, 0.0), M, &mask, share);
    CHECK(share[0] == doctest::Approx(a < coupling::kMinPasteFraction ? 0.0 : a).epsilon(1e-12));
    flow::Faces u = faces(g, 0.0);
    const std::vector<std::array<double, 3>> J = {{0.0, 0.0, 1e-5}};
    const coupling::ExchangeStats st = ex.react(p.view(), u, M, &mask, J);
    double fluid = 0.0;
    for (std::size_t f = 0; f < u[2].size(); ++f) fluid += M[2][f] * u[2][f];
    if (a < coupling::kMinPasteFraction) {
      CHECK(fluid == 0.0);
      CHECK(st.dropped_yield == doctest::Approx(1e-5));
    } else {
      CHECK(fluid == doctest::Approx(-1e-5).epsilon(1e-12));
      CHECK(st.dropped_yield == 0.0);
    }
  }
}

// bound_reaction (case 3's air runaway, VALIDATION.md): a stuck rock of 1.8e-4 kg passes a sub-cycle reaction of
// 1e-4 N s upward onto faces of 2 % paste (~5e-6 kg each): unbounded they end far past the rock's own 0.05 m/s;
// bounded, every face is back inside the hull of its start velocity (0) and the rock's, the rock gets back what
// they gave up, and particles + fluid keep their momentum to round-off. A face that passed its kick on (its
// velocity after the step below half its kick) or a paste face (fraction >= kThinPaste) is not touched.
TEST_CASE("exchange: the bounded reaction brings a thin-paste face kicked past its particles back to their hull") {
  const flow::Grid g = periodic_box();
  const flow::Faces M = faces(g, (1.2 + 0.02 * 1843.0) * g.cell_volume());
  Cloud p = one_rock({0.0, 0.0, 0.05});
  const std::vector<std::array<double, 3>> J = {{0.0, 0.0, -1e-4}};  // the rock was held back: the faces go up
  const Exchange ex(g, 2.0);
  const flow::Faces before = faces(g, 0.0);
  auto momentum = [&](const flow::Faces& u) {
    double s = 0.0;
    for (std::size_t f = 0; f < u[2].size(); ++f) s += M[2][f] * u[2][f];
    return s;
  };
  for (const double a : {0.02, 0.6}) {
    CAPTURE(a);
    const flow::Faces mask = faces(g, a);
    flow::Faces u = before;
    ex.react(p.view(), u, M, &mask, J);
    double top = 0.0;
    for (double w : u[2]) top = std::max(top, w);
    CHECK(top > 0.5);  // m/s: ten times the rock's speed
    CHECK(momentum(u) == doctest::Approx(1e-4).epsilon(1e-12));
    std::vector<std::array<double, 3>> back;
    const coupling::ExchangeStats st = ex.bound_reaction(p.view(), before, u, M, &mask, J, p.v, back);
    double after = 0.0;
    for (double w : u[2]) after = std::max(after, w);
    if (a < coupling::kThinPaste) {
      CHECK(st.clipped_faces > 0);
      CHECK(after <= 0.05 + 1e-15);
      CHECK(back[0][2] > 0.0);  // the rock gets back momentum upward
      CHECK(back[0][0] == 0.0);
      CHECK(std::abs(momentum(u) + J[0][2] + back[0][2]) <= 1e-18);  // fluid + rock: the rock's J_sub + back
    } else {
      CHECK(st.clipped_faces == 0);
      CHECK(after == top);
      CHECK(back[0][2] == 0.0);
    }
  }
  // Thin faces that passed most of their kick on: the step left each at 40 % of it, many past the hull.
  const flow::Faces mask = faces(g, 0.02);
  flow::Faces u = before;
  ex.react(p.view(), u, M, &mask, J);
  int past = 0;
  for (double& w : u[2]) w *= 0.4, past += w > 0.05 ? 1 : 0;
  CHECK(past > 0);
  std::vector<std::array<double, 3>> back;
  CHECK(ex.bound_reaction(p.view(), before, u, M, &mask, J, p.v, back).clipped_faces == 0);
}

// The reaction meets the mass its drag was computed against (Exchange::react with start_mass): a face that kept
// its fluid mass since the cycle's start takes its whole reaction, bit for bit as without start_mass; one whose
// mass fell to a fraction r takes r of it, so its kick is r R / (r m_start) = R / m_start, never more; the
// particle gets back what the faces could not take, and particles + fluid keep their momentum to round-off.
// (Chapter-7 test 3: a face of the cycle's start emptied to paste fraction 0.016 by the sub-step's advection was
// kicked from 7.6 to 326 m/s by a 50 mm rock's reaction.)
TEST_CASE("exchange: a face emptied since the drag was computed takes only its remaining mass's share of the reaction") {
  const flow::Grid g = periodic_box();
  const flow::Faces M0 = faces(g, 1843.0 * g.cell_volume());
  const flow::Faces mask = faces(g, 1.0);
  Cloud p = one_rock({0.0, 0.0, -1.0});
  const std::vector<std::array<double, 3>> J = {{2e-6, 0.0, 1e-5}};
  const Exchange ex(g, 2.0);
  flow::Faces plain = faces(g, 0.0), kept = plain;
  ex.react(p.view(), plain, M0, &mask, J);
  std::vector<std::array<double, 3>> back;
  const coupling::ExchangeStats same = ex.react(p.view(), kept, M0, &mask, J, &M0, &back);
  for (int c = 0; c < 3; ++c) CHECK(kept[c] == plain[c]);
  CHECK(back[0] == std::array<double, 3>{0.0, 0.0, 0.0});
  CHECK(same.clipped == 0.0);
  // The z faces of one layer (k = 5) lost 99 % of their mass (advected away), the others kept it.
  flow::Faces M = M0;
  const auto fd = g.face_dims(2);
  for (int j = 0; j < fd[1]; ++j)
    for (int i = 0; i < fd[0]; ++i) M[2][g.face(2, {i, j, 5})] *= 0.01;
  flow::Faces u = faces(g, 0.0);
  ex.react(p.view(), u, M, &mask, J, &M0, &back);
  double fluid = 0.0, emptied = 0.0;
  for (std::size_t f = 0; f < u[2].size(); ++f) {
    fluid += M[2][f] * u[2][f];
    CHECK(std::abs(u[2][f] - plain[2][f]) <= 1e-15 * std::abs(plain[2][f]) + 1e-300);  // the kick: R / m_start
    if (M[2][f] < M0[2][f]) emptied += M0[2][f] * plain[2][f];
  }
  CHECK(emptied != 0.0);                              // the particle's support reaches the emptied layer
  CHECK(back[0][2] == doctest::Approx(0.99 * emptied).epsilon(1e-9));  // it gets back what that layer could not take
  CHECK(back[0][0] == 0.0);                           // the x faces kept their mass
  CHECK(std::abs(fluid + J[0][2] + back[0][2]) <= 1e-18);
  // bound_reaction with the same start_mass measures the kick react gave (R / m_start where the face lost mass,
  // not R / m): a thin face (2 % paste) that lost half its mass, kicked past the rock's own speed, is brought
  // back to the hull, and particles + fluid still keep their momentum to round-off.
  const flow::Faces thin0 = faces(g, (1.2 + 0.02 * 1843.0) * g.cell_volume()), thin_mask = faces(g, 0.02);
  flow::Faces half = thin0;
  for (auto& m : half[2]) m *= 0.5;
  const std::vector<std::array<double, 3>> held = {{0.0, 0.0, -1e-4}};  // the rock (0.05 m/s up) was held back
  p.v = {{0.0, 0.0, 0.05}};
  flow::Faces w = faces(g, 0.0);
  std::vector<std::array<double, 3>> took, clipped;
  ex.react(p.view(), w, half, &thin_mask, held, &thin0, &took);
  CHECK(took[0][2] == doctest::Approx(5e-5).epsilon(1e-9));  // the faces took half: the rock gets half back
  const coupling::ExchangeStats b = ex.bound_reaction(p.view(), faces(g, 0.0), w, half, &thin_mask, held, p.v, clipped, &thin0);
  CHECK(b.clipped_faces > 0);
  double top = 0.0, moved = 0.0;
  for (std::size_t f = 0; f < w[2].size(); ++f) top = std::max(top, w[2][f]), moved += half[2][f] * w[2][f];
  CHECK(top <= 0.05 + 1e-15);
  CHECK(std::abs(moved + held[0][2] + took[0][2] + clipped[0][2]) <= 1e-18);
}

// The face weights computed once per position set (Exchange::face_weights, what a coupling cycle keeps) give the
// very numbers of computing them in every call, in a walled box (wall faces left out) with a paste mask, and
// weights of another particle count are refused.
TEST_CASE("exchange: precomputed face weights give the same bits as weights computed in the call") {
  flow::Grid g;
  g.n = {6, 5, 7};
  g.h = {0.01, 0.011, 0.01};
  g.check();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0.0, 0.06), uy(0.0, 0.055), uz(0.0, 0.07), ud(0.003, 0.012);
  Cloud p;
  for (int i = 0; i < 40; ++i) {
    p.x.push_back({ux(rng), uy(rng), uz(rng)});
    p.d.push_back(ud(rng));
    p.m.push_back(2760.0 * p.d.back() * p.d.back() * p.d.back());
    p.beta.push_back(0.5 + i * 0.1);
    p.yield.push_back(i % 3 == 0 ? 1e-4 : 0.0);
    p.v.push_back({0.01 * i, -0.02, -0.1});
  }
  const flow::Faces M = faces(g, 1843.0 * g.cell_volume());
  flow::Faces mask = faces(g, 1.0), u0 = faces(g, 0.0);
  for (int c = 0; c < 3; ++c)
    for (std::size_t f = 0; f < mask[c].size(); ++f) {
      mask[c][f] = static_cast<double>(f % 7) / 6.0;  // 0 (air), thin and full paste faces
      u0[c][f] = 1e-3 * static_cast<double>(f % 11);
    }
  const Exchange ex(g, 2.0);
  std::vector<coupling::Stencil> st;
  for (std::size_t i = 0; i < p.x.size(); ++i) st.push_back(coupling::stencil(g, p.x[i], p.d[i], 2.0));
  const coupling::FaceWeights fw = ex.face_weights(st);
  REQUIRE(fw.size() == p.x.size());
  ExchangeParticles cached = p.view();
  cached.weights = &fw;
  auto same = [](const auto& a, const auto& b) { return std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0; };
  std::vector<double> s1, s2;
  const auto f1 = ex.fluid_velocity(p.view(), u0, M, &mask, s1), f2 = ex.fluid_velocity(cached, u0, M, &mask, s2);
  CHECK(same(f1, f2));
  CHECK(same(s1, s2));
  Cloud q = p;
  flow::Faces u1 = u0, u2 = u0;
  std::vector<std::array<double, 3>> J1, J2;
  ex.apply(1e-3, p.view(), p.v, u1, M, &mask, J1);
  ex.apply(1e-3, cached, q.v, u2, M, &mask, J2);
  CHECK(same(J1, J2));
  CHECK(same(p.v, q.v));
  for (int c = 0; c < 3; ++c) CHECK(same(u1[c], u2[c]));
  const coupling::FaceWeights fewer = ex.face_weights(std::span(st).first(10));
  cached.weights = &fewer;
  CHECK_THROWS_WITH_AS(ex.fluid_velocity(cached, u0, M, &mask, s2), doctest::Contains("face weights of 10 particles"),
                       std::invalid_argument);
}
