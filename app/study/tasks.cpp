// SPDX-License-Identifier: MIT
#include "app/study/tasks.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <omp.h>

#include "base/error.h"

namespace pastemix::app::study {

const char* to_string(From f) {
  switch (f) {
    case From::ran: return "ran";
    case From::resumed: return "resumed from its checkpoint";
    case From::disk: return "on disk";
    case From::record: return "on disk";
    case From::ledger: return "in the ledger";
  }
  return "?";
}

namespace {

// A message between ranks: "index,from,<ledger row>".
std::string message(std::size_t i, From f, const Task& t, const StudyIo& io, const RunRecord& r) {
  return fmt::format("{},{},", i, static_cast<int>(f)) + ledger_line(t.key, io.study, t.what, r);
}

void parse_message(const std::string& m, std::size_t& i, From& f, RunRecord& r) {
  const std::size_t a = m.find(','), b = m.find(',', a + 1);
  if (a == std::string::npos || b == std::string::npos) throw RuntimeFailure("a malformed message between ranks");
  i = std::stoul(m.substr(0, a));
  f = static_cast<From>(std::stoi(m.substr(a + 1, b - a - 1)));
  r = parse_ledger_line(m.substr(b + 1), "a message between ranks").outcome;
}

// Runs one task through its record: found there, or computed and recorded (a failure too).
RunRecord compute(const Task& t, const StudyIo& io, const RunCache& cache, From& from) {
  if (auto rec = cache.find(t.key)) {
    from = From::record;
    return *rec;
  }
  from = From::ran;
  RunRecord r;
  try {
    r = t.run(from);
  } catch (const RuntimeFailure& e) {
    r = RunRecord::failed_with(e.what());
  }
  r.engine = io.engine;
  cache.store(t.key, r, "", t.what);
  return r;
}

class Runner {
 public:
  Runner(const std::vector<Task>& tasks, const StudyIo& io, TaskCounts& counts)
      : tasks_(tasks), io_(io), counts_(counts), cache_(io.records), out_(tasks.size()) {}

  std::vector<Finished> run() {
    const int rank = io_.ranks ? io_.ranks->rank() : 0, size = io_.ranks ? io_.ranks->size() : 1;
    if (io_.task_index && size > 1)
      throw InputError("--task-index", 0, "", "one task per process: not with several MPI ranks");
    std::vector<std::size_t> pending;
    if (rank == 0) find_finished(pending);
    // An index run of a round whose tasks are all finished goes on to the next round (or to the end).
    if (io_.task_index && !pending.empty()) run_index(pending);
    pending = share_pending(pending);
    std::vector<std::size_t> mine;
    for (std::size_t j = static_cast<std::size_t>(rank); j < pending.size(); j += static_cast<std::size_t>(size))
      mine.push_back(pending[j]);
    const std::size_t from_others = rank == 0 ? pending.size() - mine.size() : 0;
    run_mine(mine, rank == 0, from_others);
    return share_all();
  }

 private:
  // Rank 0: every task found in the ledger or the records is finished; the rest are pending.
  void find_finished(std::vector<std::size_t>& pending) {
    for (std::size_t i = 0; i < tasks_.size(); ++i) {
      const Task& t = tasks_[i];
      if (const LedgerRow* row = io_.ledger ? io_.ledger->find(t.key) : nullptr) {
        done(i, row->outcome, From::ledger);
      } else if (auto rec = cache_.find(t.key)) {
        done(i, *rec, From::record);
      } else {
        pending.push_back(i);
      }
    }
  }

  [[noreturn]] void run_index(const std::vector<std::size_t>& pending) {
    const long k = *io_.task_index;
    if (k < 0) throw InputError("--task-index", 0, "", "must be >= 0");
    if (static_cast<std::size_t>(k) >= tasks_.size())
      throw TaskIndexDone{fmt::format("task {}: this study (round) has {} tasks; nothing to do", k, tasks_.size())};
    const Task& t = tasks_[static_cast<std::size_t>(k)];
    bool todo = false;
    for (std::size_t i : pending) todo = todo || i == static_cast<std::size_t>(k);
    if (!todo) throw TaskIndexDone{fmt::format("task {} of {} ({}, key {}): finished already", k, tasks_.size(), t.what, t.key)};
    From from = From::ran;
    const RunRecord r = compute(t, io_, cache_, from);
    if (io_.on_done) io_.on_done(t, r, from);
    throw TaskIndexDone{fmt::format("task {} of {} ({}, key {}): {}{}; record {}", k, tasks_.size(), t.what, t.key,
                                    r.failed ? "FAILED" : "done", from == From::ran ? "" : fmt::format(" ({})", to_string(from)),
                                    cache_.record_path(t.key).string())};
  }

