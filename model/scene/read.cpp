// SPDX-License-Identifier: MIT
// The scene loader: read_scene calls one reader per concept (scene/read.h), then the top-level checks.
// This file also holds the small concepts: the run settings, [domain], [physics], [neighbor], [output],
// [stop], and the checks on the whole (blow-up limit, time step against the Rayleigh time).
#include "model/scene/read.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "base/error.h"
#include "base/units.h"
#include "model/fluid/fluid_scene.h"
#include "model/scene_doc.h"

namespace pastemix::model {

Vec3 vec(const Params& p, std::string_view key) {
  const auto v = p.numbers(key, 3);
  return {v[0], v[1], v[2]};
}

Vec3 vec_or(const Params& p, std::string_view key, Vec3 fallback) {
  const auto v = p.optional_numbers(key, 3);
  return v ? Vec3{(*v)[0], (*v)[1], (*v)[2]} : fallback;
}

int material_index(const Params& p, std::string_view key, const std::vector<Material>& mats) {
  const std::string name = p.string(key);
  for (std::size_t k = 0; k < mats.size(); ++k)
    if (mats[k].name == name) return static_cast<int>(k);
  std::vector<std::string> names;
  for (const auto& m : mats) names.push_back(m.name);
  p.fail(key, fmt::format("material '{}' is not defined (defined: {})", name, fmt::join(names, ", ")));
}

bool inside(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
}

bool read_domain(const Params& root, Scene& s) {
  s.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1));
  s.config.dt = root.number("time_step", Range::positive);
  s.end_time = root.number("end_time", Range::positive);
  if (s.end_time < s.config.dt)
    root.fail("end_time", fmt::format("end_time {:g} s is shorter than one time step ({:g} s): the run would make no "
                                      "step",
                                      s.end_time, s.config.dt));
  const Params dom = root.table("domain");
  s.config.domain_min = vec(dom, "min");
  s.config.domain_max = vec(dom, "max");
  const Vec3 &a = s.config.domain_min, &b = s.config.domain_max;
  if (!(b.x > a.x && b.y > a.y && b.z > a.z)) dom.fail("max", "max must exceed min on every axis");
  if (dom.choice_or("on_exit", {"stop", "remove"}, "stop") == "remove") {
    s.config.on_exit = ExitRule::remove;
    s.config.max_escaped_fraction = dom.number_or("max_escaped_fraction", 0.05, Range::fraction);
  } else if (dom.has("max_escaped_fraction")) {
    dom.fail("max_escaped_fraction", "only with on_exit = \"remove\" (a particle leaving the domain stops the run)");
  }
  bool rotation_switch = true;
  if (auto ph = root.optional_table("physics")) {
    s.config.gravity = vec_or(*ph, "gravity", s.config.gravity);
    rotation_switch = ph->boolean_or("rotation", true);
  }
  return rotation_switch;
}

// [neighbor] sort_every when the scene does not say (WorldConfig::sort_every). Measured (bench/README.md,
// 2026-12-02): the 207k-sphere bench pour, 2000 steps, 1 thread, 53.3 s unsorted against 39.2 s sorting every
// 8th rebuild (pair pass 20.6 -> 12.4 s, rebuilds 18.5 -> 14.1 s); a sort costs ~1/6 of a rebuild, and the
// order decays slowly (a particle moves < skin/2 between rebuilds), so every 8th rebuild.
constexpr long kDefaultSortEvery = 8;

void read_output(const Params& root, double r_min, Scene& s) {
  // Neighbour skin: default the smallest radius (LIGGGHTS scenes usually use ~r_min).
  s.config.skin = r_min;
  s.config.sort_every = kDefaultSortEvery;
  if (auto nb = root.optional_table("neighbor")) {
    s.config.skin = nb->number_or("skin", r_min, Range::positive);
    const long every = nb->integer_or("sort_every", kDefaultSortEvery);
    if (every < 0 || every > 1000000) nb->fail("sort_every", fmt::format("must be 0 (no sort) .. 1000000 rebuilds, got {}", every));
    s.config.sort_every = every;
  }
  s.output_interval = s.end_time / 20.0;
  s.energy_interval = 0.0;
  if (auto out = root.optional_table("output")) {
    s.output_interval = out->number_or("interval", s.output_interval, Range::positive);
    s.energy_interval = out->number_or("energy_interval", 0.0, Range::positive);
    s.checkpoint_interval = out->number_or("checkpoint_interval", 0.0, Range::positive);
  }
  if (s.energy_interval == 0.0) s.energy_interval = s.output_interval;
  s.stop = parse_stop_rule(root);
}

