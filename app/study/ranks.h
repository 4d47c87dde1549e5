// SPDX-License-Identifier: MIT
// The ranks of a study: one process, or K processes started by `mpirun -np K pastemix ...` (Open MPI).
//
// A study's tasks (app/study/tasks.h) are spread over the ranks by their index in the list of unfinished
// tasks (task j to rank j mod K); each finished task's outcome goes to rank 0, which alone prints, writes the
// ledger and the outputs, and then sends every outcome back to all ranks so that each decides the next round
// of a calibration from the same numbers. That is all the distribution there is: no scheduler, no load
// balancing beyond the round robin (the tasks of one study cost about the same).
//
// MPI is optional at build time (PASTEMIX_HAVE_MPI, set when CMake finds MPI). Without it the study is one
// rank, and asking for MPI (--mpi, or a launch by mpirun, seen from OMPI_COMM_WORLD_SIZE / PMI_SIZE) is an
// InputError that says it is not built in, rather than K copies of the whole study writing one ledger.
#pragma once

#include <optional>
#include <string>

namespace pastemix::app::study {

class Ranks {
 public:
  // The process's ranks: MPI started (once per process, finalised at exit) when `want_mpi` or when the
  // process was launched by mpirun; otherwise a single rank.
  static const Ranks& start(bool want_mpi);
  // Whether this build has MPI.
  static bool built_in();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool mpi() const { return mpi_; }

  // Rank 0's `text` on every rank (collective).
  std::string broadcast(const std::string& text) const;
  // From a rank other than 0: one message to rank 0 (blocking send; thread safe).
  void send_to_root(const std::string& text) const;
  // On rank 0: the next message from any rank, if one is waiting (thread safe, never blocks).
  std::optional<std::string> poll() const;
  // Ends every rank with `code` (an error seen by one rank alone, e.g. a bad ledger on rank 0, must not
  // leave the others waiting for it).
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
  bool mpi_ = false;
};

}  // namespace pastemix::app::study
