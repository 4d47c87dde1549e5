// SPDX-License-Identifier: MIT
// Checkpoint and resume of `pastemix run` (issue 20).
//
//   [output] checkpoint_interval = 60   # s of simulated time between checkpoints (0 / absent: none)
//   pastemix run SCENE --checkpoint-every 600   # or every 600 s of wall-clock time (either, or both)
//   pastemix run SCENE --resume DIR      # continue DIR/NAME.checkpoint.h5 of the same scene
//
// A checkpoint is one HDF5 file, DIR/NAME.checkpoint.h5, replaced atomically (written beside, fsync,
// rename, fsync of the folder: base/staged_output.h), so a kill at any moment leaves the previous one or
// the new one. It is the result file as it stands (every snapshot so far, readable with h5dump or
// h5py) plus a /checkpoint group: attributes time_s, step, wall_seconds, resume_with (the command that
// continues it), and /checkpoint/state, the engine's whole dynamic state as bytes:
//
//   - the World: time, step count, particles (every array, removed ones gone), the pair list with its
//     histories and touching flags (in pair order), the wall candidates with theirs, the positions and
//     time of the last neighbour rebuild (so the resumed run rebuilds exactly when the first would have),
//     the escaped particles, the profile;
//   - the fluid field: surfaces (the one-step lagged surface), membership, submerged volumes, candidate
//     list and its refresh state, the collective factors and the rule's step counter;
//   - the stop rule's monitor (passing checks so far); the output's sample series so far.
//
// What is not in it is rebuilt from the scene exactly as the first run built it (walls, materials, laws,
// the factories' particles: all seeded, done at t = 0), and checked: the scene's hash must match. A
// checkpoint is taken only at a step where the run loop stops anyway (a diagnostics check, a snapshot or
// sample), so it changes no batching, forces no neighbour rebuild and no extra pass: the resumed result is
// bit-identical to a run that never stopped (tests/model/checkpoint_test.cpp, at 1 and 2 threads), all
// but the wall-clock timings. The thread count may differ between the two parts (the engine's bits do not
// depend on it).
#pragma once

#include <filesystem>
#include <string>

namespace pastemix::model {

class World;
class RestMonitor;
class RunOutput;
struct Scene;

// DIR/STEM.checkpoint.h5.
std::filesystem::path checkpoint_path(const std::filesystem::path& out_dir, const std::string& stem);
// Where run_scene keeps the last checkpoint of a run that stopped on a RuntimeFailure (OUT/STEM.failed.checkpoint.h5):
// not resumed by itself; renamed to checkpoint_path it resumes like any other.
std::filesystem::path failed_checkpoint_path(const std::filesystem::path& out_dir, const std::string& stem);

struct CheckpointInfo {
  long step = 0;              // steps done
  double time = 0.0;          // s, simulated
  double wall_seconds = 0.0;  // s of wall-clock time run before the checkpoint
};

// Writes the checkpoint of the run at this step (atomically replacing the previous one). InputError with
// the path on a full disk (the run then stops with exit 2; the previous checkpoint stays).
void write_checkpoint(const std::filesystem::path& path, RunOutput& out, const World& world, const RestMonitor& rest,
                      double wall_seconds, const std::string& resume_with);

// What the checkpoint at `path` says (InputError if it is missing, damaged or not a checkpoint).
CheckpointInfo read_checkpoint_info(const std::filesystem::path& path);

// Restores world, rest and out (whose file is being written at h5_tmp) from the checkpoint at `path` of
// `scene` (world, rest and out freshly made from it). InputError (path) for a damaged file, a checkpoint of
// another scene or another engine version.
CheckpointInfo resume_from_checkpoint(const std::filesystem::path& path, const Scene& scene, World& world,
                                      RestMonitor& rest, RunOutput& out, const std::filesystem::path& h5_tmp);

}  // namespace pastemix::model
