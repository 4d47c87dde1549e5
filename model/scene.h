// SPDX-License-Identifier: MIT
// Scenes: TOML -> Scene (a resolved Plan plus the initial state). The format below is stable: the
// benchmark harness and later issues write scenes in it. All values SI (m, kg, s, Pa).
//
//   seed = 1                       # insertion RNG; recorded in the output
//   time_step = 2e-6               # s
//   end_time = 0.5                 # s
//   [domain]                       # a particle outside this box stops the run (exit 3), or see on_exit
//   min = [-0.2, -0.2, -0.05]      # m
//   max = [0.2, 0.2, 0.6]
//   on_exit = "stop"               # "stop" (default) | "remove": an outflow boundary; a particle that leaves
//                                  # the box is removed and recorded (id, time, mass, radius, material,
//                                  # position, velocity: /escaped in the result), the run goes on. NaN and
//                                  # energy blow-ups still stop it.
//   max_escaped_fraction = 0.05    # "remove" only: the run stops (exit 3) once more than this fraction of
//                                  # the total particle mass has left (many escapes = a blow-up)
//   [physics]                      # optional
//   gravity = [0, 0, -9.81]        # m/s2 (default)
//   rotation = true                # false: spheres do not rotate (no angular arrays)
//   [contact]                      # the laws and their own keys: model/laws/ (registry.h lists them)
//   law = "hertz_mindlin"          # contact law
//   rolling = "constant_torque"    # rolling law, default "none"
//   rolling_damping = 0.3          # a key of the elastic_plastic rolling law (eta_r, default 0.3)
//   [neighbor]
//   skin = 1e-3                    # m, Verlet skin (default: the smallest particle radius)
//   sort_every = 8                 # neighbour rebuilds between spatial sorts of the particle store (the
//                                  # first rebuild sorts; default 8; 0: never; `pastemix run --sort-every`; changes the order of force sums, not the
//                                  # physics; outputs stay in id order): WorldConfig::sort_every
//   [stop]                         # optional: end when the rock is at rest (keys in model/stop_rule.h)
//   rule = "at_rest"  speed = 0.01  moving_mass = 1e-3  check_interval = 0.01  start = 0.1
//   [output]                       # optional
//   interval = 0.01                # s between particle snapshots (default end_time / 20)
//   energy_interval = 0.001        # s between energy / contact-count samples (default interval)
//   checkpoint_interval = 60       # s of simulated time between restart files (model/checkpoint.h; default none)
//   [[material]]
//   name = "rock"  density = 2760  youngs_modulus = 4.68e7  poisson_ratio = 0.19
//   [[interaction]]                # one per pair of materials that can touch (walls included)
//   materials = "rock/rock"        # "a/b", order-free
//   restitution = 0.79  friction = 0.466  rolling_friction = 0.15
//   [initial_state]                # optional: start from a snapshot of an earlier run (a settled bed)
//   file = "settled.h5"            # relative to this scene file
//   snapshot = -1                  # index, -1 = last; materials are matched by name
//   [[particle]]                   # explicit spheres
//   material = "rock"  radius = 0.01  position = [0, 0, 0.1]
//   velocity = [0, 0, 0]  angular_velocity = [0, 0, 0]     # optional
//   [[factory]]                    # fill a region at t = 0 with a PSD, without overlaps
//   material = "rock"  mass = 0.3  # kg of rock
//   shape = "box"  min = [..]  max = [..]                    # or
//   shape = "cylinder"  center = [x, y]  radius = 0.05  z_min = 0  z_max = 0.1   # or
//   shape = "funnel"  wall = "funnel"                        # the cone part of a funnel wall
//   seed = 7                       # optional, default = scene seed + factory index
//   [[factory.psd]]                # sieve intervals (m) and mass fractions (sum 1)
//   d_min = 2.5e-3  d_max = 5e-3  fraction = 1.0
//   [[fluid]]                      # fluid regions (several allowed): keys in model/fluid/fluid_scene.h
//   [[wall]]                       # name, type, material, then the type's keys:
//   type = "plane"     point = [..]  normal = [..]           (normal towards the particles)
//   type = "box"       min = [..]  max = [..]                (open top: floor + 4 sides)
//   type = "cylinder"  center = [x, y]  radius  z_min  z_max
//   type = "cone"      center = [x, y]  z0  r0  z1  r1       (frustum)
//   type = "disk"      center = [x, y, z]  radius            (a plate)
//   type = "funnel"    center = [x, y]  z_exit  exit_diameter  top_diameter  height  tube_length
//   velocity = [0, 0, 0.01]  move_start = 0  move_end = inf  # optional prescribed translation (m/s, s)
//   remove_at = 0.1                                          # optional: the wall vanishes at t (s)
//
// Checks (InputError with file:line): unknown keys; negative or zero radius, modulus, density; restitution
// outside (0, 1]; a material or wall name used but not defined; a pair of materials that can touch without
// an [[interaction]]; an explicit particle overlapping another or a wall, or outside the domain; a wall
// passing through a factory region (e.g. a plate across the fill box); a factory region too small.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "model/fluid/field.h"
#include "model/stop_rule.h"
#include "model/world.h"

namespace pastemix::model {

// What the scene needs the engine to run (STYLE 5.3): passes, arrays, history width.
struct Plan {
  std::string law;                     // contact law (laws/registry.h)
  std::string rolling = "none";        // rolling law (laws/registry.h)
  bool rotation = true;       // angular arrays allocated and integrated
  bool tangential = true;     // some pair has friction -> tangential history
  int history_width = 0;      // doubles per contact
  bool fluid = false;         // some [[fluid]] region at rest (model/fluid/fluid_scene.h); absent -> no fluid arrays or pass
  bool flow = false;          // a dynamics = "flow" region (model/fluid/flow_coupling.h); absent -> no flow pass
};

struct Scene {
  std::string path;           // as given
  std::string text;           // the scene file as read (stored in the output)
  std::uint64_t seed = 1;
  double end_time = 0.0;      // s
  double output_interval = 0.0;  // s
  double energy_interval = 0.0;  // s
  double checkpoint_interval = 0.0;  // s of simulated time between checkpoints (model/checkpoint.h); 0: none
  StopRule stop;              // [stop]: end at rest (model/stop_rule.h); end_time is then the limit
  Plan plan;
  WorldConfig config;
  std::vector<Material> materials;
  std::vector<MaterialPair> pairs;  // n_materials^2, symmetric
  LawTable laws;                    // contact law parameters per material pair
  RollingTable rolling;             // rolling law parameters per material pair
  Particles particles;
  std::vector<Wall> walls;
  std::vector<fluid::FluidRegion> fluid;  // [[fluid]] regions (empty: no fluid pass)
  std::vector<std::string> warnings;      // legal but doubtful settings (a time step near the Rayleigh time)
};

// The loaders (scene/read.cpp): one reader per concept of the format (scene/read.h); editing a scene before
// it is read (--set, --overrides, the studies) goes through SceneDoc (scene_doc.h).
Scene load_scene(const std::filesystem::path& path);
Scene parse_scene(std::string_view text, const std::string& display_path);
World make_world(const Scene& scene);
// s: the smallest Rayleigh time of the scene's spheres, pi r sqrt(rho/G) / (0.8766 + 0.163 nu)
// (../shared/DESIGN.md section 3); inf without spheres.
double smallest_rayleigh_time(const Scene& scene);

}  // namespace pastemix::model
