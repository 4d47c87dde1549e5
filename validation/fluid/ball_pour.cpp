// SPDX-License-Identifier: MIT
#include "validation/fluid/ball_pour.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "base/error.h"
#include "base/units.h"
#include "model/fluid/flow_coupling.h"
#include "model/insert/fill.h"
#include "model/scene.h"

namespace pastemix::validation {

using namespace model;          // the engine these harnesses drive
using namespace model::fluid;

namespace {

struct Geometry {
  double cx, cy;       // m, funnel and frame axis
  double z_tube;       // m, bottom of the exit tube (the plate)
  double z_exit;       // m, bottom of the cone = top of the tube
  double z_top;        // m, top of the cone
};

Geometry geometry(const FunnelPour& p) {
  Geometry g;
  g.cx = 0.5 * p.box_x, g.cy = 0.5 * p.box_y;
  g.z_tube = p.paste_depth + p.fall;
  g.z_exit = g.z_tube + p.tube;
  g.z_top = g.z_exit + p.cone_h;
  return g;
}

// The funnel as the scene expands it (model/scene.cpp): cone frustum plus exit tube, so the random
// placement keeps clear of the same surfaces the contacts see.
std::vector<Wall> funnel_walls(const FunnelPour& p, const Geometry& g) {
  Wall cone;
  cone.kind = WallKind::revolution;
  cone.origin = {g.cx, g.cy, 0.0};
  cone.r0 = 0.5 * p.exit_d, cone.z0 = g.z_exit, cone.r1 = 0.5 * p.top_d, cone.z1 = g.z_top;
  Wall tube = cone;
  tube.r0 = tube.r1 = 0.5 * p.exit_d, tube.z0 = g.z_tube, tube.z1 = g.z_exit;
  return {cone, tube};
}
}  // namespace

double rayleigh_time(const FunnelPour& p) {
  const double G = p.youngs_modulus / (2.0 * (1.0 + p.poisson));
  return units::pi * 0.5 * p.ball_d * std::sqrt(p.rho_ball / G) / (0.8766 + 0.163 * p.poisson);
}

std::string ball_pour_scene(const FunnelPour& p, std::uint64_t seed) {
  if (p.balls < 1) throw InputError("ball_pour", 0, "balls", "needs at least one ball");
  const Geometry g = geometry(p);
  const double r = 0.5 * p.ball_d, R_top = 0.5 * p.top_d;
  const double dt = p.dt_rayleigh * rayleigh_time(p);
  std::string s = fmt::format(
      "seed = {seed}\ntime_step = {dt:.9g}\nend_time = {end}\n"
      "[domain]\nmin = [{xl}, {yl}, -0.01]\nmax = [{xh}, {yh}, {zh}]\n"
      "[contact]\nlaw = \"hertz_mindlin\"\nrolling = \"constant_torque\"\n[output]\ninterval = {end}\n"
      "[[material]]\nname = \"steel\"\ndensity = {rho}\nyoungs_modulus = {E:.9g}\npoisson_ratio = {nu}\n"
      "[[interaction]]\nmaterials = \"steel/steel\"\nrestitution = {e}\nfriction = {mu}\nrolling_friction = {mr}\n"
      "[[wall]]\nname = \"frame\"\ntype = \"box\"\nmaterial = \"steel\"\nmin = [0, 0, 0]\nmax = [{bx}, {by}, {bz}]\n"
      "[[wall]]\nname = \"funnel\"\ntype = \"funnel\"\nmaterial = \"steel\"\ncenter = [{cx}, {cy}]\nz_exit = {ze:.9g}\n"
      "exit_diameter = {de}\ntop_diameter = {dtop}\nheight = {h}\ntube_length = {tube}\n"
      "[[wall]]\nname = \"plate\"\ntype = \"disk\"\nmaterial = \"steel\"\ncenter = [{cx}, {cy}, {zt:.9g}]\n"
      "radius = {rp}\nremove_at = {rel}\n"
      "[[fluid]]\nname = \"paste\"\nx = [0, {bx}]\ny = [0, {by}]\nbottom = 0\nsurface = {bz}\ndensity = {rf}\n"
      "rheology = \"bingham\"\nyield_stress = {tau:.9g}\nplastic_viscosity = {eta:.9g}\ncurve = \"{curve}\"\n"
      "solids_fraction = 0.75\n",
      fmt::arg("seed", seed), fmt::arg("dt", dt), fmt::arg("end", p.end_time),
      fmt::arg("xl", std::min(0.0, g.cx - R_top) - 0.01), fmt::arg("yl", std::min(0.0, g.cy - R_top) - 0.01),
      fmt::arg("xh", std::max(p.box_x, g.cx + R_top) + 0.01), fmt::arg("yh", std::max(p.box_y, g.cy + R_top) + 0.01),
      fmt::arg("zh", g.z_top + 0.02), fmt::arg("rho", p.rho_ball), fmt::arg("E", p.youngs_modulus),
      fmt::arg("nu", p.poisson), fmt::arg("e", p.restitution), fmt::arg("mu", p.friction), fmt::arg("mr", p.rolling),
      fmt::arg("bx", p.box_x), fmt::arg("by", p.box_y), fmt::arg("bz", p.paste_depth), fmt::arg("cx", g.cx),
      fmt::arg("cy", g.cy), fmt::arg("ze", g.z_exit), fmt::arg("de", p.exit_d), fmt::arg("dtop", p.top_d),
      fmt::arg("h", p.cone_h), fmt::arg("tube", p.tube), fmt::arg("zt", g.z_tube), fmt::arg("rp", 0.5 * p.exit_d + 0.01),
      fmt::arg("rel", p.release), fmt::arg("rf", p.rho_paste), fmt::arg("tau", p.tau_y), fmt::arg("eta", p.eta_B),
      fmt::arg("curve", p.curve.info().name));
  if (!p.curve.coefficients.empty()) {
    s += "coefficients = [";
    for (std::size_t k = 0; k < p.curve.coefficients.size(); ++k)
      s += fmt::format("{}{:.17g}", k ? ", " : "", p.curve.coefficients[k]);
    s += "]\n";
  }
  if (p.flow) {
    const auto n = pour_flow_cells(p, *p.flow);
    s += fmt::format("dynamics = \"flow\"\ncells = [{}, {}, {}]\ntop = {:.9g}\nkernel_width = {:.17g}\n"
                     "coupling_interval = {}\nregularisation = {:.17g}\n",
                     n[0], n[1], n[2], p.paste_depth + p.flow->air, p.flow->kernel_width, p.flow->coupling_interval,
                     p.flow->regularisation);
    if (p.flow->implicit_stick) s += "implicit_stick = true\n";
  }
  // Seeded random loose placement in the lowest fill_height of the cone (the engine's insertion).
  FillRegion region;
  region.shape = FillRegion::frustum;
  region.cx = g.cx, region.cy = g.cy;
  region.z_min = g.z_exit, region.z_max = g.z_exit + p.fill_height;
  region.r_bottom = 0.5 * p.exit_d;
  region.r_top = 0.5 * p.exit_d + 0.5 * (p.top_d - p.exit_d) * p.fill_height / p.cone_h;
  const std::vector<double> radii(static_cast<std::size_t>(p.balls), r);
  const FillResult fill = fill_region(region, radii, {}, {}, funnel_walls(p, g), seed);
  if (!fill.complete)
    throw InputError("ball_pour", 0, "fill_height",
                     fmt::format("only {} of {} balls fit in the lowest {} m of the funnel", fill.placed, p.balls,
                                 p.fill_height));
  for (const Vec3& c : fill.positions)
    s += fmt::format("[[particle]]\nmaterial = \"steel\"\nradius = {}\nposition = [{:.9g}, {:.9g}, {:.9g}]\n", r, c.x,
                     c.y, c.z);
  return s;
}

std::array<int, 3> pour_flow_cells(const FunnelPour& p, const PourFlow& f) {
  if (!(f.cell > 0.0) || !(f.air > 0.0) || !(f.rest_speed > 0.0) || !(f.rest_time > 0.0))
    throw InputError("ball_pour", 0, "flow", "cell, air, rest_speed and rest_time must be positive");
  const auto whole = [&](double side) { return std::max(1, static_cast<int>(std::lround(side / f.cell))); };
  return {whole(p.box_x), whole(p.box_y), whole(p.paste_depth + f.air)};
}

namespace {
// The ball's state for the tally: in the paste (its bottom below the paste surface) and at rest.
struct BallState {
  const World& w;
  const FunnelPour& p;
  double surface = 0.0;  // m, with flow: the area-mean surface (the header's rule)
  bool inside(std::size_t a) const {
    if (!p.flow) return w.fluid()->inside(static_cast<long>(a));
    return w.particles().x[a].z - 0.5 * p.ball_d < surface;
  }
  bool resting(std::size_t a) const {
    const double v2 = norm2(w.particles().v[a]);
    return p.flow ? v2 < p.flow->rest_speed * p.flow->rest_speed : v2 == 0.0;
  }
};

double flow_surface(const World& w, const FunnelPour& p) {
  const auto& pt = w.particles();
  const double r = 0.5 * p.ball_d, area = p.box_x * p.box_y;
  double below = 0.0;  // m3 of the balls below the rim (whole balls: a ball straddling the rim counts whole)
  for (std::size_t a = 0; a < pt.size(); ++a)
    if (pt.x[a].z - r < p.paste_depth) below += 4.0 / 3.0 * units::pi * r * r * r;
  return (w.flow()->paste_volume() + below) / area;
}
}  // namespace

BallPourResult ball_pour(const FunnelPour& p, std::uint64_t seed) {
  const Scene scene = parse_scene(ball_pour_scene(p, seed), fmt::format("ball_pour_seed{}.toml", seed));
  World w = make_world(scene);
  const Geometry g = geometry(p);
  const double r = 0.5 * p.ball_d;
  BallPourResult b;
  b.seed = seed;
  b.dt = scene.config.dt;
  const long max_steps = std::lround(p.end_time / b.dt);
  const auto& pt = w.particles();
  std::vector<char> out(pt.size(), 0);
  std::size_t n_out = 0;
  // At rest: one check (v == 0 holds by itself: the at-rest paste's stick), or rest_time of them with flow.
  const long checks_to_rest = p.flow ? std::max(1L, std::lround(p.flow->rest_time / (1000.0 * b.dt))) : 1;
  long rest_checks = 0;
  for (long s = 1; s <= max_steps; ++s) {
    w.step();
    b.steps = s;
    if (s % 50 == 0) {  // exit passages: a ball at 2 m/s moves 0.35 mm in 50 steps of 3.5 us
      // By id: the engine may reorder its particles at rebuilds ([neighbor] sort_every).
      for (std::size_t a = 0; a < pt.size(); ++a)
        if (const auto id = static_cast<std::size_t>(pt.id[a]); !out[id] && pt.x[a].z + r < g.z_tube) {
          out[id] = 1;
          if (n_out++ == 0) b.first_out = w.time();
          b.last_out = w.time();
        }
    }
    if (s % 1000 == 0) {
      w.check();
      if (n_out < pt.size()) continue;
      BallState st{w, p, p.flow ? flow_surface(w, p) : 0.0};
      bool all_rest = true;
      for (std::size_t a = 0; a < pt.size() && all_rest; ++a) all_rest = st.resting(a) && st.inside(a);
      rest_checks = all_rest ? rest_checks + 1 : 0;
      if (rest_checks >= checks_to_rest) break;
    }
  }
  w.check();
  b.t_end = w.time();
  b.z_min = 1e300, b.z_max = -1e300;
  const BallState st{w, p, p.flow ? flow_surface(w, p) : 0.0};
  for (std::size_t a = 0; a < pt.size(); ++a) {
    b.x.push_back(pt.x[a].x);
    b.y.push_back(pt.x[a].y);
    b.z.push_back(pt.x[a].z);
    b.id.push_back(pt.id[a]);
    const bool inside = st.inside(a);
    b.in_paste += inside;
    const bool floor = pt.x[a].z - r < 1e-4;
    b.on_floor += floor;
    b.at_rest += inside && !floor && st.resting(a);
    if (pt.x[a].z + r > g.z_tube) {
      ++b.in_funnel;  // still in (or partly in) the funnel
      continue;
    }
    b.max_speed = std::max(b.max_speed, std::sqrt(norm2(pt.v[a])));
    b.z_min = std::min(b.z_min, pt.x[a].z);
    b.z_max = std::max(b.z_max, pt.x[a].z);
  }
  std::vector<std::int64_t> ids = b.id;
  std::sort(ids.begin(), ids.end());
  b.ids_ok = static_cast<int>(ids.size()) == p.balls;
  for (std::size_t k = 0; k < ids.size() && b.ids_ok; ++k) b.ids_ok = ids[k] == static_cast<std::int64_t>(k);
  b.surface = p.flow ? st.surface : w.fluid()->surface_z(0);
  if (p.flow) {
    const auto& f = *w.flow();
    b.flow_cycles = f.cycles(), b.flow_steps = f.flow_steps();
    b.pressure_iterations = f.pressure_iterations(), b.viscous_iterations = f.viscous_iterations();
    b.flow_seconds = f.solver_seconds();
  }
  return b;
}

}  // namespace pastemix::validation
