// SPDX-License-Identifier: MIT
#include "model/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "base/error.h"
#include "base/h5.h"
#include "base/params.h"
#include "base/psd.h"
#include "model/fluid/fluid_scene.h"
#include "model/insert/fill.h"
#include "model/neighbor.h"

namespace pastemix::model {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

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

Wall base_wall(const Params& w, const std::string& name, int material) {
  Wall b;
  b.name = name;
  b.material = material;
  b.velocity = vec_or(w, "velocity", {});
  b.move_start = w.number_or("move_start", 0.0, Range::non_negative);
  b.move_end = w.number_or("move_end", inf, Range::non_negative);
  b.remove_at = w.number_or("remove_at", inf, Range::non_negative);
  return b;
}

Wall revolution(Wall b, double cx, double cy, double r0, double z0, double r1, double z1) {
  b.kind = WallKind::revolution;
  b.origin = {cx, cy, 0.0};
  b.r0 = r0;
  b.z0 = z0;
  b.r1 = r1;
  b.z1 = z1;
  return b;
}

// Expands one [[wall]] into primitives.
void read_wall(const Params& w, const std::vector<Material>& mats, std::vector<Wall>& out) {
  const std::string name = w.string("name");
  const std::string type = w.choice("type", {"plane", "box", "cylinder", "cone", "disk", "funnel"});
  const Wall b = base_wall(w, name, material_index(w, "material", mats));
  if (type == "plane") {
    Wall p = b;
    p.kind = WallKind::plane;
    p.origin = vec(w, "point");
    const Vec3 n = vec(w, "normal");
    if (norm(n) == 0.0) w.fail("normal", "the normal must not be zero");
    p.normal = n * (1.0 / norm(n));
    out.push_back(p);
  } else if (type == "box") {
    const Vec3 lo = vec(w, "min"), hi = vec(w, "max");
    if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z)) w.fail("max", "max must exceed min on every axis");
    const Vec3 c{0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), 0.5 * (lo.z + hi.z)};
    const Vec3 h{0.5 * (hi.x - lo.x), 0.5 * (hi.y - lo.y), 0.5 * (hi.z - lo.z)};
    auto rect = [&](Vec3 o, Vec3 u, Vec3 v) {
      Wall r = b;
      r.kind = WallKind::rectangle;
      r.origin = o;
      r.u = u;
      r.v = v;
      r.finish();
      out.push_back(r);
    };
    rect({c.x, c.y, lo.z}, {h.x, 0, 0}, {0, h.y, 0});  // floor
    rect({lo.x, c.y, c.z}, {0, h.y, 0}, {0, 0, h.z});
    rect({hi.x, c.y, c.z}, {0, h.y, 0}, {0, 0, h.z});
    rect({c.x, lo.y, c.z}, {h.x, 0, 0}, {0, 0, h.z});
    rect({c.x, hi.y, c.z}, {h.x, 0, 0}, {0, 0, h.z});
  } else if (type == "cylinder") {
    const auto c = w.numbers("center", 2);
    const double r = w.number("radius", Range::positive);
    const double z0 = w.number("z_min"), z1 = w.number("z_max");
    if (!(z1 > z0)) w.fail("z_max", "z_max must exceed z_min");
    out.push_back(revolution(b, c[0], c[1], r, z0, r, z1));
  } else if (type == "cone") {
    const auto c = w.numbers("center", 2);
    const double z0 = w.number("z0"), r0 = w.number("r0", Range::non_negative);
    const double z1 = w.number("z1"), r1 = w.number("r1", Range::non_negative);
    if (z0 == z1 && r0 == r1) w.fail("z1", "degenerate cone (a single circle)");
    out.push_back(revolution(b, c[0], c[1], r0, z0, r1, z1));
  } else if (type == "disk") {
    const Vec3 c = vec(w, "center");
    const double r = w.number("radius", Range::positive);
    Wall d = revolution(b, c.x, c.y, 0.0, 0.0, r, 0.0);
    d.origin.z = c.z;
    out.push_back(d);
  } else {  // funnel: frustum from the exit up, plus the exit tube below it
    const auto c = w.numbers("center", 2);
    const double ze = w.number("z_exit");
    const double re = 0.5 * w.number("exit_diameter", Range::positive);
    const double rt = 0.5 * w.number("top_diameter", Range::positive);
    const double h = w.number("height", Range::positive);
    const double tube = w.number_or("tube_length", 0.0, Range::non_negative);
    if (rt <= re) w.fail("top_diameter", "the top diameter must exceed the exit diameter");
    out.push_back(revolution(b, c[0], c[1], re, ze, rt, ze + h));
    if (tube > 0.0) out.push_back(revolution(b, c[0], c[1], re, ze - tube, re, ze));
  }
}

