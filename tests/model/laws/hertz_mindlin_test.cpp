// SPDX-License-Identifier: MIT
// Two-sphere impacts against Hertz and Mindlin theory (../shared/DESIGN.md section 4, thesis Table 5.1).
#include "model/laws/hertz_mindlin.h"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "base/csv.h"
#include "base/rng.h"
#include "tests/model/scene_text.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

struct MaterialRow {
  std::string name;
  double E, rho, nu, R, v, dt;
};

std::vector<MaterialRow> table_5_1() {
  const auto t = CsvTable::read(pastemix::test::source_path("datasets/thesis/hertz_validation_materials.csv"));
  std::vector<MaterialRow> rows;
  for (const auto& r : t.rows())
    rows.push_back({t.text(r, "material"), t.number(r, "youngs_modulus_Pa"), t.number(r, "density_kg_m3"),
                    t.number(r, "poisson_ratio"), t.number(r, "sphere_radius_m"), t.number(r, "initial_speed_m_s"),
                    t.number(r, "optimal_time_step_s")});
  return rows;
}

// Two spheres approaching head-on (or with a tangential component) at v each way, no gravity.
// gap (m) between the surfaces at t = 0.
std::string two_spheres(const MaterialRow& m, double e, double mu, double vt, double gap = 1e-6) {
  return fmt::format(
      "time_step = {}\nend_time = 1e-3\n[domain]\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\n[physics]\ngravity = [0, 0, 0]\n"
      "[contact]\nlaw = \"hertz_mindlin\"\n{}{}"
      "[[particle]]\nmaterial = \"m\"\nradius = {}\nposition = [{}, 0, 0]\nvelocity = [{}, {}, 0]\n"
      "[[particle]]\nmaterial = \"m\"\nradius = {}\nposition = [{}, 0, 0]\nvelocity = [{}, {}, 0]\n",
      m.dt, model::test::material("m", m.rho, m.E, m.nu), model::test::interaction("m/m", e, mu), m.R, -(m.R + gap), m.v, vt, m.R,
      m.R + gap, -m.v, -vt);
}

}  // namespace

TEST_CASE("Hertz-Mindlin kernel: zero force without overlap history, formula at a given overlap") {
  Material a{"a", 7750, 2e11, 0.3};
  MaterialPair pr{&a, &a, 1.0, 0.0, 0.0};
  const auto p = HertzMindlin::from_pair(pr);
  CHECK(p.E_star == doctest::Approx(2e11 / (2 * (1 - 0.09))).epsilon(1e-14));
  CHECK(p.damping == 0.0);
  HertzMindlin::Geometry g{{1, 0, 0}, 1e-5, 0.005, 0.01, {}, {}, 0.01, 1e-7};
  const auto r = HertzMindlin::force(p, g, nullptr, 0);
  CHECK(r.force_i.x == doctest::Approx(-4.0 / 3.0 * p.E_star * std::sqrt(0.005) * std::pow(1e-5, 1.5)).epsilon(1e-13));
  // Damping opposes approach: e < 1 makes an approaching pair push harder.
  MaterialPair pd{&a, &a, 0.5, 0.0, 0.0};
  const auto q = HertzMindlin::from_pair(pd);
  g.v_rel = {-1, 0, 0};
  CHECK(HertzMindlin::force(q, g, nullptr, 0).force_i.x < r.force_i.x);
}

