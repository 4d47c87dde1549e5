// SPDX-License-Identifier: MIT
// The spheres a scene starts with: an [initial_state] snapshot of an earlier run (a settled bed), then the
// explicit [[particle]]s; each checked against the domain, the walls and the others.
#include <algorithm>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "base/h5.h"
#include "model/neighbor.h"
#include "model/scene/read.h"

namespace pastemix::model {
namespace {

// A snapshot of an earlier run has spheres resting on its walls with contact overlaps of ~1e-3 r; a cut
// deeper than this share of the radius is a wall the snapshot never had.
constexpr double kWallCutTolerance = 0.02;

// [initial_state] file, relative to the scene.
std::filesystem::path initial_file(const Params& t, const std::string& scene_path) {
  std::filesystem::path f = t.string("file");
  if (f.is_relative()) f = std::filesystem::path(scene_path).parent_path() / f;
  if (!std::filesystem::exists(f)) t.fail("file", fmt::format("no such file: {}", f.string()));
  return f;
}

// [initial_state] snapshot: index, -1 = last.
std::string initial_group(const Params& t, const H5Reader& h5) {
  const auto times = h5.read_doubles("/snapshots/time");
  const long n = static_cast<long>(times.size());
  long k = t.integer_or("snapshot", -1);
  if (k < 0) k += n;
  if (k < 0 || k >= n) t.fail("snapshot", fmt::format("the file has {} snapshots", n));
  return fmt::format("/snapshots/{:06d}", k);
}

void check_inside_domain(const Params& t, std::string_view key, const Vec3& p, const WorldConfig& c,
                         const std::string& what) {
  if (!inside(p, c.domain_min, c.domain_max))
    t.fail(key, fmt::format("{} at ({:g}, {:g}, {:g}) m is outside the [domain] box ({:g}, {:g}, {:g}) to ({:g}, {:g}, "
                            "{:g}) m",
                            what, p.x, p.y, p.z, c.domain_min.x, c.domain_min.y, c.domain_min.z, c.domain_max.x,
                            c.domain_max.y, c.domain_max.z));
}

// A sphere cut by a wall of this scene would be pushed out at an arbitrary speed on the first step.
void check_not_cut(const Params& t, const Scene& s, std::size_t a, const Vec3& p, double r) {
  for (const Wall& wall : s.walls) {
    Vec3 n;
    const double gap = wall_distance(wall, Vec3{}, p, &n);
    if (gap < r * (1.0 - kWallCutTolerance))
      t.fail("file", fmt::format("sphere {} of the snapshot (radius {:g} m) is cut by wall '{}' ({:.3g} m deep) at t = 0",
                                 a, r, wall.name, r - gap));
  }
}

void read_initial_state(const Params& t, Scene& s) {
  H5Reader h5(initial_file(t, s.path));
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
    check_not_cut(t, s, a, p, r[a]);
    s.particles.add(mat, r[a], s.materials[static_cast<std::size_t>(mat)].density, p,
                    {v[3 * a], v[3 * a + 1], v[3 * a + 2]}, om);
  }
}

void read_explicit(const Params& p, int material, Scene& s) {
  const double r = p.number("radius", Range::positive);
  const Vec3 x = vec(p, "position");
  const Vec3 v = vec_or(p, "velocity", {});
  const Vec3 w = vec_or(p, "angular_velocity", {});
  if (!s.plan.rotation && p.has("angular_velocity") && norm(w) > 0.0)
    p.fail("angular_velocity", "the scene has no rotation (no friction or rotation = false)");
  if (!inside(x, s.config.domain_min, s.config.domain_max)) p.fail("position", "the particle is outside the [domain] box");
  for (const Wall& wall : s.walls) {
    Vec3 n;
    if (wall_distance(wall, Vec3{}, x, &n) < r)
      p.fail("position", fmt::format("the particle overlaps wall '{}' at t = 0", wall.name));
  }
  s.particles.add(material, r, s.materials[static_cast<std::size_t>(material)].density, x, v, w);
}

// Overlaps among the spheres so far (initial state + explicit), found with the cell list (a scene may list
// ~10^4 spheres): reported at the later sphere's table.
void check_overlaps(const std::vector<Params>& tables, const Particles& p) {
  const std::size_t first_explicit = p.size() - tables.size();
  const CandidatePairs c = build_pairs(p.x, p.radius, 0.0);
  for (std::size_t k = 0; k < c.i.size(); ++k) {
    const std::size_t a = c.i[k], b = c.j[k];  // a < b
    if (b < first_explicit) continue;          // two spheres of an earlier run's snapshot: its business
    tables[b - first_explicit].fail("position", fmt::format("the particle overlaps particle {} ({} m deep)", a,
                                                            p.radius[a] + p.radius[b] - norm(p.x[b] - p.x[a])));
  }
}

}  // namespace

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
  return {used.begin(), used.end()};
}

double read_particles(const ParticleSources& src, Scene& s) {
  if (s.plan.rotation) s.particles.enable_rotation();
  if (src.initial) read_initial_state(*src.initial, s);
  for (std::size_t k = 0; k < src.particles.size(); ++k) read_explicit(src.particles[k], src.particle_material[k], s);
  check_overlaps(src.particles, s.particles);
  double r_min = std::numeric_limits<double>::infinity();
  for (double r : s.particles.radius) r_min = std::min(r_min, r);
  return r_min;
}

}  // namespace pastemix::model
