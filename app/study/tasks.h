// SPDX-License-Identifier: MIT
// The tasks of a study: every run of a sweep or calibration (`sweep`, `calibrate rolling-resistance`,
// `calibrate rheology`) is one Task, and this file runs a list of them; it is the studies' only scheduler.
//
// A task has a key: the text hash (base/hash.h) of the run's resolved scene text (every override, the
// ladder's or calibration's value and the seed are in it), with the QoI's name for the QoI studies; the
// engine version is recorded beside the outcome, not in the key (see ledger.h). A finished task is found
// again, in this order, in
//   1. the ledger (ledger.h: a committed CSV; alone enough to skip it),
//   2. the run records (run_cache.h: OUT/runs/<key>.toml, one per task, on the machine that ran it),
//   3. the task's own files (the rheology calibration's OUT/runs/<key>.h5: `run` says so with From::disk),
// and is then never run again; else `run` computes it, and continues from its checkpoint when a kill left
// one (From::resumed). A RuntimeFailure of a run is an outcome too (a failed task, kept, not rerun).
//
// Where the tasks run:
//   - `jobs` threads on one machine (one OpenMP thread each), a queue over the list;
//   - K MPI ranks (ranks.h): the unfinished tasks, in list order, go to ranks round robin; every outcome is
//     sent to rank 0, which writes the ledger; at the end every rank gets every outcome;
//   - one task (`task_index`, a Slurm job array's index): that task alone is run (or found finished) and its
//     record written; the ledger is left to a final gathering run of the same command without the index,
//     so that many array jobs never append to one file at once. Then TaskIndexDone is thrown. A list whose
//     tasks are all finished returns as usual (a calibration's next round is then the one indexed).
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/study/ledger.h"
#include "app/study/ranks.h"
#include "app/study/run_cache.h"

namespace pastemix::app::study {

// Where a finished task's outcome came from.
enum class From { ran, resumed, disk, record, ledger };
const char* to_string(From f);

struct Task {
  std::string key;   // 16 hex digits
  std::string what;  // for people and the ledger: "dt = 1e-05 seed 3"
  // Computes the outcome (the QoI values and cost); may set `from` to resumed or disk. A RuntimeFailure it
  // throws becomes a failed outcome.
  std::function<RunRecord(From& from)> run;
};

struct StudyIo {
  std::string study;               // the study's name in ledger rows ("sweep dt peak_force", ...)
  std::string engine;              // software version, into records and rows
  std::filesystem::path records;   // folder of run records; empty: none
  Ledger* ledger = nullptr;        // null: none
  int jobs = 1;
  const Ranks* ranks = nullptr;    // null: one rank
  std::optional<long> task_index;  // run this task of the list alone
  // Rank 0, once per task as it is finished or found (under a lock; for the per-run line).
  std::function<void(const Task&, const RunRecord&, From)> on_done;
};

// The StudyIo of a command's options (any options struct with engine, ledger, jobs, ranks and task_index:
// SweepOptions, RollingOptions, RheologyCalOptions, PredictOptions), so that the four commands fill it alike.
template <class Options>
StudyIo study_io(const Options& o, std::string study, std::filesystem::path records = {}) {
  StudyIo io;
  io.study = std::move(study);
  io.engine = o.engine;
  io.records = std::move(records);
  io.ledger = o.ledger;
  io.jobs = o.jobs;
  io.ranks = o.ranks;
  io.task_index = o.task_index;
  return io;
}

// Each task's position in its list, by key (for the per-run lines of on_done).
inline std::map<std::string, std::size_t> index_by_key(const std::vector<Task>& list) {
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < list.size(); ++i) index[list[i].key] = i;
  return index;
}

struct TaskCounts {
  int ran = 0, resumed = 0, disk = 0, record = 0, ledger = 0;
  int computed() const { return ran + resumed; }
  int read_back() const { return disk + record + ledger; }
};

struct Finished {
  RunRecord outcome;
  From from = From::ran;
};

// After a `task_index` run: what was done, for the command to print (exit 0).
struct TaskIndexDone {
  std::string message;
};

// Runs (or finds) every task; one Finished per task, in list order, on every rank. Adds to `counts`.
std::vector<Finished> run_tasks(const std::vector<Task>& tasks, const StudyIo& io, TaskCounts& counts);

}  // namespace pastemix::app::study
