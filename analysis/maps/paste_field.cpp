// SPDX-License-Identifier: MIT
#include "analysis/maps/paste_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "base/error.h"
#include "base/h5.h"
#include "base/units.h"

namespace pastemix::analysis {

namespace {

const char* const kAxis[3] = {"x", "y", "z"};
constexpr double kAlphaSlack = 1e-4;      // -, round-off: clamped silently (see read_paste_field)
constexpr double kAlphaDefect = 0.1;      // -, per cell: clamped and named in the field's source; beyond, a bad file
constexpr double kDefectVolume = 1e-3;    // -, all the clamped excess over the field's paste: beyond, a bad file

// Component d (0 = x, 1 = y, 2 = z) of a point.
double& at(Vec3& v, int d) { return d == 0 ? v.x : d == 1 ? v.y : v.z; }
double at(const Vec3& v, int d) { return d == 0 ? v.x : d == 1 ? v.y : v.z; }

// The cell indices [lo, hi) along axis d that overlap [a, b] (m); empty when outside the grid.
std::array<int, 2> cell_range(const PasteField& f, int d, double a, double b) {
  const double lo = std::floor((a - f.origin[d]) / f.h[d]);
  const double hi = std::ceil((b - f.origin[d]) / f.h[d]);
  return {static_cast<int>(std::clamp(lo, 0.0, double(f.n[d]))), static_cast<int>(std::clamp(hi, 0.0, double(f.n[d])))};
}

Box3 intersect(const Box3& a, const Box3& b) {
  Box3 r;
  for (int d = 0; d < 3; ++d) {
    at(r.lo, d) = std::max(at(a.lo, d), at(b.lo, d));
    at(r.hi, d) = std::min(at(a.hi, d), at(b.hi, d));
  }
  return r;
}

double volume(const Box3& b) {
  double v = 1.0;
  for (int d = 0; d < 3; ++d) v *= std::max(0.0, at(b.hi, d) - at(b.lo, d));
  return v;
}

bool sphere_touches(const Vec3& c, double r, const Box3& b) {
  for (int d = 0; d < 3; ++d)
    if (at(c, d) + r <= at(b.lo, d) || at(c, d) - r >= at(b.hi, d)) return false;
  return true;
}

// The flow snapshot groups /flow/snapshots/NNNNNN with their times: each group's time_s attribute (the engine's
// result files) or, without it, the /flow/snapshots/time dataset (the flow solver's own files, flow_output.h).
std::vector<std::pair<std::string, double>> flow_snapshots(const H5Reader& h5, const std::string& file) {
  std::vector<std::string> names;
  for (const std::string& c : h5.children("/flow/snapshots"))
    if (c.size() == 6 && c.find_first_not_of("0123456789") == std::string::npos) names.push_back(c);
  std::sort(names.begin(), names.end());
  std::vector<double> listed;
  if (h5.exists("/flow/snapshots/time")) listed = h5.read_doubles("/flow/snapshots/time");
  std::vector<std::pair<std::string, double>> out;
  for (std::size_t s = 0; s < names.size(); ++s) {
    const std::string g = "/flow/snapshots/" + names[s];
    const std::size_t idx = static_cast<std::size_t>(std::stoul(names[s]));
    if (h5.has_attribute(g, "time_s")) out.emplace_back(g, h5.attribute_double(g, "time_s"));
    else if (idx < listed.size()) out.emplace_back(g, listed[idx]);
    else throw InputError(file, 0, g, "a flow snapshot without a time (no time_s attribute, not in /flow/snapshots/time)");
  }
  if (out.empty()) throw InputError(file, 0, "/flow/snapshots", "the flow field has no snapshot");
  return out;
}

// The snapshot group nearest time_s (see the header for the tolerance).
std::string nearest_snapshot(const H5Reader& h5, const std::string& file, double time_s, double& t_found) {
  const auto snaps = flow_snapshots(h5, file);
  std::size_t best = 0;
  for (std::size_t s = 1; s < snaps.size(); ++s)
    if (std::abs(snaps[s].second - time_s) < std::abs(snaps[best].second - time_s)) best = s;
  double tol = 1e-9;
  if (snaps.size() > 1) tol = 0.5 * std::abs(snaps[1].second - snaps[0].second) + 1e-9;
  if (!(std::abs(snaps[best].second - time_s) <= tol))
    throw InputError(file, 0, "/flow/snapshots",
                     fmt::format("no flow snapshot at the particles' time {:g} s (nearest {:g} s)", time_s,
                                 snaps[best].second));
  t_found = snaps[best].second;
  return snaps[best].first;
}

}  // namespace

Box3 PasteField::cell_box(int i, int j, int k) const {
  const int idx[3] = {i, j, k};
  Box3 b;
  for (int d = 0; d < 3; ++d) {
    at(b.lo, d) = origin[d] + idx[d] * h[d];
    at(b.hi, d) = origin[d] + (idx[d] + 1) * h[d];
  }
  return b;
}

bool has_paste_field(const H5Reader& h5) {
  if (!h5.exists("/flow/snapshots")) return false;
  for (const std::string& c : h5.children("/flow/snapshots"))
    if (c.size() == 6 && c.find_first_not_of("0123456789") == std::string::npos) return true;
  return false;
}

PasteField read_paste_field(const H5Reader& h5, const std::string& file, double time_s) {
  PasteField f;
  for (int d = 0; d < 3; ++d) {
    const std::string nn = fmt::format("n{}", kAxis[d]), hn = fmt::format("h{}", kAxis[d]);
    const std::string on = fmt::format("origin_{}", kAxis[d]);
    for (const std::string& a : {nn, hn, on})
      if (!h5.has_attribute("/flow", a))
        throw InputError(file, 0, fmt::format("attribute '{}' of '/flow'", a), "missing (a flow field needs its grid)");
    const std::int64_t n = h5.attribute_int("/flow", nn);
    f.h[d] = h5.attribute_double("/flow", hn);
    f.origin[d] = h5.attribute_double("/flow", on);
    if (n < 1 || n > 100000 || !(f.h[d] > 0.0) || !std::isfinite(f.h[d]) || !std::isfinite(f.origin[d]))
      throw InputError(file, 0, fmt::format("/flow grid along {}", kAxis[d]),
                       fmt::format("n = {}, h = {:g} m, origin = {:g} m is not a grid", n, f.h[d], f.origin[d]));
    f.n[d] = static_cast<int>(n);
  }
  const std::string grp = nearest_snapshot(h5, file, time_s, f.time_s);
  const std::string ds = grp + "/paste_fraction";
  if (!h5.exists(ds)) throw InputError(file, 0, ds, "missing");
  const std::vector<std::uint64_t> dims = h5.dims(ds);
  const std::vector<std::uint64_t> want = {std::uint64_t(f.n[2]), std::uint64_t(f.n[1]), std::uint64_t(f.n[0])};
  if (dims != want)
    throw InputError(file, 0, ds, fmt::format("dims are not the grid's nz x ny x nx = {} x {} x {}", want[0], want[1], want[2]));
  f.alpha = h5.read_doubles(ds);
  // The flow's advection keeps alpha in [0, 1] to ~5e-6 in a clear fluid (datasets/scenes/flow_drop.toml: max
  // alpha - 1 = 5.2e-6): values within 1e-4 are its round-off, clamped. In air cells inside a packed rock pile
  // (fluid fraction ~0.43) the coupled advection leaves alpha below 0 (case 3 with flow, docs/studies/case3_flow:
  // seed 3 down to -0.0104 in 12 cells, seed 4 to -0.0242 in 6; all of it 1.1e-5 of the paste), the VOF's
  // boundedness not holding where the fluid fraction changes (results of engines before e133a78, whose sweeps cut
  // a partly full donor's slab as if its fluid filled the cell: fixed there, model/flow/advection.cpp). Such
  // values, up to 0.1 a cell and 1e-3 of the field's paste in all, are clamped and named in the source; anything
  // beyond is a bad file.
  double worst = 0.0, excess_sum = 0.0, paste_sum = 0.0;
  std::size_t defects = 0;
  for (std::size_t c = 0; c < f.alpha.size(); ++c) {
    double& a = f.alpha[c];
    if (!std::isfinite(a) || a < -kAlphaDefect || a > 1.0 + kAlphaDefect)
      throw InputError(file, 0, ds, fmt::format("cell {} has paste fraction {:.9g}, not in [0, 1]", c, a));
    const double excess = std::max({-a, a - 1.0, 0.0});
    if (excess > kAlphaSlack) ++defects, worst = std::max(worst, excess);
    excess_sum += excess;
    a = std::clamp(a, 0.0, 1.0);
    paste_sum += a;
  }
  if (excess_sum > kDefectVolume * std::max(paste_sum, 1.0))
    throw InputError(file, 0, ds, fmt::format("paste fractions outside [0, 1] by {:.3g} cells in all ({} cells beyond "
                                              "1e-4), more than {:g} of the field's paste ({:.6g} cells)",
                                              excess_sum, defects, kDefectVolume, paste_sum));
  f.source = fmt::format("{}:{}", file, grp);
  if (defects > 0)
    f.source += fmt::format(" (paste fraction clamped to [0, 1] in {} cell(s), by up to {:.3g})", defects, worst);
  return f;
}

double paste_surface_z(const PasteField& f, double x0, double x1, double y0, double y1) {
  double sum = 0.0, area = 0.0;
  const auto ri = cell_range(f, 0, x0, x1), rj = cell_range(f, 1, y0, y1);
  for (int j = rj[0]; j < rj[1]; ++j)
    for (int i = ri[0]; i < ri[1]; ++i) {
      const Box3 c = f.cell_box(i, j, 0);
      const double w = std::max(0.0, std::min(x1, c.hi.x) - std::max(x0, c.lo.x)) *
                       std::max(0.0, std::min(y1, c.hi.y) - std::max(y0, c.lo.y));
      if (w <= 0.0) continue;
      double height = f.origin[2];
      for (int k = 0; k < f.n[2]; ++k) height += f.alpha[f.cell(i, j, k)] * f.h[2];
      sum += w * height;
      area += w;
    }
  if (!(area > 0.0))
    throw InputError(f.source, 0, "/flow grid",
                     fmt::format("the block grid's footprint x [{:g}, {:g}] y [{:g}, {:g}] m is outside the flow grid",
                                 x0, x1, y0, y1));
  return sum / area;
}

double paste_volume_in(const PasteField& f, const Box3& box, const ParticleView& particles) {
  std::vector<std::size_t> near;  // particles that reach into the box
  for (std::size_t p = 0; p < particles.position.size(); ++p)
    if (sphere_touches(particles.position[p], particles.radius[p], box)) near.push_back(p);
  const auto ri = cell_range(f, 0, box.lo.x, box.hi.x), rj = cell_range(f, 1, box.lo.y, box.hi.y);
  const auto rk = cell_range(f, 2, box.lo.z, box.hi.z);
  double paste = 0.0;
  for (int k = rk[0]; k < rk[1]; ++k)
    for (int j = rj[0]; j < rj[1]; ++j)
      for (int i = ri[0]; i < ri[1]; ++i) {
        const double a = f.alpha[f.cell(i, j, k)];
        if (a == 0.0) continue;
        const Box3 piece = intersect(f.cell_box(i, j, k), box);
        const double v = volume(piece);
        if (v <= 0.0) continue;
        double rock = 0.0;
        for (std::size_t p : near)
          if (sphere_touches(particles.position[p], particles.radius[p], piece))
            rock += sphere_box_volume(particles.position[p], particles.radius[p], piece);
        paste += a * std::max(0.0, v - rock);  // overlapping soft spheres can overfill a piece: no paste then
      }
  return paste;
}

std::vector<double> paste_share_around(const PasteField& f, const ParticleView& particles) {
  std::vector<double> share(particles.position.size(), 0.0);
  for (std::size_t p = 0; p < share.size(); ++p) {
    const Vec3& c = particles.position[p];
    const double r = particles.radius[p];
    const auto ri = cell_range(f, 0, c.x - r, c.x + r), rj = cell_range(f, 1, c.y - r, c.y + r);
    const auto rk = cell_range(f, 2, c.z - r, c.z + r);
    double wet = 0.0;
    for (int k = rk[0]; k < rk[1]; ++k)
      for (int j = rj[0]; j < rj[1]; ++j)
        for (int i = ri[0]; i < ri[1]; ++i) {
          const double a = f.alpha[f.cell(i, j, k)];
          if (a > 0.0) wet += a * sphere_box_volume(c, r, f.cell_box(i, j, k));
        }
    share[p] = std::clamp(wet / (4.0 / 3.0 * units::pi * r * r * r), 0.0, 1.0);
  }
  return share;
}

}  // namespace pastemix::analysis