  // Rank 0's pending list on every rank.
  std::vector<std::size_t> share_pending(const std::vector<std::size_t>& pending) const {
    if (!io_.ranks || !io_.ranks->mpi()) return pending;
    std::string text;
    for (std::size_t i : pending) text += std::to_string(i) + " ";
    std::istringstream in(io_.ranks->broadcast(text));
    std::vector<std::size_t> out;
    for (std::size_t i; in >> i;) out.push_back(i);
    return out;
  }

  // Rank 0 only: keeps the outcome, writes the ledger row, counts and reports it.
  void done(std::size_t i, const RunRecord& r, From from) {
    std::lock_guard<std::mutex> g(lock_);
    out_[i] = {r, from};
    ++(from == From::ran ? counts_.ran : from == From::resumed ? counts_.resumed : from == From::disk ? counts_.disk
       : from == From::record ? counts_.record : counts_.ledger);
    // Array jobs (task_index) never append: many writers, one file; the gathering run does.
    if (io_.ledger && from != From::ledger && !io_.task_index) io_.ledger->append(tasks_[i].key, io_.study, tasks_[i].what, r);
    if (io_.on_done) io_.on_done(tasks_[i], r, from);
  }

  void run_mine(const std::vector<std::size_t>& mine, bool root, std::size_t from_others) {
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
      if (io_.jobs > 1 || (io_.ranks && io_.ranks->mpi())) omp_set_num_threads(1);
      for (std::size_t j; (j = next++) < mine.size();) {
        From from = From::ran;
        const RunRecord r = compute(tasks_[mine[j]], io_, cache_, from);
        if (root)
          done(mine[j], r, from);
        else
          io_.ranks->send_to_root(message(mine[j], from, tasks_[mine[j]], io_, r));
      }
    };
    const int threads = std::max(1, std::min<int>(io_.jobs, static_cast<int>(mine.size())));
    std::vector<std::thread> pool;
    // Rank 0 with other ranks: its main thread receives their outcomes, its tasks run on worker threads.
    const bool receive = root && from_others > 0;
    for (int k = receive ? 0 : 1; k < threads; ++k) pool.emplace_back(worker);
    if (!receive) worker();
    for (std::size_t got = 0; receive && got < from_others;) {
      if (auto m = io_.ranks->poll()) {
        std::size_t i = 0;
        From f = From::ran;
        RunRecord r;
        parse_message(*m, i, f, r);
        done(i, r, f);
        ++got;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    }
    for (auto& th : pool) th.join();
  }

  // Every outcome on every rank (rank 0's table, broadcast).
  std::vector<Finished> share_all() {
    if (!io_.ranks || !io_.ranks->mpi()) return out_;
    std::string text;
    if (io_.ranks->root())
      for (std::size_t i = 0; i < tasks_.size(); ++i) text += message(i, out_[i].from, tasks_[i], io_, out_[i].outcome);
    const std::string all = io_.ranks->broadcast(text);
    if (!io_.ranks->root()) {
      std::istringstream in(all);
      for (std::string line; std::getline(in, line);) {
        std::size_t i = 0;
        From f = From::ran;
        RunRecord r;
        parse_message(line + "\n", i, f, r);
        out_.at(i) = {r, f};
      }
    }
    return out_;
  }

  const std::vector<Task>& tasks_;
  const StudyIo& io_;
  TaskCounts& counts_;
  RunCache cache_;
  std::vector<Finished> out_;
  std::mutex lock_;
};

}  // namespace

std::vector<Finished> run_tasks(const std::vector<Task>& tasks, const StudyIo& io, TaskCounts& counts) {
  return Runner(tasks, io, counts).run();
}

}  // namespace pastemix::app::study
