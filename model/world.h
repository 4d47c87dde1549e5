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
#include "model/forces/registry.h"
#include "model/material.h"
#include "model/motion.h"
#include "model/parallel.h"
#include "model/particles.h"
#include "model/profile.h"
#include "model/walls.h"

namespace pastemix::model {

struct CheckpointAccess;

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
  // Loops over fewer particles (or pairs) than this run on one thread (model/parallel.h); the bits do not
  // depend on it. Tests set 0 to run the parallel paths on small scenes.
  long parallel_min_items = 512;
  // Spatial sort of the particle store ([neighbor] sort_every): every sort_every-th neighbour rebuild (the
  // first included) permutes the particles into the cell order of a grid over their bounding box, so that a
  // particle's partners lie near it in memory; 0: never (the particles stay in insertion order). Changes
  // the order of sums (forces, surface rise), so the bits, not the physics.
  long sort_every = 0;
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

// The load balance's step: each thread's speed is the cost of its slab (work, the partition's units) over
// its busy time (s); the shares of the cost move halfway from `share` towards the speeds' shares, within
// 0.5 .. 1.5 of an equal share (one slow stretch cannot starve a thread), summing to 1. Unchanged when no
// time was measured.
std::vector<double> balanced_shares(const std::vector<double>& share, const std::vector<double>& work,
                                    const std::vector<double>& busy);

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
  // --- the fluid pass (forces/fluid_forces.h): null without [[fluid]] -> no fluid pass, nothing to pay. ---
  // The field visits only particles within the Verlet skin of a region (its candidate list, refreshed at
  // every pair-list rebuild): particles far from the paste pay one flag read per step.
  void set_fluid(std::shared_ptr<fluid::FluidField> field) {
    auto& f = std::get<FluidForces>(forces_).field;
    f = std::move(field);
    // Margin 2 skin: the rebuild test keeps every particle's move below the skin (rebuild_due), the field's
    // list needs it below half its margin.
    if (f) f->set_candidate_margin(2.0 * cfg_.skin), f->set_step(cfg_.dt, cfg_.gravity);
  }
  const fluid::FluidField* fluid() const { return std::get<FluidForces>(forces_).field.get(); }
  // --- the moving paste's pass (forces/flow_forces.h): null without a dynamics = "flow" region. ---
  void set_flow(std::shared_ptr<fluid::FlowCoupling> coupling) { std::get<FlowForces>(forces_).coupling = std::move(coupling); }
  const fluid::FlowCoupling* flow() const { return std::get<FlowForces>(forces_).coupling.get(); }
  const Profile& profile() const { return profile_; }
  // The threads' shares of the partition's cost (empty before the first multi-thread partition). They
  // follow the measured speed of each thread (a core shared with another process, or slower memory, gets
  // less); fix_thread_shares() fixes them (tests: any shares give the same bits).
  const std::vector<double>& thread_shares() const { return share_; }
  void fix_thread_shares(std::vector<double> shares) { share_ = std::move(shares), balance_ = false; }
  // Particles removed at the domain boundary (on_exit = remove), in the order of removal, and their mass.
  const std::vector<Escape>& escaped() const { return escaped_; }
  double escaped_mass() const { return escaped_mass_; }  // kg

