// SPDX-License-Identifier: MIT
#include "analysis/pile/repose_angle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "base/error.h"
#include "base/stats.h"
#include "base/units.h"

namespace pastemix::analysis {

ReposeAngle measure_repose_angle(std::span<const Vec3> position, std::span<const double> radius,
                                 const ReposeOptions& opt) {
  const std::size_t n = radius.size();
  if (n < 10) throw RuntimeFailure(fmt::format("repose angle: only {} particles, no pile to measure", n));
  // Axis.
  std::array<double, 2> axis{0.0, 0.0};
  double mean_d = 0.0;
  if (opt.axis_xy) {
    axis = *opt.axis_xy;
  } else {
    double mass = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
      const double w = radius[p] * radius[p] * radius[p];
      axis[0] += w * position[p].x;
      axis[1] += w * position[p].y;
      mass += w;
    }
    axis[0] /= mass;
    axis[1] /= mass;
  }
  for (double r : radius) mean_d += 2.0 * r;
  mean_d /= static_cast<double>(n);
  const double bin = opt.bin > 0.0 ? opt.bin : 2.0 * mean_d;
  const double toe = opt.toe_height > 0.0 ? opt.toe_height : mean_d;
  // Surface heights per (sector, radial bin).
  double rho_max = 0.0;
  for (std::size_t p = 0; p < n; ++p)
    rho_max = std::max(rho_max, std::hypot(position[p].x - axis[0], position[p].y - axis[1]));
  const int bins = static_cast<int>(rho_max / bin) + 1;
  const double none = -std::numeric_limits<double>::infinity();
  std::vector<double> surface(static_cast<std::size_t>(opt.sectors * bins), none);
  std::vector<double> lift(surface.size(), 0.0);  // m, the surface sphere's bottom above the base
  double height = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    const double dx = position[p].x - axis[0], dy = position[p].y - axis[1];
    const double rho = std::hypot(dx, dy);
    double phi = std::atan2(dy, dx) + units::pi;  // [0, 2 pi]
    int s = std::min(opt.sectors - 1, static_cast<int>(phi / (2.0 * units::pi) * opt.sectors));
    int b = static_cast<int>(rho / bin);
    const double top = position[p].z + radius[p] - opt.base_z;
    const auto c = static_cast<std::size_t>(s * bins + b);
    if (top > surface[c]) surface[c] = top, lift[c] = top - 2.0 * radius[p];
    height = std::max(height, top);
  }
  std::vector<double> angles, radii;
  for (int s = 0; s < opt.sectors; ++s) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int count = 0;
    double reach = 0.0;
    // The flank is what lies outward of the sector's highest cell. Cells nearer the axis are a thin wedge
    // holding a few spheres (or the dimple the funnel tube leaves): their "surface" can be low, and fitted
    // as flank points they flattened the line (a real 2,578-sphere pile: 31.9 +- 7.4 deg over sectors
    // before, 36.2 +- 3.7 after).
    int peak = 0;
    for (int b = 1; b < bins; ++b)
      if (surface[static_cast<std::size_t>(s * bins + b)] > surface[static_cast<std::size_t>(s * bins + peak)]) peak = b;
    // The pile ends at its foot: outward of the peak, the first two bins in a row whose surface sphere lies on
    // the base (its bottom within a quarter of the mean diameter of it), or that are empty. A single layer,
    // whatever its spheres' size, is no pile. Beyond lie the apron and the debris: spheres that bounced or
    // rolled off, each a lone surface point of about its own diameter. Counted as flank or reach, they
    // flattened the line and set the sector's diameter: a lone 8 mm sphere half a metre out, and the single
    // layer of 3.35-8 mm spheres strewn 7-17 cm around the 2.9 cm high pile of a 10.5 cm drop (chapter 5's
    // falling-height test: 5.4 deg without a foot, against ~22 deg read off its radial profile).
    const auto low = [&](int b) {
      return b >= bins || surface[static_cast<std::size_t>(s * bins + b)] == none ||
             lift[static_cast<std::size_t>(s * bins + b)] < 0.25 * mean_d;
    };
    int foot = bins;
    for (int b = peak + 1; b < bins; ++b)
      if (low(b) && low(b + 1)) {
        foot = b;
        break;
      }
    for (int b = 0; b < foot; ++b) {
      const double h = surface[static_cast<std::size_t>(s * bins + b)];
      if (h == none) continue;
      const double rho = (b + 0.5) * bin;
      if (h > toe) reach = std::max(reach, (b + 1) * bin);
      if (b <= peak || h < opt.flank_lo * height || h > opt.flank_hi * height) continue;
      sx += rho;
      sy += h;
      sxx += rho * rho;
      sxy += rho * h;
      ++count;
    }
    radii.push_back(reach);
    if (count < 3) continue;
    const double denom = count * sxx - sx * sx;
    if (denom <= 0.0) continue;
    const double slope = (count * sxy - sx * sy) / denom;
    if (slope >= 0.0) continue;  // not a flank: a sector with debris only
    angles.push_back(std::atan(-slope) * 180.0 / units::pi);
  }
  if (angles.size() < 3)
    throw RuntimeFailure(fmt::format(
        "repose angle: only {} of {} sectors have a measurable flank (pile height {:.4f} m); the particles do "
        "not form a pile",
        angles.size(), opt.sectors, height));
  Summary a = summarize(angles), d = summarize(radii);
  ReposeAngle out;
  out.angle_deg = a.mean;
  out.sd_deg = a.sd;
  out.sectors_used = a.n;
  out.height = height;
  out.diameter = 2.0 * d.mean;
  out.method = fmt::format(
      "surface = highest sphere top per ({} sectors x {:.2f} mm radial bins); least-squares flank between {:.0f} "
      "and {:.0f} % of the pile height, outward of the sector's highest cell and inside its foot (two bins in a row whose top sphere lies on the base); "
      "mean over sectors",
      opt.sectors, bin * 1e3, opt.flank_lo * 100, opt.flank_hi * 100);
  return out;
}

}  // namespace pastemix::analysis
