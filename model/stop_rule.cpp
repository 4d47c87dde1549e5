// SPDX-License-Identifier: MIT
#include "model/stop_rule.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "base/params.h"
#include "model/world.h"

namespace pastemix::model {

StopRule parse_stop_rule(const Params& root) {
  StopRule r;
  const auto t = root.optional_table("stop");
  if (!t) return r;
  r.at_rest = t->choice_or("rule", {"end_time", "at_rest"}, "end_time") == "at_rest";
  r.speed = t->number_or("speed", r.speed, Range::positive);
  r.paste_speed = t->number_or("paste_speed", r.speed, Range::positive);
  r.moving_mass = t->number_or("moving_mass", r.moving_mass, Range::non_negative);
  r.check_interval = t->number_or("check_interval", r.check_interval, Range::positive);
  r.start = t->number_or("start", 0.0, Range::non_negative);
  const long hold = t->integer_or("hold", r.hold);
  if (hold < 1 || hold > 1000) t->fail("hold", fmt::format("must be 1..1000 consecutive checks, got {}", hold));
  r.hold = static_cast<int>(hold);
  r.measure = t->choice_or("measure", {"velocity", "displacement"}, "velocity") == "displacement"
                  ? RestMeasure::displacement
                  : RestMeasure::velocity;
  // start >= end_time is allowed (a shortened look with --set end_time=...): the run then ends at end_time
  // with the not-at-rest warning.
  if (!r.at_rest)
    for (const char* k : {"speed", "paste_speed", "moving_mass", "check_interval", "start", "hold", "measure"})
      if (t->has(k)) t->fail(k, "only with rule = \"at_rest\"");
  return r;
}

MotionCensus census(const World& w, const StopRule& rule, const std::vector<double>* speeds) {
  MotionCensus c;
  const Particles& p = w.particles();
  const fluid::FluidField* f = w.fluid();
  for (std::size_t a = 0; a < p.size(); ++a) {
    const double m = p.mass[a];
    const Vec3& x = p.x[a];
    const double speed = speeds ? (*speeds)[a] : std::sqrt(norm2(p.v[a]));
    c.total_mass += m;
    c.max_speed = std::max(c.max_speed, speed);
    // Submerged: centre inside a region's box, below its current surface.
    bool submerged = false;
    if (f)
      for (std::size_t k = 0; k < f->regions().size() && !submerged; ++k) {
        const auto& reg = f->regions()[k];
        submerged = reg.contains_xy(x.x, x.y) && x.z >= reg.z_bottom && x.z <= f->surface_z(k);
      }
    if (speed <= (submerged ? rule.paste_speed : rule.speed)) continue;
    c.moving_mass += m;
    ++c.moving_count;
    if (!submerged) c.in_flight_mass += m;
  }
  return c;
}

RestMonitor::RestMonitor(const StopRule& rule, double dt, long total_steps)
    : rule_(rule), dt_(dt), every_(rule.at_rest ? std::max(1L, std::lround(rule.check_interval / dt)) : total_steps + 1) {}

bool RestMonitor::check(const World& w, long step) {
  if (!rule_.at_rest || fired_ || step % every_ != 0 || w.time() < rule_.start - 0.5 * dt_) return fired_;
  last_step_ = step;
  if (rule_.measure == RestMeasure::velocity) {
    passed_ = census(w, rule_).settled(rule_) ? passed_ + 1 : 0;
  } else {
    // The first check only records where the particles are: a mean speed needs two.
    const bool first = !have_prev_;
    speeds_ = displacement_speeds(w);
    record(w);
    passed_ = !first && census(w, rule_, &speeds_).settled(rule_) ? passed_ + 1 : 0;
  }
  fired_ = passed_ >= rule_.hold;
  return fired_;
}

// |x - x_prev| / (every_ dt) per particle in storage order; +infinity (moving) for a particle not recorded then.
std::vector<double> RestMonitor::displacement_speeds(const World& w) const {
  const Particles& p = w.particles();
  const double interval = static_cast<double>(every_) * dt_;
  std::vector<double> s(p.size(), std::numeric_limits<double>::infinity());
  if (!have_prev_) return s;
  for (std::size_t a = 0; a < p.size(); ++a) {
    const auto id = static_cast<std::size_t>(p.id[a]);
    if (id < known_.size() && known_[id]) s[a] = std::sqrt(norm2(p.x[a] - prev_[id])) / interval;
  }
  return s;
}

void RestMonitor::record(const World& w) {
  const Particles& p = w.particles();
  std::size_t n = 0;
  for (const auto id : p.id) n = std::max(n, static_cast<std::size_t>(id) + 1);
  prev_.assign(n, Vec3{});
  known_.assign(n, 0);
  for (std::size_t a = 0; a < p.size(); ++a) {
    const auto id = static_cast<std::size_t>(p.id[a]);
    prev_[id] = p.x[a];
    known_[id] = 1;
  }
  have_prev_ = true;
}

const std::vector<double>* RestMonitor::mean_speeds(const World& w, long step) const {
  const bool fresh = rule_.measure == RestMeasure::displacement && last_step_ == step;
  return fresh && speeds_.size() == w.particles().size() ? &speeds_ : nullptr;
}

std::string StopOutcome::line() const {
  const std::string moving =
      fmt::format("{:.4g} g moving ({} particles, {:.4g} g of it above the paste), max speed {:.3g} m/s",
                  1e3 * last.moving_mass, last.moving_count, 1e3 * last.in_flight_mass, last.max_speed);
  if (!rule_at_rest) return fmt::format("stop: end_time {:g} s (no [stop] rule); {}\n", time, moving);
  if (fired) return fmt::format("stop: at rest at t = {:.4g} s; {}\n", time, moving);
  if (last.moving_mass <= 0.0 || time < start)
    return fmt::format("WARNING: end_time {:g} s reached before the [stop] rule could fire (it checks from t = {:g} s "
                       "on): {}. Not a finished pour\n",
                       time, start, moving);
  return fmt::format("WARNING: end_time {:g} s reached before the rock came to rest: {}. Raise end_time or check the "
                     "scene; the maps will refuse this state\n",
                     time, moving);
}

}  // namespace pastemix::model
