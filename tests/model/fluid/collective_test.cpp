// SPDX-License-Identifier: MIT
// Collective yield resistance (model/fluid/collective.*): the footprint area against closed forms, the
// footing factor, the cluster rule on hand-built clusters, and a raft of spheres in the engine that sinks
// to the depth where its load equals the footing's bearing capacity (solved independently here).
#include "model/fluid/collective.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "base/rng.h"
#include "model/fluid/field.h"
#include "model/run.h"
#include "model/scene.h"

using namespace pastemix;
using namespace pastemix::model;
using namespace pastemix::model::fluid;

namespace {

// Area of the lens shared by two discs of radius r at centre distance c (m2).
double lens(double r, double c) { return 2.0 * r * r * std::acos(c / (2.0 * r)) - 0.5 * c * std::sqrt(4.0 * r * r - c * c); }

// The pairs (a < b) of p whose gap is below `gap` (m), by brute force: the candidate pairs a World would give.
void near_pairs(const Particles& p, double gap, std::vector<std::uint32_t>& pi, std::vector<std::uint32_t>& pj) {
  for (std::uint32_t a = 0; a < p.size(); ++a)
    for (std::uint32_t b = a + 1; b < p.size(); ++b)
      if (norm(p.x[a] - p.x[b]) < p.radius[a] + p.radius[b] + gap) pi.push_back(a), pj.push_back(b);
}

}  // namespace

TEST_CASE("collective: a lone disc's strips sum to its area to round-off, wherever it sits on the strips") {
  // Each strip takes the disc's exact area between the strip's boundaries (the chord's integral at both), so
  // the strips telescope to pi r^2: an extra, missing or shifted strip shows here at >= 4e-5 (a strip at the
  // disc's edge, r = 600 h). Radii from 3 strips to 600 (several blocks of 64 strips), centres anywhere on the
  // strips' grid; round-off ~3.5e-9 (the boundaries' offsets y_lo + k h - y_c, |y| ~ 0.1 m, cancel; the same
  // with libm's asin).
  Rng rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const double r = 0.001 * std::pow(200.0, rng.uniform()), h = 0.001 / 3.0 * (1.0 + 0.01 * rng.uniform());
    const double x = rng.uniform(-0.1, 0.1), y = rng.uniform(-0.1, 0.1);
    INFO("trial " << trial << ": r = " << r << " m, h = " << h << " m");
    CHECK(disc_union_area({x}, {y}, {r}, h) == doctest::Approx(M_PI * r * r).epsilon(1e-8));
    // Two discs that share no strip: the sum of both.
    const double r2 = 0.5 * r, y2 = y + r + r2 + 3.0 * h;
    CHECK(disc_union_area({x, x}, {y, y2}, {r, r2}, h) == doctest::Approx(M_PI * (r * r + r2 * r2)).epsilon(1e-8));
  }
}

