// SPDX-License-Identifier: MIT
#include "model/fluid/validations.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "base/error.h"
#include "base/rng.h"
#include "model/scene.h"

namespace pastemix::model::fluid {

namespace {
constexpr double kG = 9.81;  // m/s2, the scene default gravity
constexpr double kPiV = 3.14159265358979323846;
}  // namespace

WaterSettling water_settling(double dt) {
  SphereRun r;
  r.d = 1e-4, r.rho_p = 2700, r.rho_f = 1000, r.eta = 1e-3;
  r.curve = {drag::CurveId::stokes, {}};
  r.depth = 0.05, r.box_half = 0.01, r.dt = dt, r.floor = false;
  r.drop = -1e-3;  // fully submerged from the start (the analytic case)
  WaterSettling w;
  w.dt = dt;
  w.v_terminal = (r.rho_p - r.rho_f) * kG * r.d * r.d / (18.0 * r.eta);
  w.tau = r.rho_p * r.d * r.d / (18.0 * r.eta);
  const double end = std::max(10.0 * w.tau, 2.0 * dt);
  const SphereTrace tr = run_single_sphere(r, end);
  for (std::size_t k = 1; k < tr.t.size(); ++k) {
    const double va = w.v_terminal * -std::expm1(-tr.t[k] / w.tau);
    w.max_rel_error = std::max(w.max_rel_error, std::abs(-tr.vz[k] - va) / va);
  }
  w.steps = static_cast<long>(tr.t.size()) - 1;
  return w;
}

ColumnSettling column_settling(SphereRun r, double column) {
  r.depth = column + 2.0 * r.d + 0.01;
  r.drop = -1e-3;
  r.floor = false;  // the run ends a radius + 1 mm above the bottom (a floor contact would need a small dt)
  // The end time only bounds a sphere slower than 0.3 mm/s; every run ends at the bottom or at rest.
  const SphereTrace tr = run_single_sphere(r, 1e4, 200);
  ColumnSettling c;
  c.time = tr.t.back();
  c.trapped = tr.stopped && !tr.reached_bottom;
  c.v_final = -tr.vz.back();
  // Speed 10 % of the travel earlier.
  const double z_end = tr.z.back(), z_start = tr.z.front();
  const double z_ref = z_end + 0.1 * (z_start - z_end);
  auto it = std::find_if(tr.z.begin(), tr.z.end(), [&](double z) { return z <= z_ref; });
  const double v_ref = -tr.vz[static_cast<std::size_t>(it - tr.z.begin())];
  c.v_change = c.v_final != 0.0 ? std::abs(c.v_final - v_ref) / c.v_final : 0.0;
  return c;
}

double suspension_threshold(const drag::DragCurve& curve) {
  // k = lim Cd Re' as Re' -> 0, taken at Re' = 1e-30: exact for the fixed curves; for a fitted a Re'^(1-b) the
  // leftover is a 1e-30^(1-b) (1e-6 a for the lab fit's b = 0.80; large only as b -> 1).
  // For a curve that depends on the yield number this is its Y = 0 limit (the validations use fixed curves).
  const double k = curve.cd(1e-30, 0.0) * 1e-30;
  return (kPiV / 6.0) / (kPiV * kPiV / 4.0 + k * kPiV / 8.0);
}

SuspensionResult suspension(SphereRun r, double end_time) {
  r.drop = -0.01;
  r.floor = true;
  const SphereTrace tr = run_single_sphere(r, end_time);
  SuspensionResult s;
  s.threshold_ratio = r.tau_y / (kG * r.d * (r.rho_p - r.rho_f));
  s.displacement = std::abs(tr.z.back() - tr.z.front());
  s.speed_end = std::abs(tr.vz.back());
  return s;
}

BallDrop steel_ball_drop(const SteelBallPaste& p, double d, double height, double eta_B) {
  SphereRun r;
  r.d = d, r.rho_p = p.rho_ball, r.rho_f = p.rho_paste, r.tau_y = p.tau_y, r.eta = eta_B, r.curve = p.curve;
  r.depth = p.mould_height;
  // The mould is round (75 mm); the fluid box has the same area, so the surface rises as in the mould.
  r.box_half = 0.5 * std::sqrt(kPiV / 4.0) * p.mould_diameter;
  r.drop = height, r.dt = p.dt, r.floor = true;
  const double t_fall = std::sqrt(2.0 * std::max(height, 0.0) / kG);
  const SphereTrace tr = run_single_sphere(r, t_fall + 5.0, 50);
  BallDrop b;
  b.reached_bottom = tr.reached_bottom;
  if (!tr.stopped && !tr.reached_bottom)
    throw RuntimeFailure(fmt::format("steel ball d = {} m, drop {} m, eta {} Pa.s: not at rest after {} s", d, height,
                                     eta_B, tr.t.back()));
  b.distance = settling_distance(r, tr);
  b.time_to_rest = tr.t.back() - 50 * p.dt;
  return b;
}

Calibration calibrate_viscosity(const SteelBallPaste& p, double d, double height, double distance, double lo,
                                double hi, double rel_tol) {
  Calibration c;
  auto dist = [&](double eta) {
    ++c.runs;
    return steel_ball_drop(p, d, height, eta).distance;
  };
  const double d_lo = dist(lo), d_hi = dist(hi);  // d_lo > d_hi: more viscous, shallower
  if (!(distance <= d_lo && distance >= d_hi))
    throw RuntimeFailure(fmt::format("settling distance {:.4g} m is outside [{:.4g}, {:.4g}] m, the distances for "
                                     "eta_B in [{}, {}] Pa.s",
                                     distance, d_hi, d_lo, lo, hi));
  while (hi / lo > 1.0 + rel_tol) {
    const double mid = std::sqrt(lo * hi);
    if (dist(mid) > distance) lo = mid;
    else hi = mid;
  }
  c.eta = std::sqrt(lo * hi);
  c.distance = dist(c.eta);
  return c;
}

}  // namespace pastemix::model::fluid

