// SPDX-License-Identifier: MIT
// Pours that end at rest: the [stop] table of a scene and the motion census it is judged on.
//
//   [stop]
//   rule = "at_rest"        # "end_time" (default: run to end_time) | "at_rest": end when the rock has settled;
//                           # end_time is then the safety limit (reaching it first is a warning, and in a study
//                           # a failed point)
//   speed = 0.01            # m/s: a particle faster than this is moving (the lab's specimens hardened at rest)
//   paste_speed = 0.01      # m/s: the same for a particle whose centre is in a [[fluid]] region below its
//                           # surface (a rock creeping in the paste); default = speed
//   moving_mass = 1e-3      # kg: the run ends once the moving mass is at most this (1 g of a 1 kg pour)
//   check_interval = 0.01   # s of simulated time between two checks
//   start = 0.1             # s: no check before (the rock rests in the closed funnel at t = 0)
//   hold = 2                # consecutive checks that must pass (a pause in the stream is not the end)
//   measure = "velocity"    # a particle's speed at a check: "velocity" (its velocity then) | "displacement"
//                           # (|x(t) - x(t - check_interval)| / check_interval: its mean speed over the interval)
//
// Why "displacement": with the paste moving (dynamics = "flow") a rock can oscillate in place, phase-locked to the
// coupling cycle, so its velocity at every check (a whole number of cycles apart) is the same non-zero value while
// it goes nowhere (case 7, 2026-12-04: 13-25 g of rock at 1-3 cm/s at every check from 3 to 4.2 s, moving 20 um
// per 0.1 s). Its mean speed over the interval sees the settling and not the oscillation. The first check after
// `start` only records the positions (it cannot pass); a particle without a position at the previous check (new)
// is moving. The final snapshot of such a run carries each particle's mean speed (`mean_speed`), which the maps'
// census (analysis/maps/motion.h) then uses instead of the velocities.
//
// The census (`census`) is also what `pastemix maps` / `score` recompute from a snapshot's velocities to
// refuse a state that is not at rest (analysis/maps/motion.h), with the same definitions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "model/vec3.h"

namespace pastemix {
class Params;
}

namespace pastemix::model {

class World;
struct CheckpointAccess;

enum class RestMeasure { velocity, displacement };

struct StopRule {
  bool at_rest = false;        // false: the run ends at end_time
  double speed = 0.01;         // m/s
  double paste_speed = 0.01;   // m/s
  double moving_mass = 1e-3;   // kg
  double check_interval = 0.01;  // s
  double start = 0.0;          // s
  int hold = 2;                // consecutive passing checks
  RestMeasure measure = RestMeasure::velocity;
};

// Reads the optional [stop] table of a scene (InputError with file:line for a bad value).
StopRule parse_stop_rule(const Params& root);

struct MotionCensus {
  double total_mass = 0.0;      // kg, particles in the world
  double moving_mass = 0.0;     // kg, faster than the rule's speed (paste_speed in the paste)
  double in_flight_mass = 0.0;  // kg, moving with the centre above every fluid surface (falling, rolling)
  std::size_t moving_count = 0;
  double max_speed = 0.0;       // m/s, of any particle
  bool settled(const StopRule& r) const { return moving_mass <= r.moving_mass; }
};

// speeds: each particle's speed in storage order (the displacement measure's mean speeds); null: |v|.
MotionCensus census(const World& w, const StopRule& rule, const std::vector<double>* speeds = nullptr);

// The rule as the step loop sees it: `every()` steps between checks; `check(w, step)` after a batch of steps
// ending at a multiple of every() returns true once the rule has fired. With rule "end_time" it never fires.
class RestMonitor {
 public:
  RestMonitor(const StopRule& rule, double dt, long total_steps);
  long every() const { return every_; }
  bool check(const World& w, long step);
  bool fired() const { return fired_; }
  // The displacement measure's mean speeds (storage order, +inf for a particle without an earlier position)
  // when its last check was at `step`; null otherwise (the velocity measure, or no check at that step).
  const std::vector<double>* mean_speeds(const World& w, long step) const;

 private:
  friend struct CheckpointAccess;  // model/checkpoint.cpp
  StopRule rule_;
  double dt_;
  long every_;
  int passed_ = 0;
  bool fired_ = false;
  long last_step_ = -1;
  // The displacement measure: positions at the previous check by particle id (known_[id] = 1 where recorded).
  std::vector<Vec3> prev_;
  std::vector<std::uint8_t> known_;
  bool have_prev_ = false;
  std::vector<double> speeds_;  // storage order, the last check's (not in the checkpoint: remade by a check)
  std::vector<double> displacement_speeds(const World& w) const;
  void record(const World& w);
};

// What the run ended on: "at rest at t = 1.23 s" or "end_time reached before rest".
struct StopOutcome {
  bool rule_at_rest = false;   // the scene asked for the at-rest rule
  bool fired = false;          // the rule ended the run before end_time
  double start = 0.0;          // s, the rule's start (a run shorter than it cannot fire)
  double time = 0.0;           // s, the end of the run
  MotionCensus last;           // census at the end of the run
  std::string line() const;    // one line for `pastemix run` (a warning when the rule did not fire)
};

}  // namespace pastemix::model
