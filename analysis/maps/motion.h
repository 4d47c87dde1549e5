// SPDX-License-Identifier: MIT
// Is a result's state at rest? The lab cut its specimens after they hardened, so a map of a pour that is still
// falling scores a state that never existed. `pastemix maps` and `score` refuse such a state (exit 2) unless
// --allow-moving asks for an explicit look at it, and then mark it in every output.
//
// The definitions are those of the engine's [stop] rule (model/stop_rule.h), recomputed from the snapshot's
// velocities, or from its mean speeds where the run's rule measured by displacement (`mean_speed`): a particle
// is moving when faster than `speed`; moving mass above `mass_limit` = not at rest;
// "in flight" = moving with the centre above the final paste surface (falling, or rolling on the pile).
#pragma once

#include <cstddef>
#include <string>

#include "analysis/maps/result_file.h"

namespace pastemix::analysis {

struct MotionLimits {
  double speed = 0.01;        // m/s
  double mass_limit = 1e-3;   // kg (1 g of a 1 kg pour)
};

struct Motion {
  bool known = false;          // the snapshot has velocities
  bool mean = false;           // judged on the snapshot's mean speeds (the displacement measure)
  double moving_mass = 0.0;    // kg
  double in_flight_mass = 0.0; // kg
  std::size_t moving_count = 0;
  double max_speed = 0.0;      // m/s
  MotionLimits limits;
  bool at_rest() const { return known && moving_mass <= limits.mass_limit; }
  std::string line(const ResultSnapshot& r) const;      // "state at t = 2 s: 146 g moving ..."
  std::string refusal(const ResultSnapshot& r) const;   // the exit-2 message with the way out
};

// What the outputs record of a state's motion (maps.h5 root attributes, score.toml [state]).
struct StateMark {
  bool at_rest = true;        // false: an unfinished state mapped with --allow-moving
  bool known = true;          // the snapshot had velocities
  double moving_mass = 0.0, in_flight_mass = 0.0, max_speed = 0.0;  // kg, kg, m/s
  double speed_limit = 0.01, mass_limit = 1e-3;                     // m/s, kg
};

Motion motion_of(const ResultSnapshot& r, const MotionLimits& limits);

}  // namespace pastemix::analysis
