// SPDX-License-Identifier: MIT
// Hertz-Mindlin (no slip) with restitution damping and a Coulomb-limited tangential spring: the law EDEM and
// LIGGGHTS call "hertz" (DESIGN.md section 3). Rolling resistance is a law of its own (laws/rolling.h).
//
//   1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2    1/R* = 1/R1 + 1/R2    1/m* = 1/m1 + 1/m2
//   1/G* = (2-nu1)/G1 + (2-nu2)/G2        beta = ln e / sqrt(ln^2 e + pi^2)
//   F_n = 4/3 E* sqrt(R*) delta^1.5       S_n = 2 E* sqrt(R* delta)
//   F_n^d = -2 sqrt(5/6) beta sqrt(S_n m*) v_n
//   S_t = 8 G* sqrt(R* delta)             F_t = -S_t delta_t,  F_t^d = -2 sqrt(5/6) beta sqrt(S_t m*) v_t
//   |F_t| <= mu_s F_n (on slip the spring is rescaled so that S_t |delta_t| = mu_s F_n)
//
// Walls are spheres of infinite radius and mass: the caller passes R* = R_particle and m* = m_particle.
// The kernel is stateless; the tangential spring delta_t lives in the caller's history slots, keyed by the
// pair of particle ids.
#pragma once

#include <algorithm>
#include <cmath>

#include "base/params.h"
#include "base/units.h"
#include "model/material.h"
#include "model/vec3.h"

namespace pastemix::model {

struct HertzMindlin {
  static constexpr const char* name = "hertz_mindlin";
  struct Params {
    using Law = HertzMindlin;  // lets a visitor of LawTable name the law of a table
    double E_star = 0.0;         // Pa, effective Young's modulus
    double G_star = 0.0;         // Pa, effective shear modulus
    double damping = 0.0;        // -, -2 sqrt(5/6) beta >= 0 (0 when e = 1)
    double sqrt_st_over_sn = 0.0;  // -, sqrt(S_t / S_n) = sqrt(4 G* / E*): saves a sqrt per contact
    double friction = 0.0;       // -, mu_s
  };

  // History per contact: the tangential spring (m). A scene without friction needs none (width 0).
  static constexpr int history_size = 3;
  static int history_width(bool tangential) { return tangential ? history_size : 0; }
  // Whether a pair with these parameters needs the tangential history.
  static bool needs_history(const Params& p) { return p.friction > 0.0; }
  static constexpr bool needs_torque = true;

  // The law reads no [contact] keys of its own: e, mu_s and the materials' E, nu come with the pair.
  static Params from_params(const pastemix::Params&, const MaterialPair& p) { return from_pair(p); }

