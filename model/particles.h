// SPDX-License-Identifier: MIT
// Particles: structure-of-arrays storage for spheres.
//
// One vector per quantity, indexed by a dense index. Particles are inserted before the run starts and are
// never removed (a particle that leaves the domain stops the run with a RuntimeFailure), so the stable id
// of a particle is its insertion order and equals its dense index; `id` is still stored so outputs and
// contact-history keys never depend on that coincidence.
//
// Angular arrays (omega, torque, inv_inertia, rolling capacity) are allocated only when the Plan says a
// law produces torque (`has_rotation`); with them absent the integrator skips rotation entirely.
#pragma once

#include <cstdint>
#include <vector>

#include "model/vec3.h"

namespace pastemix::model {

struct Particles {
  bool has_rotation = false;

  std::vector<std::int64_t> id;
  std::vector<int> material;       // index into the scene's materials
  std::vector<double> radius;      // m
  std::vector<double> mass;        // kg
  std::vector<double> inv_mass;    // 1/kg
  std::vector<Vec3> x;             // m, centre position
  std::vector<Vec3> v;             // m/s
  std::vector<Vec3> f;             // N, total force of the current step (without gravity)
  // Rotation (allocated only if has_rotation).
  std::vector<Vec3> omega;         // rad/s
  std::vector<Vec3> torque;        // N.m
  std::vector<double> inv_inertia; // 1/(kg.m2), solid sphere I = 2/5 m r^2
  // Sum over contacts of the constant-directional rolling torque magnitudes (N.m), applied by the
  // integrator as an implicit, non-reversing friction on omega (see integrate.h).
  std::vector<double> rolling_capacity;

  std::size_t size() const { return x.size(); }
  // Appends one sphere at rest; density in kg/m3.
  void add(int material_index, double radius_m, double density, const Vec3& position, const Vec3& velocity,
           const Vec3& angular_velocity);
  // Allocates the angular arrays (call once, after the Plan is known, before adding particles).
  void enable_rotation() { has_rotation = true; }
};

}  // namespace pastemix::model