// [initial_state]: file (relative to the scene), snapshot (index, -1 = last). The snapshot's materials are
// matched by name (the output stores /materials).
std::filesystem::path initial_file(const Params& t, const std::string& scene_path) {
  std::filesystem::path f = t.string("file");
  if (f.is_relative()) f = std::filesystem::path(scene_path).parent_path() / f;
  if (!std::filesystem::exists(f)) t.fail("file", fmt::format("no such file: {}", f.string()));
  return f;
}

std::string initial_group(const Params& t, const H5Reader& h5) {
  const auto times = h5.read_doubles("/snapshots/time");
  const long n = static_cast<long>(times.size());
  long k = t.integer_or("snapshot", -1);
  if (k < 0) k += n;
  if (k < 0 || k >= n) t.fail("snapshot", fmt::format("the file has {} snapshots", n));
  return fmt::format("/snapshots/{:06d}", k);
}

std::vector<int> initial_state_materials(const Params& t, const std::string& scene_path,
                                         const std::vector<Material>& mats) {
  H5Reader h5(initial_file(t, scene_path));
  if (!h5.exists("/materials")) t.fail("file", "the file has no /materials (not a pastemix run output?)");
  std::vector<int> map;
  for (const std::string& name : h5.read_strings("/materials")) {
    int idx = -1;
    for (std::size_t k = 0; k < mats.size(); ++k)
      if (mats[k].name == name) idx = static_cast<int>(k);
    map.push_back(idx);
  }
  const auto g = initial_group(t, h5);
  std::set<int> used;
  for (auto m : h5.read_ints(g + "/material")) {
    if (m < 0 || m >= static_cast<long>(map.size()) || map[static_cast<std::size_t>(m)] < 0)
      t.fail("file", "the snapshot uses a material this scene does not define");
    used.insert(map[static_cast<std::size_t>(m)]);
  }
  t.integer_or("snapshot", -1);
  return {used.begin(), used.end()};
}

// A snapshot of an earlier run has spheres resting on its walls with contact overlaps of ~1e-3 r; a cut
// deeper than this share of the radius is a wall the snapshot never had.
constexpr double kWallCutTolerance = 0.02;

bool inside(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
}

void check_inside_domain(const Params& t, std::string_view key, const Vec3& p, const WorldConfig& c,
                         const std::string& what) {
  if (!inside(p, c.domain_min, c.domain_max))
    t.fail(key, fmt::format("{} at ({:g}, {:g}, {:g}) m is outside the [domain] box ({:g}, {:g}, {:g}) to ({:g}, {:g}, "
                            "{:g}) m",
                            what, p.x, p.y, p.z, c.domain_min.x, c.domain_min.y, c.domain_min.z, c.domain_max.x,
                            c.domain_max.y, c.domain_max.z));
}

// Rayleigh time of sphere a: pi r sqrt(rho/G) / (0.8766 + 0.163 nu) (DESIGN.md, time step).
double rayleigh_time(const Scene& s, std::size_t a) {
  const Material& m = s.materials[static_cast<std::size_t>(s.particles.material[a])];
  return 3.14159265358979323846 * s.particles.radius[a] * std::sqrt(m.density / m.shear_modulus()) /
         (0.8766 + 0.163 * m.poisson_ratio);
}

// The habit is 20 % of T_R; time-step studies of this project chose up to ~40 % (mixing_fast). Above half of
// it a contact lasts a few steps only: legal (a particle alone in a fluid has no contact), but worth a word.
constexpr double kRayleighWarnShare = 0.5;

