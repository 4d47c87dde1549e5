// SPDX-License-Identifier: MIT
#include "app/study/qoi.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "analysis/pile/repose_angle.h"
#include "base/error.h"

namespace pastemix::app::study {
namespace {

using model::World;

// Largest sphere-sphere overlap (m) among the current pair list.
double max_overlap(const World& w) {
  const auto& pl = w.pairs();
  const auto& p = w.particles();
  double m = 0.0;
  for (std::size_t k = 0; k < pl.size(); ++k) {
    const auto a = pl.i[k], b = pl.j[k];
    m = std::max(m, p.radius[a] + p.radius[b] - norm(p.x[a] - p.x[b]));
  }
  return m;
}

// Largest net contact force (N) on one sphere, as the engine computed it this step (gravity excluded).
// For the two-sphere impact this is the contact force itself. (The per-pair force slots are not used: the
// serial pair pass adds forces straight into the particles and leaves them stale.)
double peak_force(const World& w) {
  const auto& p = w.particles();
  double m = 0.0;
  for (std::size_t a = 0; a < p.size(); ++a) m = std::max(m, norm(p.f[a]));
  return m;
}

double kinetic_energy(const World& w) { return w.energies().kinetic; }

// Highest sphere top (m).
double top_height(const World& w) {
  const auto& p = w.particles();
  double m = -1e300;
  for (std::size_t a = 0; a < p.size(); ++a) m = std::max(m, p.x[a].z + p.radius[a]);
  return m;
}

// A repose angle is only a measurement of a finished pile: every sphere has left the funnel (or lifted
// cylinder) and the pile is at rest. A sphere whose centre is inside an active surface of revolution (above
// its lowest rim, within its largest radius) is still in the funnel; more than 1 % of the spheres faster than
// 0.05 m/s (5x the lift speed) means the pile is still flowing. Either is a failure, never an angle.
void check_pile_finished(const World& w) {
  const auto& p = w.particles();
  for (const auto& wall : w.walls()) {
    if (wall.kind != model::WallKind::revolution || !wall.active(w.time())) continue;
    const model::Vec3 o = wall.origin + wall.displacement(w.time());
    const double z_lo = o.z + std::min(wall.z0, wall.z1), r_hi = std::max(wall.r0, wall.r1);
    std::size_t inside = 0;
    for (std::size_t a = 0; a < p.size(); ++a) {
      const double dx = p.x[a].x - o.x, dy = p.x[a].y - o.y;
      if (p.x[a].z > z_lo && dx * dx + dy * dy < r_hi * r_hi) ++inside;
    }
    if (inside > 0)
      throw RuntimeFailure(fmt::format("repose angle: {} of {} spheres are still inside wall '{}' at t = {:g} s "
                                       "(its lower rim at z = {:.4f} m): the pile is not finished; run longer",
                                       inside, p.size(), wall.name, w.time(), z_lo));
  }
  std::size_t moving = 0;
  for (std::size_t a = 0; a < p.size(); ++a)
    if (norm2(p.v[a]) > 0.05 * 0.05) ++moving;
  if (moving * 100 > p.size())
    throw RuntimeFailure(fmt::format("repose angle: {} of {} spheres still move faster than 0.05 m/s at t = {:g} s: "
                                     "the pile is not at rest; run longer",
                                     moving, p.size(), w.time()));
}

// analysis/pile/repose_angle.h on the final state, pile axis = mass centre, base z = 0 (the floor).
double repose_angle(const World& w) {
  check_pile_finished(w);
  const auto& p = w.particles();
  return analysis::measure_repose_angle(p.x, p.radius).angle_deg;
}

}  // namespace

const std::vector<QoiDef>& qoi_registry() {
  static const std::vector<QoiDef> r = {
      {"max_overlap", "m", "largest sphere-sphere overlap over the run", true, max_overlap},
      {"peak_force", "N", "largest net contact force on one sphere over the run (two spheres: the contact force)", true, peak_force},
      {"max_kinetic_energy", "J", "largest total translational kinetic energy over the run", true, kinetic_energy},
      {"final_height", "m", "highest sphere top at the end", false, top_height},
      {"repose_angle", "deg", "measure_repose_angle on the final state (axis = mass centre, base z = 0)", false,
       repose_angle},
  };
  return r;
}

const QoiDef& find_qoi(const std::string& name) {
  std::string names;
  for (const auto& q : qoi_registry()) {
    if (q.name == name) return q;
    names += (names.empty() ? "" : ", ") + q.name;
  }
  throw InputError("", 0, "--qoi", "unknown quantity '" + name + "' (one of: " + names + ")");
}

}  // namespace pastemix::app::study