TEST_CASE("Hertz-Mindlin batch kernel: the same bits as force(), lane by lane (stick, slip, new contacts)") {
  Material a{"a", 2760, 4.68e7, 0.19}, b{"b", 7800, 2e11, 0.3};
  MaterialPair pab{&a, &b, 0.79, 0.466, 0.15}, paa{&a, &a, 0.5, 0.2, 0.0};
  const HertzMindlin::Params prm[2] = {HertzMindlin::from_pair(pab),
                                       HertzMindlin::from_pair(paa)};
  Rng rng(7);
  HertzMindlin::Batch B;
  const int m = 61;  // not a multiple of the vector width
  const double dt = 1e-5;
  struct Case {
    Vec3 d, va, vb, wa, wb, h;
    double ra, rb;
    int law;
  };
  std::vector<Case> cases;
  for (int q = 0; q < m; ++q) {
    Case c;
    c.ra = rng.uniform(1.25e-3, 2.5e-3), c.rb = rng.uniform(1.25e-3, 2.5e-3);
    const double dist = (c.ra + c.rb) * rng.uniform(0.97, 0.99999);
    Vec3 dir{rng.normal(), rng.normal(), rng.normal()};
    c.d = dir * (dist / norm(dir));
    c.va = {rng.normal(), rng.normal(), rng.normal()}, c.vb = {rng.normal(), rng.normal(), rng.normal()};
    c.wa = {rng.normal() * 100, rng.normal() * 100, 0}, c.wb = {0, rng.normal() * 100, rng.normal() * 100};
    // No spring (a new contact), a small one (sticks), a large one (slips).
    const double hs = q % 3 == 0 ? 0.0 : (q % 3 == 1 ? 1e-7 : 1e-3);
    c.h = {hs * rng.normal(), hs * rng.normal(), hs * rng.normal()};
    c.law = q % 2;
    cases.push_back(c);
    const HertzMindlin::Params& p = prm[c.law];
    B.dx[q] = c.d.x, B.dy[q] = c.d.y, B.dz[q] = c.d.z, B.dist2[q] = norm2(c.d), B.rsum[q] = c.ra + c.rb;
    B.ra[q] = c.ra, B.rb[q] = c.rb, B.r_star[q] = c.ra * c.rb / (c.ra + c.rb), B.m_star[q] = 1e-4;
    B.E_star[q] = p.E_star, B.G_star[q] = p.G_star, B.damping[q] = p.damping;
    B.sqrt_st_over_sn[q] = p.sqrt_st_over_sn, B.friction[q] = p.friction;
    B.vax[q] = c.va.x, B.vay[q] = c.va.y, B.vaz[q] = c.va.z, B.vbx[q] = c.vb.x, B.vby[q] = c.vb.y, B.vbz[q] = c.vb.z;
    B.wax[q] = c.wa.x, B.way[q] = c.wa.y, B.waz[q] = c.wa.z, B.wbx[q] = c.wb.x, B.wby[q] = c.wb.y, B.wbz[q] = c.wb.z;
    B.hx[q] = c.h.x, B.hy[q] = c.h.y, B.hz[q] = c.h.z;
  }
  HertzMindlin::force_batch(B, m, dt);
  int slips = 0;
  for (int q = 0; q < m; ++q) {
    const Case& c = cases[static_cast<std::size_t>(q)];
    // The pair pass's scalar path (model/contacts.cpp), operation for operation.
    const double dist = std::sqrt(norm2(c.d));
    HertzMindlin::Geometry g;
    g.n = c.d * (1.0 / dist);
    g.overlap = c.ra + c.rb - dist;
    const double arm_a = c.ra - 0.5 * g.overlap, arm_b = c.rb - 0.5 * g.overlap;
    g.R_star = B.r_star[q];
    g.m_star = 1e-4;
    g.v_rel = c.vb - c.va;
    g.v_rel -= cross(c.wa * arm_a + c.wb * arm_b, g.n);
    g.arm_i = arm_a;
    g.dt = dt;
    double h[HertzMindlin::history_size] = {c.h.x, c.h.y, c.h.z};
    const auto r = HertzMindlin::force(prm[c.law], g, h, 3);
    const Vec3 nxt = cross(g.n, r.tangential_i);
    slips += norm(r.tangential_i) >= prm[c.law].friction * r.normal_force * (1 - 1e-12);
    CAPTURE(q);
    CHECK(B.fx[q] == r.force_i.x);
    CHECK(B.fy[q] == r.force_i.y);
    CHECK(B.fz[q] == r.force_i.z);
    CHECK(B.tx[q] == nxt.x);
    CHECK(B.ty[q] == nxt.y);
    CHECK(B.tz[q] == nxt.z);
    CHECK(B.fn[q] == r.normal_force);
    CHECK(B.arm_a[q] == arm_a);
    CHECK(B.arm_b[q] == arm_b);
    CHECK(B.hx[q] == h[0]);
    CHECK(B.hy[q] == h[1]);
    CHECK(B.hz[q] == h[2]);
  }
  MESSAGE(slips << " of " << m << " contacts slip");
  CHECK(slips > 5);
  CHECK(slips < m - 5);
}