TEST_CASE("collective: footprint area of discs against closed forms, to 0.3 % at strips r/16 wide") {
  const double r = 0.004, h = r / 16.0;
  const double one = disc_union_area({0.0}, {0.0}, {r}, h);
  CHECK(std::abs(one / (M_PI * r * r) - 1.0) < 3e-3);
  // Two overlapping discs: 2 pi r^2 minus the lens, for centre distances 0.5 r .. 1.9 r.
  for (double c : {0.5 * r, 1.0 * r, 1.5 * r, 1.9 * r}) {
    const double exact = 2.0 * M_PI * r * r - lens(r, c);
    INFO("centre distance " << c / r << " r");
    CHECK(std::abs(disc_union_area({0.0, 0.96 * c}, {0.0, 0.28 * c}, {r, r}, h) / exact - 1.0) < 3e-3);
  }
  // A square raft of touching discs (no overlap) and two far-apart discs: the sum of the discs.
  // (Spacing 2 r (1 + 1e-9): rows of discs not aligned with the strips, the case that costs accuracy.)
  std::vector<double> x, y, rr;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) x.push_back(2.0 * r * i * (1 + 1e-9)), y.push_back(2.0 * r * j * (1 + 1e-9)), rr.push_back(r);
  CHECK(std::abs(disc_union_area(x, y, rr, h) / (36.0 * M_PI * r * r) - 1.0) < 3e-3);
  CHECK(std::abs(disc_union_area({0.0, 1.0}, {0.0, 0.5}, {r, 2.0 * r}, h) / (5.0 * M_PI * r * r) - 1.0) < 3e-3);
  // Against Monte Carlo on random clusters of unequal discs (within 4 standard errors plus the 0.3 %).
  Rng rng(7);
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> cx, cy, cr;
    for (int k = 0; k < 12; ++k)
      cx.push_back(0.02 * rng.uniform()), cy.push_back(0.02 * rng.uniform()), cr.push_back(0.002 + 0.004 * rng.uniform());
    const double area = disc_union_area(cx, cy, cr, 0.002 / 16.0);
    const long n = 400000;
    long hit = 0;
    for (long s = 0; s < n; ++s) {
      const double px = -0.006 + 0.032 * rng.uniform(), py = -0.006 + 0.032 * rng.uniform();
      for (std::size_t k = 0; k < cx.size(); ++k)
        if ((px - cx[k]) * (px - cx[k]) + (py - cy[k]) * (py - cy[k]) < cr[k] * cr[k]) {
          ++hit;
          break;
        }
    }
    const double frac = static_cast<double>(hit) / n, box = 0.032 * 0.032;
    const double se = box * std::sqrt(frac * (1.0 - frac) / n);
    INFO("trial " << trial << ": scan lines " << area << " m2, Monte Carlo " << frac * box << " +- " << se);
    CHECK(std::abs(area - frac * box) < 4.0 * se + 3e-3 * area);
  }
}

TEST_CASE("collective: lens areas of two discs: disjoint, nested, equal discs half a radius apart, symmetric") {
  const double r = 0.003;
  CHECK(lens_area(r, r, 2.0 * r) == 0.0);
  CHECK(lens_area(r, 2.0 * r, 0.5 * r) == doctest::Approx(M_PI * r * r));
  CHECK(lens_area(r, r, 0.0) == doctest::Approx(M_PI * r * r));
  CHECK(lens_area(r, r, 0.5 * r) == doctest::Approx(lens(r, 0.5 * r)).epsilon(1e-12));
  CHECK(lens_area(r, 1.7 * r, 1.2 * r) == doctest::Approx(lens_area(1.7 * r, r, 1.2 * r)).epsilon(1e-12));
}

TEST_CASE("collective: Skempton's N_c: 6 at the surface, 6 (1 + 0.2 D/B) below it, 9 from D/B = 2.5 on") {
  CHECK(skempton_nc(0.1, 0.0) == doctest::Approx(6.0));
  CHECK(skempton_nc(0.1, 0.1) == doctest::Approx(7.2));
  CHECK(skempton_nc(0.1, 0.25) == doctest::Approx(9.0));
  CHECK(skempton_nc(0.1, 1.0) == doctest::Approx(9.0));
  CHECK(skempton_nc(0.1, -0.01) == doctest::Approx(6.0));  // above the surface: no embedment
}

