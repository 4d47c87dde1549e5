// SPDX-License-Identifier: MIT
// [[wall]]: each wall type expanded into the primitives of model/walls.h; and whether a wall passes through a
// fill region (a factory check).
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "base/units.h"
#include "model/scene/read.h"

namespace pastemix::model {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

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

void plane(const Params& w, Wall p, std::vector<Wall>& out) {
  p.kind = WallKind::plane;
  p.origin = vec(w, "point");
  const Vec3 n = vec(w, "normal");
  if (norm(n) == 0.0) w.fail("normal", "the normal must not be zero");
  p.normal = n * (1.0 / norm(n));
  out.push_back(p);
}

// An open-top box: the floor and four sides as rectangles.
void box(const Params& w, const Wall& b, std::vector<Wall>& out) {
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
}

void cylinder(const Params& w, const Wall& b, std::vector<Wall>& out) {
  const auto c = w.numbers("center", 2);
  const double r = w.number("radius", Range::positive);
  const double z0 = w.number("z_min"), z1 = w.number("z_max");
  if (!(z1 > z0)) w.fail("z_max", "z_max must exceed z_min");
  out.push_back(revolution(b, c[0], c[1], r, z0, r, z1));
}

void cone(const Params& w, const Wall& b, std::vector<Wall>& out) {
  const auto c = w.numbers("center", 2);
  const double z0 = w.number("z0"), r0 = w.number("r0", Range::non_negative);
  const double z1 = w.number("z1"), r1 = w.number("r1", Range::non_negative);
  if (z0 == z1 && r0 == r1) w.fail("z1", "degenerate cone (a single circle)");
  out.push_back(revolution(b, c[0], c[1], r0, z0, r1, z1));
}

void disk(const Params& w, const Wall& b, std::vector<Wall>& out) {
  const Vec3 c = vec(w, "center");
  const double r = w.number("radius", Range::positive);
  Wall d = revolution(b, c.x, c.y, 0.0, 0.0, r, 0.0);
  d.origin.z = c.z;
  out.push_back(d);
}

// A funnel: the frustum from the exit up, plus the exit tube below it.
void funnel(const Params& w, const Wall& b, std::vector<Wall>& out) {
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

void read_wall(const Params& w, const std::vector<Material>& mats, std::vector<Wall>& out) {
  const std::string name = w.string("name");
  const std::string type = w.choice("type", {"plane", "box", "cylinder", "cone", "disk", "funnel"});
  const Wall b = base_wall(w, name, material_index(w, "material", mats));
  if (type == "plane") plane(w, b, out);
  else if (type == "box") box(w, b, out);
  else if (type == "cylinder") cylinder(w, b, out);
  else if (type == "cone") cone(w, b, out);
  else if (type == "disk") disk(w, b, out);
  else funnel(w, b, out);
}

}  // namespace

void read_walls(const Params& root, Scene& s) {
  std::map<std::string, int> wall_line;
  for (const Params& w : root.tables("wall")) {
    const std::string name = w.string("name");
    if (wall_line.count(name)) w.fail("name", fmt::format("wall '{}' is defined twice", name));
    wall_line[name] = w.line();
    read_wall(w, s.materials, s.walls);
  }
}

// Samples the surface on a 96 x 96 grid; a plane crosses when the region's bounding-box corners lie on both
// sides of it by more than margin.
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
          const double t = static_cast<double>(a) / N, phi = 2.0 * units::pi * b / N;
          const double r = w.r0 + t * (w.r1 - w.r0), z = w.z0 + t * (w.z1 - w.z0);
          const Vec3 pt{w.origin.x + r * std::cos(phi), w.origin.y + r * std::sin(phi), w.origin.z + z};
          if (region.contains(pt, margin)) return true;
        }
      return false;
  }
  return false;
}

}  // namespace pastemix::model
