// SPDX-License-Identifier: MIT
// World: the state of one simulation and its time step, as ordered stages with a per-stage profile.
// See the design essay at the top of world.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "model/contacts.h"
#include "model/fluid/field.h"
#include "model/material.h"
#include "model/particles.h"
#include "model/walls.h"

namespace pastemix::model {

struct CheckpointAccess;

// Wall-clock seconds spent per stage, as seen by thread 0 (the order is the order of the step):
// kick_drift = the first half kick and drift of a batch of steps (World::advance; the later ones are fused
// into walls_kick); neighbor = list rebuilds; contact_forces = the pair pass; walls_kick = the per-particle
// pass (wall forces, closing half kick, next opening half kick and drift) of the particles outside every
// fluid region; fluid = the fluid pass (the field's update, then the fluid kicks and drifts of the particles
// inside a region); wait = thread 0 waiting at the step's barrier for the other threads.
struct Profile {
  enum Stage { kick_drift, neighbor, contact_forces, walls_kick, fluid, wait, output, count };
  static constexpr std::array<const char*, count> names{"kick_drift", "neighbor", "contact_forces", "walls_kick",
                                                        "fluid",      "wait",     "output"};
  std::array<double, count> seconds{};
  long rebuilds = 0;
};

struct Energies {
  double kinetic = 0.0;      // J, translational
  double rotational = 0.0;   // J
  double potential = 0.0;    // J, gravitational, relative to z = 0 (-m g.x)
  double elastic = 0.0;      // J, the contact law's normal springs (Law::elastic_energy); tangential excluded
  long pair_contacts = 0;
  long wall_contacts = 0;
};

// What a particle found outside the domain box does: stops the run with a RuntimeFailure (the default), or
// is removed and recorded (an outflow boundary, as EDEM's and LIGGGHTS's deletion regions): a rock thrown
// over the wall of an open-top box is a physical event, not a blow-up.
enum class ExitRule { stop, remove };

struct WorldConfig {
  double dt = 0.0;                 // s
  Vec3 gravity{0, 0, -9.81};       // m/s2
  double skin = 0.0;               // m, Verlet skin
  Vec3 domain_min, domain_max;     // m, leaving this box stops the run, or removes the particle (on_exit)
  ExitRule on_exit = ExitRule::stop;
  // on_exit = remove: once more than this fraction of the total particle mass (present + escaped) has
  // left, the run stops anyway (many escapes are a blow-up, not a splash).
  double max_escaped_fraction = 0.05;
  // Kinetic energy above this (J) is a blow-up; set by the scene from the energy the particles can have.
  double kinetic_limit = 0.0;
};

// A particle removed at the domain boundary (on_exit = remove).
struct Escape {
  std::int64_t id = 0;
  double time = 0.0;    // s, the time of the drift that took it out of the domain
  double mass = 0.0;    // kg
  double radius = 0.0;  // m
  int material = 0;     // index into the scene's materials
  Vec3 x, v;            // m, m/s: its position (just outside the domain) and half-step velocity then
};

class World {
 public:
  World(WorldConfig config, std::vector<Material> materials, LawTable laws, RollingTable rolling,
        Particles particles, std::vector<Wall> walls, int history_width);

  // Advances one step of velocity Verlet (the first call also evaluates the initial forces).
  void step() { advance(1); }
  // Advances n steps: the same trajectory, bit for bit, as n calls of step(), with fewer passes over
  // memory and fewer thread synchronisations: the closing half kick of a step and the opening half kick and
  // drift of the next one are one per-particle pass (they touch only that particle).
  void advance(long n);
  // Throws RuntimeFailure (particle id, time, cause) if a particle is non-finite, outside the domain,
  // or the kinetic energy exceeds the blow-up limit. Cheap: call every few steps. (With on_exit = remove,
  // advance() has already removed every particle that left the domain.)
  void check() const { check_particles(true); }
  Energies energies() const;

