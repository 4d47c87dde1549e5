// SPDX-License-Identifier: MIT
// Internal to the scene loader: one reader per concept of the scene format (model/scene.h lists the keys).
// read_scene (read.cpp) calls them in this order; each reads its own table(s) and fails with the line of the
// key it reads. The order matters: materials before the walls and particles that name them, walls before the
// particles they must not cut, the laws (Plan) before the particle arrays they size.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "base/params.h"
#include "model/insert/fill.h"
#include "model/scene.h"

namespace pastemix::model {

// The scene from its parsed document; `text` is what the run stores (model/scene_doc.h).
Scene read_scene(const Params& root, std::string text);

// Top level and [domain], [physics]: seed, time_step, end_time, the domain box and its exit rule, gravity.
// Returns the [physics] rotation switch.
bool read_domain(const Params& root, Scene& s);

// [[material]]; returns each material's table line (for errors about a missing pair). Needs one at least.
std::vector<int> read_materials(const Params& root, std::vector<Material>& out);
// [[interaction]]: the pair coefficients, both orders.
void read_interactions(const Params& root, Scene& s);

// [[wall]]: each expanded into primitives.
void read_walls(const Params& root, Scene& s);

// Where the particles come from: [initial_state], [[particle]], [[factory]], with their materials.
struct ParticleSources {
  std::optional<Params> initial;
  std::vector<Params> particles, factories;
  std::vector<int> particle_material, factory_material;
  std::set<int> materials;  // every material a particle can have
};
ParticleSources read_particle_sources(const Params& root, const Scene& s);
// The materials the [initial_state] snapshot uses, matched by name (scene/particles.cpp).
std::vector<int> initial_state_materials(const Params& t, const std::string& scene_path,
                                         const std::vector<Material>& mats);
// Every pair of materials that can touch (particle-particle, particle-wall) has an [[interaction]].
void require_interactions(const Scene& s, const std::set<int>& particle_materials,
                          const std::vector<int>& material_line);

// The Plan: the laws of [contact] mix each pair's coefficients; rotation, history width.
void plan_laws(const Params& contact, bool rotation_switch, const std::set<int>& particle_materials, Scene& s);

// The initial state and the explicit spheres, checked against the domain, the walls and each other. Returns
// the smallest radius placed (inf if none).
double read_particles(const ParticleSources& src, Scene& s);
// The factories' fills, in Morton order. Returns the smallest radius placed (inf if none).
double read_factories(const ParticleSources& src, Scene& s);

// Whether a wall surface enters `region` deeper than `margin` (m) (scene/walls.cpp).
bool wall_crosses(const Wall& w, const FillRegion& region, double margin);

// [neighbor], [output], [stop].
void read_output(const Params& root, double r_min, Scene& s);

// The kinetic-energy blow-up limit, and a warning for a time step near the Rayleigh time.
void set_kinetic_limit(Scene& s);
void warn_time_step(Scene& s);

// Small readers the concepts share.
Vec3 vec(const Params& p, std::string_view key);
Vec3 vec_or(const Params& p, std::string_view key, Vec3 fallback);
int material_index(const Params& p, std::string_view key, const std::vector<Material>& mats);
bool inside(const Vec3& p, const Vec3& lo, const Vec3& hi);

}  // namespace pastemix::model