void warn_time_step(Scene& s) {
  if (s.particles.size() == 0) return;
  double t_r = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < s.particles.size(); ++a) t_r = std::min(t_r, rayleigh_time(s, a));
  if (s.config.dt > kRayleighWarnShare * t_r)
    s.warnings.push_back(fmt::format("{}: time_step {:g} s is {:.0f} % of the Rayleigh time of the smallest sphere "
                                     "({:.3g} s; the habit is 20 %): contacts may be unresolved; check with a "
                                     "time-step study (pastemix sweep --vary dt)",
                                     s.path, s.config.dt, 100 * s.config.dt / t_r, t_r));
}

void read_initial_state(const Params& t, const std::string& scene_path, Scene& s) {
  H5Reader h5(initial_file(t, scene_path));
  std::vector<int> map;
  for (const std::string& name : h5.read_strings("/materials"))
    for (std::size_t k = 0; k < s.materials.size(); ++k)
      if (s.materials[k].name == name) map.push_back(static_cast<int>(k));
  const auto g = initial_group(t, h5);
  const auto x = h5.read_doubles(g + "/position"), v = h5.read_doubles(g + "/velocity");
  const auto r = h5.read_doubles(g + "/radius");
  const auto m = h5.read_ints(g + "/material");
  const bool has_w = h5.exists(g + "/angular_velocity");
  const auto w = has_w ? h5.read_doubles(g + "/angular_velocity") : std::vector<double>{};
  for (std::size_t a = 0; a < r.size(); ++a) {
    const int mat = map[static_cast<std::size_t>(m[a])];
    const Vec3 om = has_w && s.plan.rotation ? Vec3{w[3 * a], w[3 * a + 1], w[3 * a + 2]} : Vec3{};
    const Vec3 p{x[3 * a], x[3 * a + 1], x[3 * a + 2]};
    check_inside_domain(t, "file", p, s.config, fmt::format("sphere {} of the snapshot", a));
    // A sphere cut by a wall of this scene would be pushed out at an arbitrary speed on the first step.
    for (const Wall& wall : s.walls) {
      Vec3 n;
      const double gap = wall_distance(wall, Vec3{}, p, &n);
      if (gap < r[a] * (1.0 - kWallCutTolerance))
        t.fail("file", fmt::format("sphere {} of the snapshot (radius {:g} m) is cut by wall '{}' ({:.3g} m deep) "
                                   "at t = 0",
                                   a, r[a], wall.name, r[a] - gap));
    }
    s.particles.add(mat, r[a], s.materials[static_cast<std::size_t>(mat)].density, p,
                    {v[3 * a], v[3 * a + 1], v[3 * a + 2]}, om);
  }
}

// Whether a wall surface enters `region` deeper than `margin` (m): samples the surface on a 96 x 96 grid;
// a plane crosses when the region's bounding-box corners lie on both sides of it by more than margin.
bool wall_crosses(const Wall& w, const FillRegion& region, double margin) {
  constexpr int N = 96;
  switch (w.kind) {
    case WallKind::plane: {
      Vec3 lo, hi, n;
      region.bounds(&lo, &hi);
      double dmin = inf, dmax = -inf;
      for (int c = 0; c < 8; ++c) {
        const Vec3 corner{c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z};
        const double d = wall_distance(w, Vec3{}, corner, &n);
        dmin = std::min(dmin, d);
        dmax = std::max(dmax, d);
      }
      return dmin < -margin && dmax > margin;
    }
    case WallKind::rectangle:
      for (int a = 0; a <= N; ++a)
        for (int b = 0; b <= N; ++b) {
          const Vec3 pt = w.origin + w.u * (2.0 * a / N - 1.0) + w.v * (2.0 * b / N - 1.0);
          if (region.contains(pt, margin)) return true;
        }
      return false;
    case WallKind::revolution:
      for (int a = 0; a <= N; ++a)
        for (int b = 0; b < N; ++b) {
          const double t = static_cast<double>(a) / N, phi = 2.0 * M_PI * b / N;
          const double r = w.r0 + t * (w.r1 - w.r0), z = w.z0 + t * (w.z1 - w.z0);
          const Vec3 pt{w.origin.x + r * std::cos(phi), w.origin.y + r * std::sin(phi), w.origin.z + z};
          if (region.contains(pt, margin)) return true;
        }
      return false;
  }
  return false;
}