namespace pastemix::model::fluid {

std::string ball_pour_scene(const SteelBallPaste& p, double eta_B, std::uint64_t seed, double fall, double end_time,
                            int balls, double E) {
  const double r = 0.0063, lx = 0.20, ly = 0.165, depth = 0.15;
  // Rayleigh time of the ball, 20 % of it.
  const double G = E / (2.0 * 1.3);
  const double dt = 0.2 * kPiV * r * std::sqrt(p.rho_ball / G) / (0.8766 + 0.163 * 0.3);
  std::string s = fmt::format(
      "seed = {}\ntime_step = {:.6g}\nend_time = {}\n[domain]\nmin = [-0.01, -0.01, -0.01]\nmax = [{}, {}, 0.8]\n"
      "[contact]\nlaw = \"hertz_mindlin\"\n[output]\ninterval = {}\n"
      "[[material]]\nname = \"steel\"\ndensity = {}\nyoungs_modulus = {:.6g}\npoisson_ratio = 0.3\n"
      "[[material]]\nname = \"frame\"\ndensity = 1200\nyoungs_modulus = {:.6g}\npoisson_ratio = 0.3\n"
      "[[interaction]]\nmaterials = \"steel/steel\"\nrestitution = 0.6\nfriction = 0.3\n"
      "[[interaction]]\nmaterials = \"steel/frame\"\nrestitution = 0.6\nfriction = 0.3\n"
      "[[wall]]\nname = \"frame\"\ntype = \"box\"\nmaterial = \"frame\"\nmin = [0, 0, 0]\nmax = [{}, {}, 0.8]\n"
      "[[fluid]]\nname = \"paste\"\nx = [0, {}]\ny = [0, {}]\nbottom = 0\nsurface = {}\ndensity = {}\n"
      "rheology = \"bingham\"\nyield_stress = {}\nplastic_viscosity = {}\ncurve = \"{}\"\nsolids_fraction = 0.75\n",
      seed, dt, end_time, lx + 0.01, ly + 0.01, end_time, p.rho_ball, E, E, lx, ly, lx, ly, depth, p.rho_paste,
      p.tau_y, eta_B, p.curve.info().name);
  if (!p.curve.coefficients.empty()) {
    s += "coefficients = [";
    for (std::size_t k = 0; k < p.curve.coefficients.size(); ++k)
      s += fmt::format("{}{:.17g}", k ? ", " : "", p.curve.coefficients[k]);
    s += "]\n";
  }
  // Seeded random non-overlapping positions in the start cylinder (rejection sampling, layer by layer).
  Rng rng(seed);
  std::vector<Vec3> pos;
  const double rc = 0.035 - r, z0 = depth + fall + r;
  double z_top = z0;
  while (static_cast<int>(pos.size()) < balls) {
    for (int tries = 0; tries < 2000 && static_cast<int>(pos.size()) < balls; ++tries) {
      const double a = 2.0 * kPiV * rng.uniform(), rr = rc * std::sqrt(rng.uniform());
      const Vec3 c{0.5 * lx + rr * std::cos(a), 0.5 * ly + rr * std::sin(a), z_top + 0.4 * r * rng.uniform()};
      bool ok = true;
      for (const Vec3& q : pos) ok = ok && norm(q - c) > 2.0 * r + 2e-4;
      if (ok) pos.push_back(c);
    }
    z_top += 2.0 * r + 1e-3;
  }
  for (const Vec3& c : pos)
    s += fmt::format("[[particle]]\nmaterial = \"steel\"\nradius = {}\nposition = [{:.9g}, {:.9g}, {:.9g}]\n", r, c.x,
                     c.y, c.z);
  return s;
}

BallPour ball_pour(const SteelBallPaste& p, double eta_B, std::uint64_t seed, double fall, double end_time, int balls,
                   double E) {
  const Scene scene = parse_scene(ball_pour_scene(p, eta_B, seed, fall, end_time, balls, E), "ball_pour.toml");
  World w = make_world(scene);
  const long steps = std::lround(end_time / scene.config.dt);
  for (long s = 1; s <= steps; ++s) {
    w.step();
    if (s % 100 == 0) w.check();
  }
  w.check();
  BallPour b;
  const auto& pt = w.particles();
  b.z_min = 1e300, b.z_max = -1e300;
  for (std::size_t a = 0; a < pt.size(); ++a) {
    b.x.push_back(pt.x[a].x);
    b.y.push_back(pt.x[a].y);
    b.z.push_back(pt.x[a].z);
    b.z_min = std::min(b.z_min, pt.x[a].z);
    b.z_max = std::max(b.z_max, pt.x[a].z);
    b.at_rest += norm2(pt.v[a]) == 0.0;
  }
  b.surface = w.fluid()->surface_z(0);
  return b;
}

}  // namespace pastemix::model::fluid