  // Mixes a material pair once, at load time.
  static Params from_pair(const MaterialPair& p) {
    const Material& a = *p.a;
    const Material& b = *p.b;
    Params q;
    q.E_star = 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                      (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
    q.G_star = 1.0 / ((2.0 - a.poisson_ratio) / a.shear_modulus() + (2.0 - b.poisson_ratio) / b.shear_modulus());
    const double le = std::log(p.restitution);
    const double beta = le / std::sqrt(le * le + units::pi * units::pi);
    q.damping = -2.0 * std::sqrt(5.0 / 6.0) * beta;
    q.sqrt_st_over_sn = std::sqrt(4.0 * q.G_star / q.E_star);
    q.friction = p.friction;
    return q;
  }

  // J, elastic energy of the normal spring at overlap delta: 8/15 E* sqrt(R*) delta^2.5 (tangential excluded).
  static double elastic_energy(const Params& p, double R_star, double overlap) {
    return 8.0 / 15.0 * p.E_star * std::sqrt(R_star) * std::pow(overlap, 2.5);
  }

  // Geometry and kinematics of one contact, seen from particle i. n points from i to j; for a wall, i is
  // the particle and n points from the particle towards the wall.
  struct Geometry {
    Vec3 n;              // unit normal, i -> j
    double overlap;      // m, > 0
    double R_star;       // m
    double m_star;       // kg
    Vec3 v_rel;          // m/s, velocity of j's contact point minus i's
    Vec3 w_rel;          // rad/s, omega_i - omega_j: unused here (the rolling law's input)
    double arm_i;        // m, centre of i to contact point
    double dt;           // s
  };
  struct Result {
    Vec3 force_i;          // N, on i (j gets -force_i)
    Vec3 tangential_i;     // N, tangential part of force_i (the caller turns it into torques)
    double normal_force;   // N, F_n >= 0 used for Coulomb and rolling limits
    double normal_stiffness;  // N/m, S_n = 2 E* sqrt(R* delta) (a rolling spring scales with it)
  };

  // Structure of arrays for force_batch(): kBatch sphere-sphere contacts, one per lane. Inputs as in
  // Geometry (separation d = x_j - x_i, |d|^2, r_i + r_j, radii, velocities, angular velocities), the
  // parameters of each contact, and the tangential spring (hx, hy, hz: in and out). Outputs: force on i,
  // n x F_t (the caller scales it by each sphere's arm), F_n >= 0 and the two arms.
  static constexpr int kBatch = 64;
  struct Batch {
    double dx[kBatch], dy[kBatch], dz[kBatch], dist2[kBatch], rsum[kBatch], ra[kBatch], rb[kBatch];
    double r_star[kBatch], m_star[kBatch];
    double E_star[kBatch], G_star[kBatch], damping[kBatch], sqrt_st_over_sn[kBatch], friction[kBatch];
    double vax[kBatch], vay[kBatch], vaz[kBatch], vbx[kBatch], vby[kBatch], vbz[kBatch];
    double wax[kBatch], way[kBatch], waz[kBatch], wbx[kBatch], wby[kBatch], wbz[kBatch];
    double hx[kBatch], hy[kBatch], hz[kBatch];
    double fx[kBatch], fy[kBatch], fz[kBatch], tx[kBatch], ty[kBatch], tz[kBatch];
    double fn[kBatch], arm_a[kBatch], arm_b[kBatch];
  };
  // Lane e of b gets the parameters of its contact.
  static void load_params(Batch& b, int e, const Params& p) {
    b.E_star[e] = p.E_star, b.G_star[e] = p.G_star, b.damping[e] = p.damping;
    b.sqrt_st_over_sn[e] = p.sqrt_st_over_sn, b.friction[e] = p.friction;
  }
  // One contact of a batch kernel, from its unit normal n (towards the other body), v_rel, overlap, R*, m*
  // and parameters: force() with a tangential spring, in the same order of operations, the branches as
  // selects (both sides computed, the lane's side kept), so that a loop over lanes vectorizes and every
  // lane gets the bits force() gives. The spring (hx, hy, hz) is updated in place.
  struct Lane {
    double fx, fy, fz, ftx, fty, ftz, fn;  // force on i, its tangential part, F_n >= 0
  };
  static inline Lane lane(double nx, double ny, double nz, double vx, double vy, double vz, double overlap,
                          double r_star, double m_star, double E_star, double G_star, double damping,
                          double sqrt_st_over_sn, double friction, double dt, double& hx, double& hy, double& hz) {
    const double sqrt_Rd = std::sqrt(r_star * overlap);
    const double Sn = 2.0 * E_star * sqrt_Rd;
    const double fn_elastic = (2.0 / 3.0) * Sn * overlap;
    const double vn = vx * nx + vy * ny + vz * nz;
    const double sqrt_sn_m = std::sqrt(Sn * m_star);
    const double fn = fn_elastic - damping * sqrt_sn_m * vn;
    const double fn_pos = fn < 0.0 ? 0.0 : fn;  // std::max(fn, 0.0)
    // The stored spring, turned into the tangent plane and rescaled to its old length.
    double xx = hx, xy = hy, xz = hz;
    const double xi_old2 = xx * xx + xy * xy + xz * xz;
    const double dxn = xx * nx + xy * ny + xz * nz;
    const double px = xx - nx * dxn, py = xy - ny * dxn, pz = xz - nz * dxn;
    const double xi_new2 = px * px + py * py + pz * pz;
    // Every value is computed before the selects: an operation only inside a select would be one that
    // may trap, and the compiler keeps such branches (no vectorization).
    const double scale = std::sqrt(xi_old2 / xi_new2);
    const double qx = px * scale, qy = py * scale, qz = pz * scale;
    const bool turn = xi_old2 > 0.0, rescale = xi_new2 > 0.0;
    xx = turn ? (rescale ? qx : px) : xx;
    xy = turn ? (rescale ? qy : py) : xy;
    xz = turn ? (rescale ? qz : pz) : xz;
    const double tvx = vx - nx * vn, tvy = vy - ny * vn, tvz = vz - nz * vn;
    xx += tvx * dt;
    xy += tvy * dt;
    xz += tvz * dt;
    const double St = 8.0 * G_star * sqrt_Rd;
    const double c = damping * sqrt_sn_m * sqrt_st_over_sn;
    double ftx = xx * St + tvx * c, fty = xy * St + tvy * c, ftz = xz * St + tvz * c;
    const double ft_len2 = ftx * ftx + fty * fty + ftz * ftz;
    const double ft_max = friction * fn_pos;
    // Slip: the friction force on the Coulomb limit, the spring carrying all of it.
    const bool slip = ft_len2 > ft_max * ft_max;
    const double ft_len = std::sqrt(ft_len2);
    const bool some = ft_len > 0.0, stiff = St > 0.0;
    const double r = ft_max / ft_len, inv_st = 1.0 / St;
    const double rx = ftx * r, ry = fty * r, rz = ftz * r;
    const double sx2 = some ? rx : 0.0, sy2 = some ? ry : 0.0, sz2 = some ? rz : 0.0;
    const double ux = sx2 * inv_st, uy = sy2 * inv_st, uz = sz2 * inv_st;
    xx = slip ? (stiff ? ux : 0.0) : xx;
    xy = slip ? (stiff ? uy : 0.0) : xy;
    xz = slip ? (stiff ? uz : 0.0) : xz;
    ftx = slip ? sx2 : ftx;
    fty = slip ? sy2 : fty;
    ftz = slip ? sz2 : ftz;
    hx = xx, hy = xy, hz = xz;
    return {nx * (-fn) + ftx, ny * (-fn) + fty, nz * (-fn) + ftz, ftx, fty, ftz, fn_pos};
  }

  // Contacts 0 .. m-1 of b: the operations of the pair pass plus force() with a tangential spring (width
  // 3), rotation on and no rolling spring, in the same order, lane by lane; the branches become selects
  // (both sides computed, lanes whose side is not taken discarded), so the compiler runs 4 contacts per
  // AVX2 instruction and every lane gets the bits force() gives that contact.
  static void force_batch(Batch& b, int m, double dt) {
    for (int q = 0; q < m; ++q) {
      const double dist = std::sqrt(b.dist2[q]);
      const double inv = 1.0 / dist;
      const double nx = b.dx[q] * inv, ny = b.dy[q] * inv, nz = b.dz[q] * inv;
      const double overlap = b.rsum[q] - dist;
      const double arm_a = b.ra[q] - 0.5 * overlap, arm_b = b.rb[q] - 0.5 * overlap;
      // v_rel = v_b - v_a - (arm_a w_a + arm_b w_b) x n
      const double sx = b.wax[q] * arm_a + b.wbx[q] * arm_b;
      const double sy = b.way[q] * arm_a + b.wby[q] * arm_b;
      const double sz = b.waz[q] * arm_a + b.wbz[q] * arm_b;
      const double vx = (b.vbx[q] - b.vax[q]) - (sy * nz - sz * ny);
      const double vy = (b.vby[q] - b.vay[q]) - (sz * nx - sx * nz);
      const double vz = (b.vbz[q] - b.vaz[q]) - (sx * ny - sy * nx);
      const Lane c = lane(nx, ny, nz, vx, vy, vz, overlap, b.r_star[q], b.m_star[q], b.E_star[q], b.G_star[q],
                          b.damping[q], b.sqrt_st_over_sn[q], b.friction[q], dt, b.hx[q], b.hy[q], b.hz[q]);
      b.fx[q] = c.fx;
      b.fy[q] = c.fy;
      b.fz[q] = c.fz;
      b.tx[q] = ny * c.ftz - nz * c.fty;  // n x F_t
      b.ty[q] = nz * c.ftx - nx * c.ftz;
      b.tz[q] = nx * c.fty - ny * c.ftx;
      b.fn[q] = c.fn;
      b.arm_a[q] = arm_a;
      b.arm_b[q] = arm_b;
    }
  }

  // Structure of arrays for wall_force_batch(): kBatch sphere-wall contacts, one per lane, with the
  // geometry the wall pass computes (n towards the wall, overlap, R* = R, m* = m, v_rel = v_wall - v -
  // w x (arm n)), the parameters and the tangential spring (in and out). Outputs: the force on the sphere,
  // its tangential part and F_n >= 0. (Issue 19: one wall contact through force() cost ~6 batched pair
  // contacts; the box walls were ~11 % of the settled bed and ~9 % of the pour.)
  struct WallBatch {
    double nx[kBatch], ny[kBatch], nz[kBatch], overlap[kBatch], r_star[kBatch], m_star[kBatch];
    double vx[kBatch], vy[kBatch], vz[kBatch];
    double E_star[kBatch], G_star[kBatch], damping[kBatch], sqrt_st_over_sn[kBatch], friction[kBatch];
    double hx[kBatch], hy[kBatch], hz[kBatch];
    double fx[kBatch], fy[kBatch], fz[kBatch], tx[kBatch], ty[kBatch], tz[kBatch], fn[kBatch];
  };
  static void load_params(WallBatch& b, int e, const Params& p) {
    b.E_star[e] = p.E_star, b.G_star[e] = p.G_star, b.damping[e] = p.damping;
    b.sqrt_st_over_sn[e] = p.sqrt_st_over_sn, b.friction[e] = p.friction;
  }
  // Contacts 0 .. m-1 of b: force() with a tangential spring (width 3), lane by lane, the bits force() gives.
  static void wall_force_batch(WallBatch& b, int m, double dt) {
    for (int q = 0; q < m; ++q) {
      const Lane c = lane(b.nx[q], b.ny[q], b.nz[q], b.vx[q], b.vy[q], b.vz[q], b.overlap[q], b.r_star[q], b.m_star[q],
                          b.E_star[q], b.G_star[q], b.damping[q], b.sqrt_st_over_sn[q], b.friction[q], dt, b.hx[q],
                          b.hy[q], b.hz[q]);
      b.fx[q] = c.fx, b.fy[q] = c.fy, b.fz[q] = c.fz;
      b.tx[q] = c.ftx, b.ty[q] = c.fty, b.tz[q] = c.ftz;
      b.fn[q] = c.fn;
    }
  }

  // history: the contact's slots (width 0: no tangential spring; else the spring in history[0..3)).
  static Result force(const Params& p, const Geometry& g, double* history, int width) {
    Result r{};
    const double sqrt_Rd = std::sqrt(g.R_star * g.overlap);
    const double Sn = 2.0 * p.E_star * sqrt_Rd;
    const double fn_elastic = (2.0 / 3.0) * Sn * g.overlap;  // = 4/3 E* sqrt(R*) delta^1.5
    const double vn = dot(g.v_rel, g.n);                     // < 0 while approaching
    const double sqrt_sn_m = std::sqrt(Sn * g.m_star);
    const double fn = fn_elastic - p.damping * sqrt_sn_m * vn;  // repulsive > 0
    r.normal_force = std::max(fn, 0.0);
    r.normal_stiffness = Sn;
    r.force_i = g.n * (-fn);
    if (width == 0) return r;

    // Tangential spring: rotate the stored displacement into the current tangent plane (keeping its
    // length), then add this step's tangential slip.
    // One sqrt for the rescale (sqrt(|xi|^2 / |xi_t|^2) instead of |xi| / |xi_t|), none for a new contact.
    Vec3 xi{history[0], history[1], history[2]};
    const double xi_old2 = norm2(xi);
    if (xi_old2 > 0.0) {
      xi -= g.n * dot(xi, g.n);
      const double xi_new2 = norm2(xi);
      if (xi_new2 > 0.0) xi *= std::sqrt(xi_old2 / xi_new2);
    }
    const Vec3 vt = g.v_rel - g.n * vn;
    xi += vt * g.dt;
    const double St = 8.0 * p.G_star * sqrt_Rd;
    Vec3 ft = xi * St + vt * (p.damping * sqrt_sn_m * p.sqrt_st_over_sn);  // on i: drags i along with j
    // Coulomb test on squares: the sqrt is taken only for a slipping contact (most contacts stick).
    const double ft_len2 = norm2(ft);
    const double ft_max = p.friction * r.normal_force;
    if (ft_len2 > ft_max * ft_max) {
      // Slip: the friction force sits on the Coulomb limit and the spring carries all of it.
      const double ft_len = std::sqrt(ft_len2);
      ft = ft_len > 0.0 ? ft * (ft_max / ft_len) : Vec3{};
      xi = St > 0.0 ? ft * (1.0 / St) : Vec3{};
    }
    history[0] = xi.x;
    history[1] = xi.y;
    history[2] = xi.z;
    r.tangential_i = ft;
    r.force_i += ft;
    return r;
  }
};

}  // namespace pastemix::model
