// SPDX-License-Identifier: MIT
// Particles: structure-of-arrays storage for spheres.
//
// One vector per quantity, indexed by a dense index. Particles are inserted before the run starts; the id
// of a particle is its insertion order. With [domain] on_exit = "stop" (the default) none is ever removed,
// so id equals the dense index; with on_exit = "remove" a particle that leaves the domain is removed by
// World (remove_if compacts every array, order kept), the later dense indices shift down and only `id`
// still names the particle (outputs write it; contact histories are remapped by World, see world.cpp).
// With [neighbor] sort_every > 0 the World also permutes the store into the cell order of the neighbour
// grid at rebuilds (apply_map): then the dense order is spatial, not the id order, and the outputs write
// the particles sorted by id (output.cpp), so the files keep their layout.
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
  // integrator as an implicit, non-reversing friction on omega (the half kicks in world.cpp; laws/rolling.h).
  std::vector<double> rolling_capacity;

  std::size_t size() const { return x.size(); }
  // Appends one sphere at rest; density in kg/m3.
  void add(int material_index, double radius_m, double density, const Vec3& position, const Vec3& velocity,
           const Vec3& angular_velocity);
  // Allocates the angular arrays (call once, after the Plan is known, before adding particles).
  void enable_rotation() { has_rotation = true; }
  // Removes the particles with gone[a] != 0 from every array (rotation arrays included), keeping the order
  // of the others; returns the old -> new dense index map (kGone for a removed particle).
  static constexpr std::uint32_t kGone = 0xffffffffu;
  std::vector<std::uint32_t> remove_if(const std::vector<char>& gone);
  // Moves every particle a to dense index map[a] in every array (rotation arrays included), dropping those
  // with map[a] == kGone; count: the new size. map is injective on the kept particles and onto 0 .. count-1
  // (remove_if's compaction, or World's spatial sort at rebuilds: a permutation). `id` moves with the rest.
  void apply_map(const std::vector<std::uint32_t>& map, std::size_t count);
};

}  // namespace pastemix::model