  double time() const { return t_; }
  long steps() const { return steps_; }
  const WorldConfig& config() const { return cfg_; }
  const Particles& particles() const { return p_; }
  Particles& particles() { return p_; }
  const std::vector<Wall>& walls() const { return walls_; }
  const std::vector<Material>& materials() const { return materials_; }
  const PairList& pairs() const { return pairs_; }
  Profile& profile() { return profile_; }
  // --- fluid hook (model/fluid/field.h): null without [[fluid]] -> no fluid pass, nothing to pay. ---
  // The field visits only particles within the Verlet skin of a region (its candidate list, refreshed at
  // every pair-list rebuild): particles far from the paste pay one flag read per step.
  void set_fluid(std::shared_ptr<fluid::FluidField> field) {
    fluid_ = std::move(field);
    if (fluid_) fluid_->set_candidate_margin(cfg_.skin), fluid_->set_step(cfg_.dt, cfg_.gravity);
  }
  const fluid::FluidField* fluid() const { return fluid_.get(); }
  const Profile& profile() const { return profile_; }
  // Particles removed at the domain boundary (on_exit = remove), in the order of removal, and their mass.
  const std::vector<Escape>& escaped() const { return escaped_; }
  double escaped_mass() const { return escaped_mass_; }  // kg

 private:
  friend struct CheckpointAccess;  // model/checkpoint.cpp: saves and restores every member of the state
  void check_particles(bool domain) const;
  [[noreturn]] void fail(std::size_t a, const std::string& cause) const;
  // A drift flagged a particle (bad_index_): check() with on_exit = stop; with remove, the health checks
  // and then remove_escaped(). moved2: the displacement since the last rebuild (reset by a removal).
  void flagged(double& moved2);
  // Removes and records the particles outside the domain, renames the contact histories through the index
  // map and rebuilds the lists (RuntimeFailure past max_escaped_fraction).
  void remove_escaped(double& moved2);
  void rebuild_neighbors();
  // What the per-particle pass after the forces does besides summing them.
  enum class Then { nothing, kick, kick_drift };
  // Force passes in one parallel region, at most `n` of them: per thread, its pair forces, then per owned
  // particle its wall forces, the closing half kick and (Then::kick_drift, all but the n-th pass) the next
  // step's opening half kick and drift; then the one barrier of the step. Stops after a pass that leaves
  // a rebuild due or a particle bad (moved2 = the largest squared displacement since the last rebuild).
  // initial: one pass without kick (the forces at t = 0). Returns the number of passes.
  long passes(long n, double h, bool initial, double& moved2);
  // Whether the lists must be rebuilt at time t, the particles having moved sqrt(moved2) since the last.
  bool rebuild_due(double moved2, double t) const;
  void kick_one(long a, double h, bool rot, bool roll);
  void kick_twice(long a, double h, bool rot, bool roll);
  // Drift of particle a by dt, its domain check and its squared displacement since the last rebuild.
  void drift_one(long a, double& d2, long& first_bad);
  // First half kick and drift; returns the largest squared displacement since the last rebuild (m2).
  double kick_drift(double h);

  WorldConfig cfg_;
  std::vector<Material> materials_;
  LawTable laws_;
  RollingTable rolling_;
  bool kick_friction_ = false;  // the rolling law acts as a friction on omega in the half kick
  Particles p_;
  std::vector<Wall> walls_;
  PairList pairs_;
  WallContacts wall_contacts_;
  std::vector<WallState> wall_state_;  // per thread
  NeighborSearch search_;
  CandidatePairs candidates_;          // the neighbour search's output, kept for its capacity
  // Per thread and step parity: largest squared displacement and first bad particle of its block; padded
  // to a cache line, read by every thread after the step's barrier.
  struct alignas(64) ThreadResult {
    double d2 = 0.0;
    long bad = 0;
  };
  std::vector<ThreadResult> results_[2];
  std::vector<Vec3> x_at_rebuild_;
  Profile profile_;
  double t_ = 0.0;
  double t_at_rebuild_ = 0.0;
  long steps_ = 0;
  bool started_ = false;
  // First problem found during a step (dense index, or -1) and its cause, reported by check().
  mutable long bad_index_ = -1;
  std::shared_ptr<fluid::FluidField> fluid_;  // fluid hook
  std::vector<Escape> escaped_;
  double escaped_mass_ = 0.0;  // kg
};

}  // namespace pastemix::model