std::vector<double> diameters_from(const Params& f, double density, std::uint64_t seed) {
  Psd psd;
  for (const Params& i : f.tables("psd"))
    psd.intervals.push_back({i.number("d_min", Range::positive), i.number("d_max", Range::positive),
                             i.number("fraction", Range::fraction)});
  if (psd.intervals.empty()) f.fail("psd", "a factory needs at least one [[factory.psd]] interval");
  try {
    psd.check();
  } catch (const std::invalid_argument& e) {
    f.fail("psd", e.what());
  }
  return generate_diameters(psd, f.number("mass", Range::positive), density, seed);
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& display_path) {
  const Params root = Params::parse(text, display_path);
  Scene s;
  s.path = display_path;
  s.text = std::string(text);
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
  {
    const Vec3 &a = s.config.domain_min, &b = s.config.domain_max;
    if (!(b.x > a.x && b.y > a.y && b.z > a.z)) dom.fail("max", "max must exceed min on every axis");
  }
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
  s.fluid = fluid::read_fluid_regions(root, display_path, s.config.domain_min, s.config.domain_max);  // fluid hook
  s.plan.fluid = !s.fluid.empty();

  const Params contact = root.table("contact");
  s.plan.law = contact.choice("law", ContactLaws::names());
  s.plan.rolling = contact.choice_or("rolling", RollingLaws::names(), "none");

  // Materials and interactions.
  std::vector<int> material_line;
  for (const Params& m : root.tables("material")) {
    Material mat;
    mat.name = m.string("name");
    for (const auto& other : s.materials)
      if (other.name == mat.name) m.fail("name", fmt::format("material '{}' is defined twice", mat.name));
    mat.density = m.number("density", Range::positive);
    mat.youngs_modulus = m.number("youngs_modulus", Range::positive);
    mat.poisson_ratio = m.number("poisson_ratio", Range::non_negative);
    if (mat.poisson_ratio >= 0.5) m.fail("poisson_ratio", "expected a value in [0, 0.5)");
    s.materials.push_back(mat);
    material_line.push_back(m.line());
  }
  if (s.materials.empty()) root.fail("material", "a scene needs at least one [[material]]");
  const std::size_t nm = s.materials.size();
  s.pairs.assign(nm * nm, MaterialPair{});
  std::vector<int> pair_line(nm * nm, 0);
  for (const Params& it : root.tables("interaction")) {
    const std::string names = it.string("materials");
    const auto slash = names.find('/');
    if (slash == std::string::npos) it.fail("materials", "expected \"a/b\" (two material names)");
    int idx[2];
    const std::string part[2] = {names.substr(0, slash), names.substr(slash + 1)};
    for (int q = 0; q < 2; ++q) {
      idx[q] = -1;
      for (std::size_t k = 0; k < nm; ++k)
        if (s.materials[k].name == part[q]) idx[q] = static_cast<int>(k);
      if (idx[q] < 0) it.fail("materials", fmt::format("material '{}' is not defined", part[q]));
    }
    MaterialPair mp;
    mp.restitution = it.number("restitution", Range::positive);
    if (mp.restitution > 1.0) it.fail("restitution", "expected a value in (0, 1]");
    mp.friction = it.number_or("friction", 0.0, Range::non_negative);
    mp.rolling_friction = it.number_or("rolling_friction", 0.0, Range::non_negative);
    for (auto [a, b] : {std::pair{idx[0], idx[1]}, std::pair{idx[1], idx[0]}}) {
      MaterialPair q = mp;
      q.a = &s.materials[static_cast<std::size_t>(a)];
      q.b = &s.materials[static_cast<std::size_t>(b)];
      s.pairs[static_cast<std::size_t>(a) * nm + b] = q;
      pair_line[static_cast<std::size_t>(a) * nm + b] = it.line();
    }
  }

  // Walls.
  std::map<std::string, int> wall_line;
  for (const Params& w : root.tables("wall")) {
    const std::string name = w.string("name");
    if (wall_line.count(name)) w.fail("name", fmt::format("wall '{}' is defined twice", name));
    wall_line[name] = w.line();
    read_wall(w, s.materials, s.walls);
  }

  // An initial state (e.g. a settled bed from an earlier run) brings its own particle materials.
  const auto initial = root.optional_table("initial_state");
  std::vector<int> initial_mats;
  if (initial) initial_mats = initial_state_materials(*initial, display_path, s.materials);

  // Which material pairs can touch: particle-particle among particle materials, particle-wall.
  std::set<int> particle_mats;
  std::vector<std::pair<const Params*, int>> needs;  // (where, material) for error lines
  const auto particle_tables = root.tables("particle");
  const auto factory_tables = root.tables("factory");
  std::vector<int> particle_mat_of, factory_mat_of;
  for (const Params& p : particle_tables) particle_mat_of.push_back(material_index(p, "material", s.materials));
  for (const Params& f : factory_tables) factory_mat_of.push_back(material_index(f, "material", s.materials));
  for (int m : particle_mat_of) particle_mats.insert(m);
  for (int m : initial_mats) particle_mats.insert(m);
  for (int m : factory_mat_of) particle_mats.insert(m);
  if (particle_mats.empty()) root.fail("particle", "the scene has no [[particle]], [[factory]] or [initial_state]");
  auto require_pair = [&](int a, int b, const std::string& what) {
    if (!s.pairs[static_cast<std::size_t>(a) * nm + b].a)
      throw InputError(display_path, material_line[static_cast<std::size_t>(a)], "interaction",
                       fmt::format("no [[interaction]] for materials '{}/{}' ({}): add one with restitution, "
                                   "friction and rolling_friction",
                                   s.materials[a].name, s.materials[b].name, what));
  };
  for (int a : particle_mats)
    for (int b : particle_mats) require_pair(a, b, "particles of both can touch");
  for (const Wall& w : s.walls)
    for (int a : particle_mats) require_pair(a, w.material, fmt::format("particles touch wall '{}'", w.name));

  // Plan: which arrays and passes. The laws mix each pair's coefficients (and read their own [contact] keys).
  s.laws = ContactLaws::table_of(s.plan.law);
  s.rolling = RollingLaws::table_of(s.plan.rolling);
  std::visit(
      [&](auto& table, auto& rolling) {
        using Law = LawOf<decltype(table)>;
        using Roll = LawOf<decltype(rolling)>;
        table.resize(nm * nm);
        rolling.resize(nm * nm);
        for (std::size_t k = 0; k < nm * nm; ++k)
          if (s.pairs[k].a) table[k] = Law::from_params(contact, s.pairs[k]), rolling[k] = Roll::from_params(contact, s.pairs[k]);
        s.plan.tangential = false;
        for (int a : particle_mats)
          for (std::size_t b = 0; b < nm; ++b)
            if (s.pairs[static_cast<std::size_t>(a) * nm + b].a)
              s.plan.tangential = s.plan.tangential || Law::needs_history(table[static_cast<std::size_t>(a) * nm + b]);
        if (Roll::needs_rotation && !rotation_switch)
          contact.fail("rolling", "rolling resistance needs rotation: set [physics] rotation = true");
        s.plan.rotation = rotation_switch && (s.plan.tangential || Roll::needs_rotation);
        // A rolling spring's slots follow the contact law's (kept even without friction: one layout).
        s.plan.history_width =
            Roll::history_size > 0 ? Law::history_size + Roll::history_size : Law::history_width(s.plan.tangential);
      },
      s.laws, s.rolling);

  // Particles: an initial state from an earlier run, explicit ones, then factories.
  if (s.plan.rotation) s.particles.enable_rotation();
  double r_min = inf;
  if (initial) {
    read_initial_state(*initial, display_path, s);
    for (double r : s.particles.radius) r_min = std::min(r_min, r);
  }
  for (std::size_t k = 0; k < particle_tables.size(); ++k) {
    const Params& p = particle_tables[k];
    const double r = p.number("radius", Range::positive);
    const Vec3 x = vec(p, "position");
    const Vec3 v = vec_or(p, "velocity", {});
    const Vec3 w = vec_or(p, "angular_velocity", {});
    if (!s.plan.rotation && p.has("angular_velocity") && norm(w) > 0.0)
      p.fail("angular_velocity", "the scene has no rotation (no friction or rotation = false)");
    const Vec3 &lo = s.config.domain_min, &hi = s.config.domain_max;
    if (!(x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z))
      p.fail("position", "the particle is outside the [domain] box");
    for (const Wall& wall : s.walls) {
      Vec3 n;
      if (wall_distance(wall, Vec3{}, x, &n) < r)
        p.fail("position", fmt::format("the particle overlaps wall '{}' at t = 0", wall.name));
    }
    s.particles.add(particle_mat_of[k], r, s.materials[particle_mat_of[k]].density, x, v, w);
    r_min = std::min(r_min, r);
  }
  // Overlaps among the spheres so far (initial state + explicit), found with the cell list (a scene may
  // list ~10^4 spheres): reported at the later sphere's table.
  {
    const std::size_t first_explicit = s.particles.size() - particle_tables.size();
    const CandidatePairs c = build_pairs(s.particles.x, s.particles.radius, 0.0);
    for (std::size_t k = 0; k < c.i.size(); ++k) {
      const std::size_t a = c.i[k], b = c.j[k];  // a < b
      if (b < first_explicit) continue;        // two spheres of an earlier run's snapshot: its business
      particle_tables[b - first_explicit].fail(
          "position", fmt::format("the particle overlaps particle {} ({} m deep)", a,
                                  s.particles.radius[a] + s.particles.radius[b] - norm(s.particles.x[b] - s.particles.x[a])));
    }
  }
  for (std::size_t k = 0; k < factory_tables.size(); ++k) {
    const Params& f = factory_tables[k];
    const int mat = factory_mat_of[k];
    const std::uint64_t seed = static_cast<std::uint64_t>(f.integer_or("seed", static_cast<long>(s.seed + k)));
    FillRegion region;
    std::string container;  // a funnel fill lies inside its own wall: that wall is not "in the region"
    const std::string shape = f.choice("shape", {"box", "cylinder", "funnel"});
    if (shape == "box") {
      region.shape = FillRegion::box;
      region.lo = vec(f, "min");
      region.hi = vec(f, "max");
      if (!(region.hi.x > region.lo.x && region.hi.y > region.lo.y && region.hi.z > region.lo.z))
        f.fail("max", "max must exceed min on every axis");
    } else if (shape == "cylinder") {
      region.shape = FillRegion::cylinder;
      const auto c = f.numbers("center", 2);
      region.cx = c[0];
      region.cy = c[1];
      region.r_bottom = region.r_top = f.number("radius", Range::positive);
      region.z_min = f.number("z_min");
      region.z_max = f.number("z_max");
      if (!(region.z_max > region.z_min)) f.fail("z_max", "z_max must exceed z_min");
    } else {
      container = f.string("wall");
      const Wall* cone = nullptr;
      for (const Wall& w : s.walls)
        if (w.name == container && w.kind == WallKind::revolution && w.r0 != w.r1) {
          cone = &w;
          break;
        }
      if (!cone) f.fail("wall", fmt::format("no funnel or cone wall named '{}'", container));
      region.shape = FillRegion::frustum;
      region.cx = cone->origin.x;
      region.cy = cone->origin.y;
      const bool up = cone->z1 > cone->z0;
      region.z_min = up ? cone->z0 : cone->z1;
      region.z_max = up ? cone->z1 : cone->z0;
      region.r_bottom = up ? cone->r0 : cone->r1;
      region.r_top = up ? cone->r1 : cone->r0;
    }
    {
      // A region reaching out of the domain would put spheres there: the run would stop at t = 0 with "left
      // the domain" and no line. Said here, at the factory's table.
      Vec3 lo, hi;
      region.bounds(&lo, &hi);
      const Vec3 &dlo = s.config.domain_min, &dhi = s.config.domain_max;
      if (!inside(lo, dlo, dhi) || !inside(hi, dlo, dhi))
        f.fail(shape == "box" ? "max" : shape == "funnel" ? "wall" : "radius",
               fmt::format("the {} region ({:g}, {:g}, {:g}) to ({:g}, {:g}, {:g}) m reaches outside the [domain] box "
                           "({:g}, {:g}, {:g}) to ({:g}, {:g}, {:g}) m",
                           shape, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, dlo.x, dlo.y, dlo.z, dhi.x, dhi.y, dhi.z));
    }
    // A wall crossing the region (e.g. a plate across the fill box) is a scene error. A wall surface point
    // deeper inside the region than the smallest particle radius means the wall passes through it; walls
    // on the region's boundary (a box filled up to its sides) do not count.
    std::vector<double> radii = diameters_from(f, s.materials[mat].density, seed);
    for (double& r : radii) r *= 0.5;
    {
      const double margin = *std::min_element(radii.begin(), radii.end());
      for (const Wall& w : s.walls) {
        if (w.name == container) continue;
        if (wall_crosses(w, region, margin))
          f.fail("shape", fmt::format("wall '{}' passes through the factory region", w.name));
      }
    }
    const Vec3 v = vec_or(f, "velocity", {});
    const FillResult fill =
        fill_region(region, radii, s.particles.x, s.particles.radius, s.walls, seed ^ 0x5eedf111ULL);
    if (!fill.complete)
      f.fail("mass", fmt::format("the region holds only {} of the {} spheres without overlap: enlarge it or "
                                 "reduce the mass",
                                 fill.placed, radii.size()));
    // Ids follow a Morton (Z-order) curve through the region: spatial neighbours are neighbours in
    // memory, which keeps the contact loops cache-friendly (a pour keeps much of that order as it falls).
    std::vector<std::pair<std::uint64_t, std::size_t>> order;
    {
      Vec3 lo, hi;
      region.bounds(&lo, &hi);
      auto spread = [](std::uint64_t a) {  // 21 bits -> every third bit
        a &= 0x1fffff;
        a = (a | a << 32) & 0x1f00000000ffffULL;
        a = (a | a << 16) & 0x1f0000ff0000ffULL;
        a = (a | a << 8) & 0x100f00f00f00f00fULL;
        a = (a | a << 4) & 0x10c30c30c30c30c3ULL;
        a = (a | a << 2) & 0x1249249249249249ULL;
        return a;
      };
      auto cell = [](double x, double a, double b) {
        return static_cast<std::uint64_t>(std::clamp((x - a) / (b - a), 0.0, 1.0) * 2097151.0);
      };
      for (std::size_t q = 0; q < radii.size(); ++q) {
        const Vec3& x = fill.positions[q];
        order.emplace_back(spread(cell(x.x, lo.x, hi.x)) | spread(cell(x.y, lo.y, hi.y)) << 1 |
                               spread(cell(x.z, lo.z, hi.z)) << 2,
                           q);
      }
      std::sort(order.begin(), order.end());
    }
    for (const auto& [code, q] : order) {
      s.particles.add(mat, radii[q], s.materials[mat].density, fill.positions[q], v, {});
      r_min = std::min(r_min, radii[q]);
    }
  }

  // Neighbour skin: default the smallest radius (LIGGGHTS scenes usually use ~r_min).
  s.config.skin = r_min;
  if (auto nb = root.optional_table("neighbor")) s.config.skin = nb->number_or("skin", r_min, Range::positive);

  s.output_interval = s.end_time / 20.0;
  s.energy_interval = 0.0;
  if (auto out = root.optional_table("output")) {
    s.output_interval = out->number_or("interval", s.output_interval, Range::positive);
    s.energy_interval = out->number_or("energy_interval", 0.0, Range::positive);
    s.checkpoint_interval = out->number_or("checkpoint_interval", 0.0, Range::positive);
  }
  if (s.energy_interval == 0.0) s.energy_interval = s.output_interval;
  s.stop = parse_stop_rule(root);

  // Blow-up limit: the particles cannot gain more kinetic energy than the initial one plus the largest
  // fall inside the domain; twice that is certainly a numerical blow-up.
  {
    double ke0 = 0.0, m = 0.0;
    for (std::size_t a = 0; a < s.particles.size(); ++a) {
      ke0 += 0.5 * s.particles.mass[a] * norm2(s.particles.v[a]);
      m += s.particles.mass[a];
    }
    const Vec3 d = s.config.domain_max - s.config.domain_min;
    const double fall = std::abs(s.config.gravity.x) * d.x + std::abs(s.config.gravity.y) * d.y +
                        std::abs(s.config.gravity.z) * d.z;
    s.config.kinetic_limit = 2.0 * (ke0 + m * fall) + 1e-12;
  }
  root.finish();
  warn_time_step(s);
  return s;
}

Scene load_scene(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), 0, "", "cannot open the scene file");
  std::stringstream buf;
  buf << in.rdbuf();
  return parse_scene(buf.str(), path.string());
}

World make_world(const Scene& s) {
  World w(s.config, s.materials, s.laws, s.rolling, s.particles, s.walls, s.plan.history_width);
  if (s.plan.fluid) w.set_fluid(std::make_shared<fluid::FluidField>(s.fluid));  // fluid hook
  return w;
}

}  // namespace pastemix::model