TEST_CASE("collective: the cluster rule: isolated spheres keep their law, a raft is held by its footing, a column by its lowest sphere and its side") {
  const double r = 0.005, tau = 20.0, zs = 0.1;
  Particles p;
  std::vector<std::uint32_t> pi, pj;
  // A 4 x 4 raft, centres 1 mm below the surface, touching; one sphere far away; a vertical column of 5.
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) p.add(0, r, 2700, {2.0 * r * i, 2.0 * r * j, zs - 0.001}, {}, {});
  p.add(0, r, 2700, {0.5, 0.5, 0.05}, {}, {});
  for (int k = 0; k < 5; ++k) p.add(0, r, 2700, {-0.3, 0.0, 0.05 + 2.0 * r * k}, {}, {});
  // Candidate pairs: every pair (a superset of the touching ones, as the pair list is).
  for (std::uint32_t a = 0; a < p.size(); ++a)
    for (std::uint32_t b = a + 1; b < p.size(); ++b) pi.push_back(a), pj.push_back(b);
  std::vector<long> members;
  std::vector<double> d0;
  for (long a = 0; a < static_cast<long>(p.size()); ++a) members.push_back(a), d0.push_back(0.02);
  CollectiveYield rule;
  std::vector<double> f;
  const ClusterStats s = rule.factors({&p, &members, &d0, &pi, &pj, zs, tau}, f);
  CHECK(s.clusters == 2);
  CHECK(s.largest == 16);
  // The raft: A = 16 pi r^2 (touching discs), B = 8 r, D = r + 1 mm.
  const double A = 16.0 * M_PI * r * r, B = 8.0 * r, D = r + 0.001;
  const double footing = tau * (6.0 * (1.0 + 0.2 * D / B) * A + M_PI * B * D);
  CHECK(f[0] == doctest::Approx(footing / (16 * 0.02)).epsilon(3e-3));
  CHECK(f[15] == f[0]);
  CHECK(f[16] == 1.0);                                      // isolated
  // The column: the four upper spheres are wholly shadowed (factor 0); the lowest carries the column's end
  // bearing, min(its own D0, N_c tau_y pi r^2), plus the side shear along the column's embedded length.
  const double Dc = zs - (0.05 - r), Bc = 2.0 * r;
  const double end = std::min(0.02, tau * skempton_nc(Bc, Dc) * M_PI * r * r), side = tau * M_PI * Bc * Dc;
  CHECK(f[17] == doctest::Approx(std::max(0.02, std::min(0.1, end + side)) / 0.02).epsilon(5e-3));
  CHECK(f[17] > 1.0);  // the side shear: more than the sphere's own rest drag
  for (int k = 18; k < 22; ++k) CHECK(f[static_cast<std::size_t>(k)] == 0.0);
  // Spheres 2 % of a radius apart still touch; 3 % apart they do not.
  Particles two;
  two.add(0, r, 2700, {0, 0, 0.05}, {}, {});
  two.add(0, r, 2700, {2.0 * r + 0.019 * r, 0, 0.05}, {}, {});
  std::vector<long> m2{0, 1};
  std::vector<double> d2{1.0, 1.0};
  std::vector<std::uint32_t> i2{0}, j2{1};
  rule.factors({&two, &m2, &d2, &i2, &j2, zs, tau}, f);
  CHECK(f[0] < 1.0);
  two.x[1].x = 2.0 * r + 0.03 * r;
  rule.factors({&two, &m2, &d2, &i2, &j2, zs, tau}, f);
  CHECK(f[0] == 1.0);
}

namespace {

// n x n raft of touching spheres (diameter d) with their tops at the paste surface, in a wide Bingham box.
std::string raft_scene(int n, double d, double rho_p, double tau, const std::string& collective, double end) {
  // Centres 1e-9 d further apart than touching (the scene rejects overlaps of round-off size): they still
  // touch for the rule (gap < 2 % of r) and exert no contact force.
  const double r = 0.5 * d, zs = 0.2, s_ = d * (1.0 + 1e-9);
  std::string s = fmt::format(
      "seed = 1\ntime_step = 1e-4\nend_time = {end}\n[domain]\nmin = [-0.3, -0.3, -0.01]\nmax = [0.3, 0.3, 0.4]\n"
      "[physics]\nrotation = false\n[contact]\nlaw = \"hertz_mindlin\"\n"
      "[[material]]\nname = \"rock\"\ndensity = {rho}\nyoungs_modulus = 1e7\npoisson_ratio = 0.3\n"
      "[[interaction]]\nmaterials = \"rock/rock\"\nrestitution = 0.5\nfriction = 0.0\n",
      fmt::arg("end", end), fmt::arg("rho", rho_p));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      s += fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = {:.17g}\nposition = [{:.17g}, {:.17g}, {:.17g}]\n", r,
                       s_ * (i - 0.5 * (n - 1)), s_ * (j - 0.5 * (n - 1)), zs - r);
  s += fmt::format(
      "[[fluid]]\nx = [-0.25, 0.25]\ny = [-0.25, 0.25]\nbottom = 0\nsurface = {zs}\ndensity = 1500\n"
      "rheology = \"bingham\"\nyield_stress = {tau}\nplastic_viscosity = 1.0\n"
      "curve = \"power_blend\"\ncoefficients = [24.0, 1.0, 0.5, 0.4, 1.5]\nsurface_rise = false\ncollective = \"{c}\"\n",
      fmt::arg("zs", zs), fmt::arg("tau", tau), fmt::arg("c", collective));
  return s;
}

struct RaftEnd {
  double sink = 0.0;  // m, how far the raft's bottom went below its start
  double speed = 0.0;  // m/s, largest at the end
};