// The particles cannot gain more kinetic energy than the initial one plus the largest fall inside the
// domain; twice that is certainly a numerical blow-up.
void set_kinetic_limit(Scene& s) {
  double ke0 = 0.0, m = 0.0;
  for (std::size_t a = 0; a < s.particles.size(); ++a) {
    ke0 += 0.5 * s.particles.mass[a] * norm2(s.particles.v[a]);
    m += s.particles.mass[a];
  }
  const Vec3 d = s.config.domain_max - s.config.domain_min;
  const double fall =
      std::abs(s.config.gravity.x) * d.x + std::abs(s.config.gravity.y) * d.y + std::abs(s.config.gravity.z) * d.z;
  s.config.kinetic_limit = 2.0 * (ke0 + m * fall) + 1e-12;
}

namespace {

// Rayleigh time of sphere a (s): pi r sqrt(rho/G) / (0.8766 + 0.163 nu) (../shared/DESIGN.md section 3).
double rayleigh_time(const Scene& s, std::size_t a) {
  const Material& m = s.materials[static_cast<std::size_t>(s.particles.material[a])];
  return units::pi * s.particles.radius[a] * std::sqrt(m.density / m.shear_modulus()) /
         (0.8766 + 0.163 * m.poisson_ratio);
}

// The habit is 20 % of T_R; time-step studies of this project chose up to ~40 % (mixing_fast). Above half of
// it a contact lasts a few steps only: legal (a particle alone in a fluid has no contact), but worth a word.
constexpr double kRayleighWarnShare = 0.5;

}  // namespace

double smallest_rayleigh_time(const Scene& s) {
  double t_r = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < s.particles.size(); ++a) t_r = std::min(t_r, rayleigh_time(s, a));
  return t_r;
}

void warn_time_step(Scene& s) {
  if (s.particles.size() == 0) return;
  const double t_r = smallest_rayleigh_time(s);
  if (s.config.dt > kRayleighWarnShare * t_r)
    s.warnings.push_back(fmt::format("{}: time_step {:g} s is {:.0f} % of the Rayleigh time of the smallest sphere "
                                     "({:.3g} s; the habit is 20 %): contacts may be unresolved; check with a "
                                     "time-step study (pastemix sweep --vary dt)",
                                     s.path, s.config.dt, 100 * s.config.dt / t_r, t_r));
}

Scene read_scene(const Params& root, std::string text) {
  Scene s;
  s.path = root.path();
  s.text = std::move(text);
  const bool rotation_switch = read_domain(root, s);
  s.fluid = fluid::read_fluid_regions(root, s.path, s.config.domain_min, s.config.domain_max);  // fluid hook
  // A flow region (the only region then, fluid_scene.cpp) is the flow pass's; the at-rest field never sees it.
  s.plan.flow = !s.fluid.empty() && s.fluid.front().flow;
  s.plan.fluid = !s.fluid.empty() && !s.plan.flow;
  const Params contact = root.table("contact");
  s.plan.law = contact.choice("law", ContactLaws::names());
  s.plan.rolling = contact.choice_or("rolling", RollingLaws::names(), "none");
  const std::vector<int> material_line = read_materials(root, s.materials);
  read_interactions(root, s);
  read_walls(root, s);
  const ParticleSources src = read_particle_sources(root, s);
  require_interactions(s, src.materials, material_line);
  plan_laws(contact, rotation_switch, src.materials, s);
  const double r_explicit = read_particles(src, s);  // first: the factories fill around these spheres
  const double r_min = std::min(r_explicit, read_factories(src, s));
  read_output(root, r_min, s);
  set_kinetic_limit(s);
  root.finish();
  warn_time_step(s);
  return s;
}

Scene parse_scene(std::string_view text, const std::string& display_path) {
  return SceneDoc::parse(std::string(text), display_path).load();
}

Scene load_scene(const std::filesystem::path& path) { return SceneDoc::parse_file(path).load(); }

World make_world(const Scene& s) {
  World w(s.config, s.materials, s.laws, s.rolling, s.particles, s.walls, s.plan.history_width);
  if (s.plan.fluid) w.set_fluid(std::make_shared<fluid::FluidField>(s.fluid));  // fluid hook
  if (s.plan.flow) w.set_flow(std::make_shared<fluid::FlowCoupling>(s.fluid.front(), s.config.dt, s.config.gravity));
  return w;
}

}  // namespace pastemix::model
