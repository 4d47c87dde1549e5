// SPDX-License-Identifier: MIT
#include "analysis/maps/motion.h"

#include <cmath>

#include <fmt/format.h>

#include "base/units.h"

namespace pastemix::analysis {

Motion motion_of(const ResultSnapshot& r, const MotionLimits& limits) {
  Motion m;
  m.limits = limits;
  m.mean = !r.mean_speed.empty();
  m.known = m.mean || !r.velocity.empty();
  const std::size_t n = m.mean ? r.mean_speed.size() : r.velocity.size();
  for (std::size_t p = 0; p < n; ++p) {
    const double speed = m.mean ? r.mean_speed[p] : norm(r.velocity[p]);
    m.max_speed = std::max(m.max_speed, speed);
    if (speed <= limits.speed) continue;
    const double mass = r.density[p] * 4.0 / 3.0 * units::pi * r.radius[p] * r.radius[p] * r.radius[p];
    m.moving_mass += mass;
    ++m.moving_count;
    if (r.position[p].z > r.surface_z.value) m.in_flight_mass += mass;
  }
  return m;
}

std::string Motion::line(const ResultSnapshot& r) const {
  if (!known) return fmt::format("state at t = {:g} s: unknown (the snapshot has no velocities)\n", r.time_s);
  return fmt::format("state at t = {:g} s: {} ({:.4g} g of rock moving faster than {:g} m/s in {} particles, "
                     "{:.4g} g of it in flight above the paste surface; max speed {:.3g} m/s; limit {:g} g){}\n",
                     r.time_s, at_rest() ? "at rest" : "NOT AT REST", 1e3 * moving_mass, limits.speed, moving_count,
                     1e3 * in_flight_mass, max_speed, 1e3 * limits.mass_limit,
                     mean ? "; speeds: the mean over the stop rule's last check interval (mean_speed)" : "");
}

std::string Motion::refusal(const ResultSnapshot& r) const {
  const std::string what =
      known ? fmt::format("the state at t = {:g} s is not at rest: {:.4g} g of rock moving faster than {:g} m/s ({} "
                          "particles, max {:.3g} m/s), {:.4g} g of it in flight above the paste surface (limit {:g} g)",
                          r.time_s, 1e3 * moving_mass, limits.speed, moving_count, max_speed, 1e3 * in_flight_mass,
                          1e3 * limits.mass_limit)
            : fmt::format("the snapshot at t = {:g} s has no velocities, so whether it is at rest is unknown", r.time_s);
  return what + ". Run the scene to rest ([stop] rule = \"at_rest\", model/stop_rule.h) or pass --allow-moving for an "
                "explicit look at an unfinished state (marked as such in every output)";
}

}  // namespace pastemix::analysis
