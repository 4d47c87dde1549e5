// SPDX-License-Identifier: MIT
// The state is written as raw bytes of each member, in a fixed order, each vector with its length: the
// doubles go out and come back bit for bit (no text round trip), which is what bit-identical resume needs.
// A checkpoint is for the same build on the same machine kind (a version tag and the sizes of the stored
// structs are checked); it is not an archive format.
#include "model/checkpoint.h"

#include <cstring>
#include <fstream>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include <fmt/format.h>
#include <omp.h>

#include "base/error.h"
#include "base/h5.h"
#include "base/staged_output.h"
#include "model/output.h"
#include "model/parallel.h"
#include "model/state_bytes.h"
#include "model/scene.h"
#include "model/stop_rule.h"
#include "model/world.h"

namespace pastemix::model {

namespace {

// Bumped whenever a stored member is added, removed or reordered.
constexpr char kMagic[] = "pastemix-checkpoint-v6";

// The members in one fixed order, for both directions: io(x) is put(x) or get(x).
template <class IO>
void particles(IO& io, auto& p) {
  io(p.has_rotation), io(p.id), io(p.material), io(p.radius), io(p.mass), io(p.inv_mass), io(p.x), io(p.v);
  io(p.f), io(p.omega), io(p.torque), io(p.inv_inertia), io(p.rolling_capacity);
}

}  // namespace

// Friend of World, FluidField, RestMonitor and RunOutput: the one place that knows their dynamic members.
struct CheckpointAccess {
  template <class IO, class W>
  static void world_state(IO& io, W& w) {
    io(w.t_), io(w.t_at_rebuild_), io(w.steps_), io(w.started_), io(w.escaped_mass_), io(w.profile_);
    io(w.rebuilds_since_sort_);
    particles(io, w.p_);
    auto& q = w.pairs_;
    io(q.width), io(q.i), io(q.j), io(q.r_star), io(q.m_star), io(q.rsum), io(q.law_index), io(q.history), io(q.touching);
    io(q.start), io(q.entry);
    auto& c = w.wall_contacts_;
    io(c.width), io(c.walls), io(c.start), io(c.near), io(c.history), io(c.touching);
    if constexpr (!std::is_const_v<W>) c.list_particles();  // derived from start, not stored
    io(w.x_at_rebuild_), io(w.shift_velocity_), io(w.escaped_);
    auto& field = std::get<FluidForces>(w.forces_).field;
    bool wet = field != nullptr;
    io(wet);
    if (wet != (field != nullptr)) throw std::logic_error("checkpoint: fluid state and scene disagree");
    if (wet) fluid_state(io, *field);
    // The moving paste (dynamics = "flow"): its state as the coupling's own bytes (fluid/flow_coupling.h), after
    // the particles, which its restore() reads.
    auto& flow = std::get<FlowForces>(w.forces_).coupling;
    bool flowing = flow != nullptr;
    io(flowing);
    if (flowing != (flow != nullptr)) throw std::logic_error("checkpoint: flow state and scene disagree");
    if (!flowing) return;
    if constexpr (std::is_const_v<W>) {
      io(flow->save());
    } else {
      std::vector<char> bytes;
      io(bytes);
      flow->restore(bytes, w.p_);
    }
  }
  template <class IO, class F>
  static void fluid_state(IO& io, F& f) {
    io(f.surface_), io(f.region_of_), io(f.v_sub_), io(f.stale_), io(f.candidates_), io(f.members_);
    io(f.surface_at_refresh_), io(f.factor_), io(f.factored_), io(f.since_clusters_), io(f.stats_);
    // The per-particle constants of the kick and the clusters' change test (FluidField, issue 19's fluid-pass
    // speed): without them a resumed run indexed empty arrays (phi_ is filled only where update() runs anew).
    io(f.phi_), io(f.y_), io(f.d0_), io(f.rest_region_), io(f.lin_k_), io(f.lin_decay_), io(f.lin_gain_);
    io(f.pairs_version_), io(f.clustered_version_), io(f.clustered_members_), io(f.clustered_x_);
    io(f.clustered_surface_);
  }
  template <class IO, class R>
  static void rest_state(IO& io, R& r) {
    io(r.passed_), io(r.fired_), io(r.last_step_), io(r.prev_), io(r.known_), io(r.have_prev_);
  }
  template <class IO, class O>
  static void output_state(IO& io, O& o) {
    io(o.snap_times_), io(o.snap_counts_), io(o.t_), io(o.ke_), io(o.rot_), io(o.pot_), io(o.el_), io(o.npair_);
    io(o.nwall_), io(o.surface_), io(o.paste_volume_);
  }
  // The pair list's thread partition is not stored: it is made again from the positions of the last
  // rebuild, for this run's thread count (the engine's bits do not depend on the partition).
  static void after_restore(World& w) {
    w.pairs_.threads = 0;
    w.pairs_.find_uniform_law();  // not stored: from the restored law entries
    w.partition(w.threads_for(static_cast<long>(w.p_.size())), w.x_at_rebuild_);
    w.bad_index_ = -1;
    if (auto& field = std::get<FluidForces>(w.forces_).field) field->restored(w.p_);
  }
  static H5Writer& h5(RunOutput& o) { return *o.h5_; }
  static void replace_h5(RunOutput& o, std::unique_ptr<H5Writer> h5) {
    o.h5_->discard();
    o.h5_ = std::move(h5);
  }
};

namespace {

std::string sizes_tag() {
  return fmt::format("{} Vec3 {} Escape {} Profile {} ClusterStats {}", kMagic, sizeof(Vec3), sizeof(Escape),
                     sizeof(Profile), sizeof(fluid::ClusterStats));
}

std::vector<char> save_state(const World& world, const RestMonitor& rest, const RunOutput& out) {
  StateBytes b;
  auto io = [&](const auto& v) { b.put(v); };
  const std::string tag = sizes_tag();
  b.put(std::vector<char>(tag.begin(), tag.end()));
  CheckpointAccess::world_state(io, world);
  CheckpointAccess::rest_state(io, rest);
  CheckpointAccess::output_state(io, out);
  return b.data();
}

}  // namespace

std::filesystem::path checkpoint_path(const std::filesystem::path& out_dir, const std::string& stem) {
  return out_dir / (stem + ".checkpoint.h5");
}

std::filesystem::path failed_checkpoint_path(const std::filesystem::path& out_dir, const std::string& stem) {
  return out_dir / (stem + ".failed.checkpoint.h5");
}

void write_checkpoint(const std::filesystem::path& path, RunOutput& out, const World& world, const RestMonitor& rest,
                      double wall_seconds, const std::string& resume_with) {
  const std::vector<char> state = save_state(world, rest, out);
  // A copy of the result so far (the run goes on writing the original), with the state added.
  H5Writer ck(path, CheckpointAccess::h5(out).image());
  ck.create_group("/checkpoint");
  ck.write_bytes("/checkpoint/state",
                 std::span(reinterpret_cast<const std::uint8_t*>(state.data()), state.size()));
  ck.attribute("/checkpoint", "time_s", world.time());
  ck.attribute("/checkpoint", "step", static_cast<std::int64_t>(world.steps()));
  ck.attribute("/checkpoint", "wall_seconds", wall_seconds);
  ck.attribute("/checkpoint", "resume_with", resume_with);
  const std::string image = ck.image();
  ck.discard();
  replace_file_atomically(path, image);
}

CheckpointInfo read_checkpoint_info(const std::filesystem::path& path) {
  const H5Reader r(path);
  if (!r.exists("/checkpoint")) throw InputError(path.string(), 0, "", "not a checkpoint (no /checkpoint group)");
  CheckpointInfo info;
  info.step = static_cast<long>(r.attribute_int("/checkpoint", "step"));
  info.time = r.attribute_double("/checkpoint", "time_s");
  info.wall_seconds = r.attribute_double("/checkpoint", "wall_seconds");
  return info;
}

CheckpointInfo resume_from_checkpoint(const std::filesystem::path& path, const Scene& scene, World& world,
                                      RestMonitor& rest, RunOutput& out, const std::filesystem::path& h5_tmp) {
  if (!std::filesystem::exists(path))
    throw InputError(path.string(), 0, "", "no checkpoint to resume (the run finished, or never wrote one: "
                                           "[output] checkpoint_interval or --checkpoint-every)");
  const CheckpointInfo info = read_checkpoint_info(path);
  std::vector<std::uint8_t> state;
  {
    const H5Reader r(path);
    const std::string hash = r.attribute_string("/", "scene_hash"), here = scene_hash(scene.text);
    if (hash != here)
      throw InputError(path.string(), 0, "scene_hash",
                       fmt::format("the checkpoint is of another scene (hash {}, this scene with its --set: {}): "
                                   "resume with the scene and overrides it was started with",
                                   hash, here));
    state = r.read_bytes("/checkpoint/state");
  }
  StateReader rd(state, path.string());
  std::vector<char> tag;
  rd.get(tag);
  if (std::string(tag.begin(), tag.end()) != sizes_tag())
    throw InputError(path.string(), 0, "/checkpoint/state",
                     fmt::format("written by another version of pastemix ({}): start the run again",
                                 std::string(tag.begin(), tag.end())));
  auto io = [&](auto& v) { rd.get(v); };
  CheckpointAccess::world_state(io, world);
  CheckpointAccess::rest_state(io, rest);
  CheckpointAccess::output_state(io, out);
  if (!rd.done()) rd.damaged("bytes left over");
  CheckpointAccess::after_restore(world);
  // The result so far, without the checkpoint's own group, goes on in memory.
  std::string image;
  {
    // One read of the whole file (a character at a time through istreambuf_iterator, case 3's 25 MB
    // checkpoint took 0.18 s of a resumed run's start: perf, session 39).
    std::ifstream in(path, std::ios::binary | std::ios::ate);  // opened at the end: tellg() is the size
    const std::streamsize size = in ? static_cast<std::streamsize>(in.tellg()) : -1;
    if (size >= 0) {
      image.resize(static_cast<std::size_t>(size));
      in.seekg(0).read(image.data(), size);
    }
    if (size < 0 || !in) throw InputError(path.string(), 0, "", "cannot read the checkpoint");
  }
  auto h5 = std::make_unique<H5Writer>(h5_tmp, image);
  h5->remove("/checkpoint");
  CheckpointAccess::replace_h5(out, std::move(h5));
  return info;
}

}  // namespace pastemix::model
