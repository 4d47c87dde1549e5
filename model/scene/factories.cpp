// SPDX-License-Identifier: MIT
// [[factory]]: a region (box, cylinder, or the cone of a funnel wall) filled at t = 0 with spheres drawn from
// a PSD, without overlaps, numbered along a Morton curve.
#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "base/psd.h"
#include "model/scene/read.h"

namespace pastemix::model {
namespace {

// Diameters (m) for the factory's mass (kg) of its [[factory.psd]] intervals.
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

// The frustum inside a funnel or cone wall named by the factory's `wall`.
FillRegion funnel_region(const Params& f, const std::vector<Wall>& walls, const std::string& container) {
  const Wall* cone = nullptr;
  for (const Wall& w : walls)
    if (w.name == container && w.kind == WallKind::revolution && w.r0 != w.r1) {
      cone = &w;
      break;
    }
  if (!cone) f.fail("wall", fmt::format("no funnel or cone wall named '{}'", container));
  FillRegion region;
  region.shape = FillRegion::frustum;
  region.cx = cone->origin.x;
  region.cy = cone->origin.y;
  const bool up = cone->z1 > cone->z0;
  region.z_min = up ? cone->z0 : cone->z1;
  region.z_max = up ? cone->z1 : cone->z0;
  region.r_bottom = up ? cone->r0 : cone->r1;
  region.r_top = up ? cone->r1 : cone->r0;
  return region;
}

// The factory's region; `container` is the funnel wall a funnel fill lies in (that wall is not "in the
// region").
FillRegion region_of(const Params& f, const std::string& shape, const Scene& s, std::string* container) {
  FillRegion region;
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
    *container = f.string("wall");
    region = funnel_region(f, s.walls, *container);
  }
  // A region reaching out of the domain would put spheres there: the run would stop at t = 0 with "left the
  // domain" and no line. Said here, at the factory's table.
  Vec3 lo, hi;
  region.bounds(&lo, &hi);
  const Vec3 &dlo = s.config.domain_min, &dhi = s.config.domain_max;
  if (!inside(lo, dlo, dhi) || !inside(hi, dlo, dhi))
    f.fail(shape == "box" ? "max" : shape == "funnel" ? "wall" : "radius",
           fmt::format("the {} region ({:g}, {:g}, {:g}) to ({:g}, {:g}, {:g}) m reaches outside the [domain] box "
                       "({:g}, {:g}, {:g}) to ({:g}, {:g}, {:g}) m",
                       shape, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, dlo.x, dlo.y, dlo.z, dhi.x, dhi.y, dhi.z));
  return region;
}

// 21 bits -> every third bit of a 63-bit Morton code.
std::uint64_t spread(std::uint64_t a) {
  a &= 0x1fffff;
  a = (a | a << 32) & 0x1f00000000ffffULL;
  a = (a | a << 16) & 0x1f0000ff0000ffULL;
  a = (a | a << 8) & 0x100f00f00f00f00fULL;
  a = (a | a << 4) & 0x10c30c30c30c30c3ULL;
  a = (a | a << 2) & 0x1249249249249249ULL;
  return a;
}

// Ids follow a Morton (Z-order) curve through the region: spatial neighbours are neighbours in memory, which
// keeps the contact loops cache-friendly (a pour keeps much of that order as it falls).
std::vector<std::size_t> morton_order(const FillRegion& region, const std::vector<Vec3>& x) {
  Vec3 lo, hi;
  region.bounds(&lo, &hi);
  auto cell = [](double v, double a, double b) {
    return static_cast<std::uint64_t>(std::clamp((v - a) / (b - a), 0.0, 1.0) * 2097151.0);
  };
  std::vector<std::pair<std::uint64_t, std::size_t>> order;
  for (std::size_t q = 0; q < x.size(); ++q)
    order.emplace_back(
        spread(cell(x[q].x, lo.x, hi.x)) | spread(cell(x[q].y, lo.y, hi.y)) << 1 | spread(cell(x[q].z, lo.z, hi.z)) << 2,
        q);
  std::sort(order.begin(), order.end());
  std::vector<std::size_t> out;
  for (const auto& [code, q] : order) out.push_back(q);
  return out;
}

// Fills one factory; returns the smallest radius placed.
double fill_factory(const Params& f, int mat, std::uint64_t seed, Scene& s) {
  std::string container;
  const std::string shape = f.choice("shape", {"box", "cylinder", "funnel"});
  const FillRegion region = region_of(f, shape, s, &container);
  std::vector<double> radii = diameters_from(f, s.materials[static_cast<std::size_t>(mat)].density, seed);
  for (double& r : radii) r *= 0.5;
  // A mass below one sphere of the PSD (or a d_max of astronomical size: found by fuzzing) draws nothing.
  if (radii.empty())
    f.fail("mass", fmt::format("{:g} kg makes not one sphere of this PSD (d up to {:g} m): raise the mass or check "
                               "the [[factory.psd]] sizes (m)",
                               f.number("mass"), f.tables("psd").back().number("d_max")));
  // A wall crossing the region (e.g. a plate across the fill box) is a scene error. A wall surface point
  // deeper inside the region than the smallest particle radius means the wall passes through it; walls on
  // the region's boundary (a box filled up to its sides) do not count.
  const double margin = *std::min_element(radii.begin(), radii.end());
  for (const Wall& w : s.walls)
    if (w.name != container && wall_crosses(w, region, margin))
      f.fail("shape", fmt::format("wall '{}' passes through the factory region", w.name));
  const Vec3 v = vec_or(f, "velocity", {});
  const FillResult fill = fill_region(region, radii, s.particles.x, s.particles.radius, s.walls, seed ^ 0x5eedf111ULL);
  if (!fill.complete)
    f.fail("mass", fmt::format("the region holds only {} of the {} spheres without overlap: enlarge it or reduce the "
                               "mass",
                               fill.placed, radii.size()));
  for (std::size_t q : morton_order(region, fill.positions))
    s.particles.add(mat, radii[q], s.materials[static_cast<std::size_t>(mat)].density, fill.positions[q], v, {});
  return margin;
}

}  // namespace

double read_factories(const ParticleSources& src, Scene& s) {
  double r_min = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < src.factories.size(); ++k) {
    const Params& f = src.factories[k];
    // Default seed: the scene's plus the factory's index (so realizations with another scene seed differ).
    const auto seed = static_cast<std::uint64_t>(f.integer_or("seed", static_cast<long>(s.seed + k)));
    r_min = std::min(r_min, fill_factory(f, src.factory_material[k], seed, s));
  }
  return r_min;
}

}  // namespace pastemix::model