TEST_CASE("two-sphere head-on impact, e = 1: F_n(delta), max overlap, contact time, energy vs Hertz") {
  for (const MaterialRow& m : table_5_1()) {
    CAPTURE(m.name);
    const Scene s = model::test::scene_from(two_spheres(m, 1.0, 0.0, 0.0));
    CHECK_FALSE(s.plan.rotation);  // no friction, no rolling: no angular arrays
    CHECK(s.plan.history_width == 0);
    World w = make_world(s);
    const Particles& p = w.particles();
    const double E_star = m.E / (2.0 * (1.0 - m.nu * m.nu));
    const double R_star = m.R / 2.0;
    const double m_star = p.mass[0] / 2.0;
    const double v_rel = 2.0 * m.v;
    const double delta_max_theory = std::pow(15.0 * m_star * v_rel * v_rel / (16.0 * E_star * std::sqrt(R_star)), 0.4);
    const double tc_theory = 2.9432 * delta_max_theory / v_rel;
    const double E0 = w.energies().kinetic;

    double delta_max = 0.0, fn_err = 0.0, energy_err = 0.0;
    double t_start = -1, t_end = -1, prev_delta = -1, prev_t = 0;
    while (w.time() < 3.0 * tc_theory) {
      w.step();
      const double delta = 2.0 * m.R - norm(p.x[1] - p.x[0]);
      if (delta > 0 && t_start < 0) t_start = prev_t + (w.time() - prev_t) * (-prev_delta) / (delta - prev_delta);
      if (delta <= 0 && t_start >= 0 && t_end < 0) t_end = prev_t + (w.time() - prev_t) * prev_delta / (prev_delta - delta);
      if (delta > 0) {
        delta_max = std::max(delta_max, delta);
        const Vec3 n = (p.x[1] - p.x[0]) * (1.0 / norm(p.x[1] - p.x[0]));
        const double fn = -dot(w.particles().f[0], n);
        const double hertz = 4.0 / 3.0 * E_star * std::sqrt(R_star) * std::pow(delta, 1.5);
        if (delta > 1e-3 * delta_max_theory) fn_err = std::max(fn_err, std::abs(fn / hertz - 1.0));
      }
      const Energies e = w.energies();
      energy_err = std::max(energy_err, std::abs((e.kinetic + e.elastic) / E0 - 1.0));
      prev_delta = delta;
      prev_t = w.time();
    }
    const double tc = t_end - t_start;
    MESSAGE(fmt::format("{}: F_n vs Hertz max rel err {:.2e}; delta_max {:.5e} m vs {:.5e} ({:+.3f} %); contact "
                        "time {:.5e} s vs {:.5e} ({:+.3f} %); energy drift max {:.2e}",
                        m.name, fn_err, delta_max, delta_max_theory, 100 * (delta_max / delta_max_theory - 1), tc,
                        tc_theory, 100 * (tc / tc_theory - 1), energy_err));
    CHECK(fn_err < 1e-3);
    CHECK(std::abs(delta_max / delta_max_theory - 1.0) < 0.01);
    CHECK(std::abs(tc / tc_theory - 1.0) < 0.01);
    CHECK(energy_err < 1e-3);
  }
}

TEST_CASE("oblique impact: F_t(delta_t) follows Mindlin S_t delta_t before sliding") {
  const MaterialRow m = table_5_1()[1];  // material 2 (rock-like)
  const double mu = 0.5;
  const Scene s = model::test::scene_from(two_spheres(m, 1.0, mu, 1.0, 0.0));  // 2 m/s relative tangential
  // Touching at t = 0 (gap 0): with a gap the first contact step sees a full step of tangential slip
  // over a fraction of a step of overlap and slips at once, a start-up artefact of any explicit scheme.
  REQUIRE(s.plan.rotation);
  World w = make_world(s);
  const Particles& p = w.particles();
  const double nu = m.nu, G = m.E / (2 * (1 + nu));
  const double G_star = G / (2.0 * (2.0 - nu));
  const double R_star = m.R / 2.0;
  // Independent tangential displacement: trapezoid integral of the contact-point slip velocity, kept in
  // the current tangent plane.
  Vec3 dt_vec;
  // The spheres touch at t = 0 (normal along x): the slip velocity at the start of contact.
  Vec3 vt_prev = p.v[1] - p.v[0];
  vt_prev.x = 0.0;
  bool in_contact = false;
  double err = 0.0, diff_max = 0.0, ft_peak = 0.0;
  int compared = 0;
  bool slid = false;
  for (int k = 0; k < 2000; ++k) {
    w.step();
    const Vec3 d = p.x[1] - p.x[0];
    const double dist = norm(d);
    const double delta = 2 * m.R - dist;
    const Vec3 n = d * (1.0 / dist);
    const double arm = m.R - 0.5 * delta;
    Vec3 vrel = (p.v[1] + cross(p.omega[1], n * (-arm))) - (p.v[0] + cross(p.omega[0], n * arm));
    const Vec3 vt = vrel - n * dot(vrel, n);
    if (delta <= 0) {
      if (in_contact) break;
      continue;
    }
    // Slip of j relative to i; the force on i points along it.
    const double len = norm(dt_vec);
    dt_vec -= n * dot(dt_vec, n);
    if (norm(dt_vec) > 0) dt_vec *= len / norm(dt_vec);
    dt_vec += (vt + vt_prev) * (0.5 * s.config.dt);
    in_contact = true;
    vt_prev = vt;
    const Vec3 f = w.particles().f[0];
    const double fn = -dot(f, n);
    const Vec3 ft = f + n * fn;
    if (norm(ft) >= 0.999 * mu * fn) slid = true;
    if (slid) continue;  // Mindlin no-slip holds only until the first slip
    const double mindlin = 8.0 * G_star * std::sqrt(R_star * delta) * norm(dt_vec);
    if (norm(ft) > 1e-3 * mu * fn) {
      // Vector difference relative to the peak tangential force: the relative error of |F_t| alone is
      // meaningless where the spring passes through zero (the tangential force reverses mid-contact).
      const Vec3 mindlin_vec = dt_vec * (8.0 * G_star * std::sqrt(R_star * delta));
      diff_max = std::max(diff_max, norm(ft - mindlin_vec));
      ft_peak = std::max(ft_peak, norm(ft));
      err = std::max(err, std::abs(norm(ft) / mindlin - 1.0));
      ++compared;
    }
  }
  MESSAGE(fmt::format("oblique impact (material 2, 20 m/s normal, 2 m/s tangential, mu 0.5): {} steps before "
                      "sliding compared; max |F_t - S_t delta_t| / max|F_t| = {:.2e} (peak F_t {:.4g} N); "
                      "max |F_t|/(S_t |delta_t|) - 1 = {:.2e} (largest where F_t reverses through zero)",
                      compared, diff_max / ft_peak, ft_peak, err));
  CHECK(compared > 50);
  CHECK(diff_max / ft_peak < 1e-3);
}