RaftEnd run_raft(int n, double d, double rho_p, double tau, const std::string& collective) {
  const Scene scene = parse_scene(raft_scene(n, d, rho_p, tau, collective, 6.0), "raft.toml");
  World w = make_world(scene);
  const double z0 = w.particles().x[0].z;
  w.advance(std::lround(6.0 / 1e-4));
  double speed = 0.0;
  for (const Vec3& v : w.particles().v) speed = std::max(speed, norm(v));
  return {z0 - w.particles().x[0].z, speed};
}

}  // namespace

TEST_CASE("collective: a 6 x 6 raft sinks to the depth where its load equals the footing capacity (within 0.5 %), without the rule, or alone, a sphere stays") {
  const double d = 0.01, r = 0.005, tau = 20.0, rho_f = 1500.0, g = 9.81;
  const double volume = 4.0 / 3.0 * M_PI * r * r * r;
  // Plastic viscosity 1 Pa.s: the sinking is overdamped (relaxation ~0.7 s), so the raft creeps onto the
  // static balance instead of overshooting it, as a lighter paste lets it (a real, dynamic effect).
  // Net weight per submerged sphere 0.015 N: below one sphere's rest drag (~0.0238 N: it stays alone) but
  // above its share of the raft's footing at the start (~0.0108 N).
  const double rho_p = rho_f + 0.015 / (g * volume);
  const int n = 6;
  // Equilibrium embedment D: n^2 (rho_p - rho_f) g V = tau (N_c(D/B) A + pi B D), A = n^2 pi r^2, B = 2 n r.
  const double load = n * n * (rho_p - rho_f) * g * volume;
  const double A = n * n * M_PI * r * r, B = std::sqrt(4.0 * A / M_PI);
  double lo = 0.0, hi = 0.15;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (tau * (skempton_nc(B, mid) * A + M_PI * B * mid) < load ? lo : hi) = mid;
  }
  const double d_expected = lo;  // embedment of the raft's bottom (m); it starts at d = 2 r
  const RaftEnd with = run_raft(n, d, rho_p, tau, "bearing_capacity");
  INFO("raft bottom " << (2 * r + with.sink) * 1e3 << " mm below the surface, expected " << d_expected * 1e3);
  CHECK(with.speed < 3e-5);  // still creeping onto the balance (time constant ~0.7 s): 0.02 mm to go
  CHECK(std::abs((2.0 * r + with.sink) / d_expected - 1.0) < 0.005);  // the footprint to 0.2 %, the creep
  const RaftEnd without = run_raft(n, d, rho_p, tau, "none");
  CHECK(without.sink == 0.0);  // each sphere's own rest drag holds it: exactly no creep
  const RaftEnd alone = run_raft(1, d, rho_p, tau, "bearing_capacity");
  CHECK(alone.sink == 0.0);
}

TEST_CASE("collective: the footprints shared by 2, 3 or 7 parts give the factors of one part, to the bit") {
  // CollectiveYield::begin / footprints(t) / finish: the World's threads each measure a share of every
  // cluster's strips; the covered lengths are summed in strip order, so any number of parts (and any thread
  // running any part) gives factors() exactly. A random heap of 400 spheres of 1.25-2.5 mm, partly above the
  // surface (wetted caps), several clusters.
  const double tau = 138.0, zs = 0.02;
  Rng rng(20261202);
  Particles p;
  for (int k = 0; k < 400; ++k) {
    const double r = 1.25e-3 + 1.25e-3 * rng.uniform();
    p.add(0, r, 2760, {0.04 * rng.uniform(), 0.03 * rng.uniform(), zs - 0.012 + 0.014 * rng.uniform()}, {}, {});
  }
  std::vector<std::uint32_t> pi, pj;
  near_pairs(p, 1e-4, pi, pj);
  std::vector<long> members;
  std::vector<double> d0;
  for (long a = 0; a < static_cast<long>(p.size()); ++a) members.push_back(a), d0.push_back(0.01 + 0.001 * static_cast<double>(a % 7));
  const CollectiveInput in{&p, &members, &d0, &pi, &pj, zs, tau};
  CollectiveYield one;
  std::vector<double> f1;
  const ClusterStats s1 = one.factors(in, f1);
  CHECK(s1.clusters >= 2);
  for (int parts : {2, 3, 7}) {
    CollectiveYield rule;
    std::vector<double> f;
    rule.begin(in, parts);
    for (int t = parts - 1; t >= 0; --t) rule.footprints(t);  // any order of the parts
    const ClusterStats s = rule.finish(in, f);
    CHECK(s.clusters == s1.clusters);
    CHECK(s.min_factor == s1.min_factor);
    long same = 0;
    for (std::size_t k = 0; k < f.size(); ++k) same += f[k] == f1[k] ? 1 : 0;
    CHECK(same == static_cast<long>(f1.size()));
  }
}

