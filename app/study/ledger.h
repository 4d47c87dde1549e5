// SPDX-License-Identifier: MIT
// A study's ledger: one CSV row per finished task, appended as tasks finish and read back when the study
// starts, so that a study spanning sessions and machines continues where it stopped. The ledger alone is
// enough to skip a finished task (the run files and records may be gone); it is small and meant to be
// committed (docs/studies/<name>.csv).
//
//   key,study,task,status,qoi,wall_s,particle_steps,particles,engine,failure
//   3f0c...,calibrate rolling-resistance,mu_r = 0.15 seed 7,done,33.91,812.4,4.1e10,21044,pastemix 0.9 (abc123),
//
// key: the task's key (16 hex digits, app/study/tasks.h); qoi: the QoI values, space-separated, %.17g (every
// bit); status done | failed (failure: the reason, on one line); engine: the software version that ran it
// (provenance: the key does not include it, so a ledger carries over engine changes; the study's summary says
// how many rows another engine computed). Rows are written by rank 0 only, each appended whole and fsynced;
// a kill during an append leaves at most a last line without its newline, which the next load drops with a
// warning (the task is then done again). Any other bad row is an InputError naming the file, line and column.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "app/study/run_cache.h"

namespace pastemix::app::study {

struct LedgerRow {
  std::string key, study, task;
  RunRecord outcome;
  int line = 0;  // in the file (1 = header)
};

// One row's text (with its newline), and one row parsed from a text with the ledger's header (for the MPI
// messages, which carry rows); `where` names the text in errors.
std::string ledger_line(const std::string& key, const std::string& study, const std::string& task,
                        const RunRecord& r);
LedgerRow parse_ledger_line(const std::string& line, const std::string& where);

class Ledger {
 public:
  Ledger() = default;  // no ledger: finds nothing, appends nothing
  // Reads `path` if it exists (InputError file:line:column for a bad row, a row without the header's
  // columns, or a key listed twice with different outcomes).
  explicit Ledger(std::filesystem::path path);
  bool enabled() const { return !path_.empty(); }
  const std::filesystem::path& path() const { return path_; }
  const LedgerRow* find(const std::string& key) const;
  // Appends the row (creating the file with its header) unless the key is in the ledger already.
  void append(const std::string& key, const std::string& study, const std::string& task, const RunRecord& r);
  std::size_t size() const { return rows_.size(); }
  // Rows read at start whose engine is not `engine`.
  std::size_t other_engine(const std::string& engine) const;

 private:
  std::filesystem::path path_;
  std::map<std::string, LedgerRow> rows_;
};

}  // namespace pastemix::app::study