TEST_CASE("Hertz-Mindlin wall batch kernel: the same bits as force(), lane by lane (stick, slip, new contacts)") {
  Material a{"a", 2760, 4.68e7, 0.19}, b{"b", 7800, 2e11, 0.3};
  MaterialPair pab{&a, &b, 0.79, 0.466, 0.15}, paa{&a, &a, 0.5, 0.2, 0.0};
  const HertzMindlin::Params prm[2] = {HertzMindlin::from_pair(pab), HertzMindlin::from_pair(paa)};
  Rng rng(8);
  HertzMindlin::WallBatch B;
  const int m = 59;  // not a multiple of the vector width
  const double dt = 1e-5;
  std::vector<HertzMindlin::Geometry> geo;
  std::vector<Vec3> springs;
  for (int q = 0; q < m; ++q) {
    HertzMindlin::Geometry g;
    Vec3 dir{rng.normal(), rng.normal(), rng.normal()};
    g.n = dir * (1.0 / norm(dir));
    g.R_star = rng.uniform(1.25e-3, 2.5e-3);
    g.overlap = g.R_star * rng.uniform(1e-5, 0.03);
    g.m_star = 1e-4 * rng.uniform(0.5, 2.0);
    g.v_rel = {rng.normal(), rng.normal(), rng.normal()};
    g.dt = dt;
    // No spring (a new contact), a small one (sticks), a large one (slips).
    const double hs = q % 3 == 0 ? 0.0 : (q % 3 == 1 ? 1e-7 : 1e-3);
    const Vec3 h{hs * rng.normal(), hs * rng.normal(), hs * rng.normal()};
    geo.push_back(g);
    springs.push_back(h);
    B.nx[q] = g.n.x, B.ny[q] = g.n.y, B.nz[q] = g.n.z, B.overlap[q] = g.overlap;
    B.r_star[q] = g.R_star, B.m_star[q] = g.m_star;
    B.vx[q] = g.v_rel.x, B.vy[q] = g.v_rel.y, B.vz[q] = g.v_rel.z;
    HertzMindlin::load_params(B, q, prm[q % 2]);
    B.hx[q] = h.x, B.hy[q] = h.y, B.hz[q] = h.z;
  }
  HertzMindlin::wall_force_batch(B, m, dt);
  int slips = 0;
  for (int q = 0; q < m; ++q) {
    const auto& g = geo[static_cast<std::size_t>(q)];
    const Vec3& s = springs[static_cast<std::size_t>(q)];
    double h[HertzMindlin::history_size] = {s.x, s.y, s.z};
    const auto r = HertzMindlin::force(prm[q % 2], g, h, 3);
    slips += norm(r.tangential_i) >= prm[q % 2].friction * r.normal_force * (1 - 1e-12);
    CAPTURE(q);
    CHECK(B.fx[q] == r.force_i.x);
    CHECK(B.fy[q] == r.force_i.y);
    CHECK(B.fz[q] == r.force_i.z);
    CHECK(B.tx[q] == r.tangential_i.x);
    CHECK(B.ty[q] == r.tangential_i.y);
    CHECK(B.tz[q] == r.tangential_i.z);
    CHECK(B.fn[q] == r.normal_force);
    CHECK(B.hx[q] == h[0]);
    CHECK(B.hy[q] == h[1]);
    CHECK(B.hz[q] == h[2]);
  }
  MESSAGE(slips << " of " << m << " wall contacts slip");
  CHECK(slips > 5);
  CHECK(slips < m - 5);
}