TEST_CASE("collective: the parts' strips are cut at equal shares of the discs' strip crossings") {
  // One cluster crowded at one side (a dense pile of small spheres at low y, a sparse arm of large ones
  // reaching to high y): cut at equal rows, part 0 would have most of the crossings; cut by crossings, each
  // of 2 or 3 parts has its share within one row's crossings. The factors stay those of one part (the test
  // above checks the bits; here the counts).
  const double tau = 138.0, zs = 0.02, r_small = 1.25e-3, r_big = 2.5e-3;
  Particles p;
  for (int k = 0; k < 12; ++k)      // a touching chain along y: the arm
    p.add(0, r_big, 2760, {0.0, 1.99 * r_big * k, zs - 0.004}, {}, {});
  for (int ix = 1; ix <= 10; ++ix)  // the crowd: small spheres in a touching block at the arm's low end
    for (int iy = 0; iy < 4; ++iy)
      p.add(0, r_small, 2760, {1.99 * r_small * ix + r_big - r_small, 1.99 * r_small * iy, zs - 0.004}, {}, {});
  std::vector<std::uint32_t> pi, pj;
  near_pairs(p, 1e-4, pi, pj);
  std::vector<long> members;
  std::vector<double> d0;
  for (long a = 0; a < static_cast<long>(p.size()); ++a) members.push_back(a), d0.push_back(0.02);
  const CollectiveInput in{&p, &members, &d0, &pi, &pj, zs, tau};
  for (int parts : {2, 3}) {
    CollectiveYield rule;
    rule.begin(in, parts);
    const std::vector<long>& cut = rule.part_cuts();
    REQUIRE(cut.size() == static_cast<std::size_t>(parts) + 1);  // one cluster
    const long rows = cut.back();
    REQUIRE(rows > 100);
    // The strips' layout as strip_layout makes it (r_min / 16), and each disc's strips, recounted here.
    double y_lo = INFINITY, y_hi = -INFINITY;
    for (std::size_t a = 0; a < p.size(); ++a)
      y_lo = std::min(y_lo, p.x[a].y - p.radius[a]), y_hi = std::max(y_hi, p.x[a].y + p.radius[a]);
    const double step = (y_hi - y_lo) / static_cast<double>(rows);
    std::vector<long> per_row(static_cast<std::size_t>(rows), 0);
    long total = 0;
    for (std::size_t a = 0; a < p.size(); ++a) {
      const long lo = std::max(0L, static_cast<long>(std::floor((p.x[a].y - p.radius[a] - y_lo) / step)));
      const long hi = std::min(rows - 1, static_cast<long>(std::floor((p.x[a].y + p.radius[a] - y_lo) / step)));
      for (long row = lo; row <= hi; ++row) ++per_row[static_cast<std::size_t>(row)], ++total;
    }
    long widest = 0;
    for (long c : per_row) widest = std::max(widest, c);
    const auto share = [&](long r0, long r1) {
      long s = 0;
      for (long row = r0; row < r1; ++row) s += per_row[static_cast<std::size_t>(row)];
      return s;
    };
    INFO(parts << " parts, " << rows << " strips, " << total << " crossings");
    for (int t = 0; t < parts; ++t) {
      CHECK(cut[static_cast<std::size_t>(t)] < cut[static_cast<std::size_t>(t) + 1]);
      CHECK(std::abs(share(cut[static_cast<std::size_t>(t)], cut[static_cast<std::size_t>(t) + 1]) * parts - total) <=
            parts * widest);
    }
    // Equal rows would not do: part 0's share of the crossings.
    CHECK(share(0, rows / parts) * parts > total * 3 / 2);
  }
}