 private:
  friend struct CheckpointAccess;  // model/checkpoint.cpp: saves and restores every member of the state
  void check_particles(bool domain) const;
  [[noreturn]] void fail(std::size_t a, const std::string& cause) const;
  // A drift flagged a particle (bad_index_): check() with on_exit = stop; with remove, the health checks
  // and then remove_escaped(). moved: the displacements since the last rebuild (reset by a removal).
  void flagged(Motion& moved);
  // Removes and records the particles outside the domain, renames the contact histories through the index
  // map and rebuilds the lists (RuntimeFailure past max_escaped_fraction).
  void remove_escaped(Motion& moved);
  void rebuild_neighbors();
  void rebuild_lists(int threads);
  // pairs_.partition with the passes' own cost per particle (partition_cost(a), where a pass has one).
  void partition(int threads, const std::vector<Vec3>& x, const std::array<double, 6>* box = nullptr);
  void update_shares(int threads);
  bool imbalanced(int threads) const;
  std::vector<double> pass_cost_;
  // The spatial sort (WorldConfig::sort_every): the permutation old -> new of the cell order, then every
  // per-particle array and list moved through it (Particles::apply_map, PairList / WallContacts::rename,
  // the passes' particles_moved). Serial and a function of the positions only: the same for any threads.
  void sort_particles();
  std::vector<std::uint32_t> cell_order() const;
  // The sort's axes, fastest .. slowest, from `axis` (by extent): the slowest the one the threads' slabs
  // cut across best (world_sort.cpp).
  std::array<int, 3> slab_axes(std::array<int, 3> axis) const;
  // The threads of a loop over n items (WorldConfig::parallel_min_items).
  int threads_for(long n) const;
  // What the kick of a pass does after the forces.
  enum class Then { nothing, kick, kick_drift };
  // Force passes in one parallel region, at most `n` of them: per thread, one step() of its particles, then
  // (Then::kick_drift, all but the n-th pass) the one barrier of the step. Stops after a pass that leaves
  // a rebuild due or a particle bad (moved: the displacements since the last rebuild, model/motion.h).
  // initial: one pass without kick (the forces at t = 0). Returns the number of passes.
  long passes(long n, double h, bool initial, Motion& moved);
  struct Lane;  // one thread's part of passes() (world.cpp)
  struct Batch;  // what passes() hands its threads and gets back
  template <class Law, class Roll>
  void run_lane(const std::vector<typename Law::Params>& laws, const std::vector<typename Roll::Params>& rolling,
                Batch& batch);
  // One step of thread lane.me: the passes' prepare(), the pair pass, the force passes, the plain kicks of
  // the unclaimed particles, the kick passes; each timed on its profile line (thread 0).
  template <class Law, class Roll>
  void step_lane(const PassStep<Law, Roll>& s, Lane& lane, Then then, double h);
  // The closing half kick of particle a (and the next opening half kick and drift, Then::kick_drift).
  // Returns its displacement since the last rebuild (m; 0 without a drift).
  Vec3 close_kick(Lane& lane, long a, Then then, double h);
  // The force passes and close_kick(Then::kick_drift) of every particle of the lane with rotation, in blocks
  // (a kick pass's particles' velocities by the pass).
  template <class Law, class Roll>
  void close_kicks_blocked(const PassStep<Law, Roll>& s, Lane& lane, double h);
  template <class Law, class Roll>
  void add_force_passes(const PassStep<Law, Roll>& s, const long* idx, int m);
  void publish_ghost(const Lane& lane, long a);
  // Whether the lists must be rebuilt at time t, the particles having moved `moved` since the last.
  bool rebuild_due(const Motion& moved, double t) const;
  // The common displacement (m) the rebuild test measures the particles against at time t (model/motion.h).
  Vec3 common_shift(double t) const { return shift_velocity_ * (t - t_at_rebuild_); }
  // At a rebuild: shift_velocity_ from the particles' velocities.
  void set_shift_velocity();
  // Whether the next step's drifts are measured against the common displacement too (Lane::refine).
  bool refine_moves(const Motion& moved) const;
  void kick_one(long a, double h, bool rot, bool roll);
  void kick_twice(long a, double h, bool rot, bool roll);
  bool kick8_by_pass(long a0, double h);
  void kick_claimed_twice(long a, double h);
  void kick_velocity_twice(long a, double h);
  // Drift of particle a by dt and its domain check; returns its displacement since the last rebuild (m).
  Vec3 drift_one(long a, long& first_bad);
  // First half kick and drift; returns the displacements since the last rebuild.
  Motion kick_drift(double h);

  WorldConfig cfg_;
  std::vector<Material> materials_;
  LawTable laws_;
  RollingTable rolling_;
  bool kick_friction_ = false;  // the rolling law acts as a friction on omega in the half kick
  Particles p_;
  std::vector<Wall> walls_;
  PairList pairs_;
  WallContacts wall_contacts_;
  ForcePasses forces_;  // forces/registry.h: gravity, walls, fluid
  Vec3 accel_;          // m/s2, the passes' body acceleration (gravity)
  NeighborSearch search_;
  CandidatePairs candidates_;          // the neighbour search's output, kept for its capacity
  // Per thread and step parity: the displacements and first bad particle of its block; padded to a cache
  // line, read by every thread after the step's barrier.
  struct alignas(64) ThreadResult {
    Motion moved;
    long bad = 0;
  };
  std::vector<ThreadResult> results_[2];
  YieldBarrier step_barrier_;  // run_lane's barrier between the steps of a batch
  // The load balance of the threads (partition()): each thread's busy time (s, its steps' work without the
  // waits at the step barriers) since the last partition, and each thread's share of the partition's cost.
  struct alignas(64) Busy {
    double s = 0.0;
  };
  std::vector<Busy> busy_;
  std::vector<double> share_;
  bool balance_ = true;  // adapt share_ to the measured speeds (false: fixed shares, fix_thread_shares)
  std::vector<Vec3> x_at_rebuild_;
  Profile profile_;
  double t_ = 0.0;
  double t_at_rebuild_ = 0.0;
  // m/s: the velocity of the rebuild test's common displacement (model/motion.h): at each rebuild, the
  // mean velocity of the particles at least half as fast as the fastest (a falling stream's).
  Vec3 shift_velocity_;
  long steps_ = 0;
  long rebuilds_since_sort_ = 0;  // neighbour rebuilds since the last spatial sort (sort_every)
  bool started_ = false;
  // First problem found during a step (dense index, or -1) and its cause, reported by check().
  mutable long bad_index_ = -1;
  std::vector<Escape> escaped_;
  double escaped_mass_ = 0.0;  // kg
};

}  // namespace pastemix::model
