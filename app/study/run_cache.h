// SPDX-License-Identifier: MIT
// A study's finished runs, kept on disk so that a rerun of the study, or its resumption after a kill,
// never recomputes a finished point (issue 20: "studies resume too").
//
//   RunCache cache(out / "runs");
//   if (auto r = cache.find(key)) ...            // read back: no run
//   else cache.store(key, record, scene_path);   // after the run, atomically
//
// One small TOML file per run, DIR/<key>.toml, written through StagedOutput (checked as TOML, fsynced,
// renamed into place): a kill leaves either no record or a complete one, never a half. The key is the
// text hash (base/hash.h) of the QoI name and the run's resolved scene text (every override, the ladder's
// value and the seed are in that text), so a different scene, value, seed or QoI is a different run, and
// a record is found again only for exactly the run it describes. A failed run (blow-up, unfinished pile)
// is a finished run too: its reason is kept and it is not rerun; change the scene to rerun it.
//
// A record that does not parse or lacks a field (an edit by hand, a foreign file) is ignored with a
// warning naming the file, and the run is done again; a record of another key (a renamed file) likewise.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/scene_doc.h"

namespace pastemix::app::study {

// The outcome of one finished run (a study task): its QoI values or its failure, and its cost.
struct RunRecord {
  bool failed = false;
  std::string failure;   // the RuntimeFailure's message when failed
  std::vector<double> qoi;  // the QoI's values (units of the study's QoI; one for sweep and rolling
                            // resistance, the three layer masses in kg for the rheology calibration)
  double wall_s = 0.0;   // wall-clock seconds of the step loop when it ran
  double work = 0.0;     // particles x steps
  std::size_t particles = 0;
  std::string engine;    // software version that ran it (provenance; not part of the key)
  // The record of a run that failed with `message`.
  static RunRecord failed_with(std::string message) {
    RunRecord r;
    r.failed = true;
    r.failure = std::move(message);
    return r;
  }
};

// The key of one run: text hash of the QoI name and the resolved scene text.
std::string run_key(const model::SceneDoc& doc, const std::string& qoi);

class RunCache {
 public:
  // An empty dir: no cache (find finds nothing, store stores nothing).
  explicit RunCache(std::filesystem::path dir) : dir_(std::move(dir)) {}
  bool enabled() const { return !dir_.empty(); }
  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path record_path(const std::string& key) const { return dir_ / (key + ".toml"); }

  std::optional<RunRecord> find(const std::string& key) const;
  // Writes DIR/<key>.toml atomically; `scene` (the scene file) and `what` (e.g. "dt = 1e-5 seed 3") are
  // written as comments-with-values for the reader. InputError (path, cause) on a write failure.
  void store(const std::string& key, const RunRecord& r, const std::string& scene, const std::string& what) const;

 private:
  std::filesystem::path dir_;
};

}  // namespace pastemix::app::study
