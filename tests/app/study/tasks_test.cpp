// SPDX-License-Identifier: MIT
// The studies' task runner (app/study/tasks.h) through the commands, on tiny scenes:
//  - a study (a sweep of a final-state QoI) killed with SIGKILL mid-run (a run in progress, with its
//    checkpoint) and rerun: nothing finished is recomputed, the interrupted run continues from its
//    checkpoint, and the QoIs are those of an uninterrupted study, bit for bit;
//  - the rolling-resistance calibration's (mu_r, seed) tasks go into its ledger and are never rerun;
//  - `--task-index` (a Slurm array job) runs one task and records it, and the gathering run reads it back;
//  - the Slurm script passes `bash -n` and runs one task.
#include "app/study/tasks.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "tests/fresh_dir.h"
#include "tests/run_command.h"

namespace fs = std::filesystem;
using namespace pastemix;

namespace {

fs::path fresh(const std::string& name) {
  return test::fresh_dir(fs::temp_directory_path() / fmt::format("pastemix_tasks_{}_{}", name, getpid()));
}

std::string slurp(const fs::path& p) { return test::file_text(p); }

std::size_t lines_in(const fs::path& p) {
  const std::string s = slurp(p);
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

bool has_checkpoint(const fs::path& dir) {
  if (!fs::exists(dir)) return false;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().string().ends_with(".checkpoint.h5")) return true;
  return false;
}

// points.csv without the wall-clock column: mu_r, seed, angle (every bit), status.
std::string angles(const fs::path& csv) {
  std::istringstream in(slurp(csv));
  std::string out;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> c;
    std::stringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) c.push_back(cell);
    if (c.size() == 6) out += c[0] + "," + c[1] + "," + c[2] + "," + c[5] + "\n";
  }
  return out;
}

// sweep.csv's value and QoI columns.
std::string qoi_columns(const fs::path& csv) {
  std::istringstream in(slurp(csv));
  std::string out;
  for (std::string line; std::getline(in, line);) {
    const std::size_t a = line.find(','), b = line.find(',', a + 1), c = line.find(',', b + 1);
    out += line.substr(0, a) + line.substr(b, c - b) + "\n";
  }
  return out;
}

std::string rolling_args(const fs::path& out, const std::string& extra) {
  return fmt::format("calibrate rolling-resistance '{}' --target 25 --values 0.05 0.2 0.4 --seeds 2 --refine 0 "
                     "--out '{}' {}",
                     test::source_path("tests/app/study/data/repose_tiny.toml"), out.string(), extra);
}

}  // namespace

TEST_CASE("a study killed mid-run resumes: nothing finished is redone, the run in progress continues, same QoIs") {
  // A sweep of a final-state QoI on the tiny pour: 6 runs of ~1 s, each through model::run_scene with a
  // checkpoint every 0.05 s of wall clock.
  const fs::path d = fresh("kill");
  const std::string common = fmt::format("sweep '{}' --vary dt --qoi final_height --values 1e-5 9e-6 8e-6 --seeds 2 "
                                         "--tol 0.5",
                                         test::source_path("tests/app/study/data/repose_tiny.toml"));
  const std::string args =
      common + fmt::format(" --out '{}' --ledger '{}' --checkpoint-every 0.05", (d / "out").string(), (d / "ledger.csv").string());
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", (std::string("exec '") + PASTEMIX_BINARY + "' " + args + " >/dev/null 2>&1").c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  // Kill once two tasks are in the ledger and the next one has written a checkpoint.
  const auto t0 = std::chrono::steady_clock::now();
  while (!(fs::exists(d / "ledger.csv") && lines_in(d / "ledger.csv") >= 3 && has_checkpoint(d / "out" / "runs")) &&
         std::chrono::steady_clock::now() - t0 < std::chrono::seconds(300))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  const std::size_t finished = lines_in(d / "ledger.csv") - 1;
  REQUIRE(finished >= 2);
  REQUIRE_MESSAGE(has_checkpoint(d / "out" / "runs"), "the kill found no run in progress");
  const auto again = test::run_pastemix(args);
  INFO(again.output);
  REQUIRE(again.exit_code == 0);
  CHECK(again.output.find(fmt::format("{} finished task(s)", finished)) != std::string::npos);
  CHECK(again.output.find("(resumed from its checkpoint)") != std::string::npos);
  CHECK(again.output.find(fmt::format("runs: {} done now, {} read back", 6 - finished, finished)) != std::string::npos);
  CHECK(lines_in(d / "ledger.csv") == 7);
  CHECK_FALSE(has_checkpoint(d / "out" / "runs"));
  // The same study uninterrupted, in a fresh folder: the same QoIs, bit for bit.
  const auto whole = test::run_pastemix(common + fmt::format(" --quiet --out '{}'", (d / "whole").string()));
  REQUIRE(whole.exit_code == 0);
  CHECK(qoi_columns(d / "out" / "sweep.csv") == qoi_columns(d / "whole" / "sweep.csv"));
  // A third time: everything from the ledger, nothing run.
  const auto third = test::run_pastemix(args);
  CHECK(third.output.find("runs: 0 done now, 6 read back") != std::string::npos);
}

TEST_CASE("calibrate rolling-resistance: every (mu_r, seed) a task in the ledger, and a rerun runs none of them") {
  // The tiny pile is too small for a trustworthy angle (some runs fail as "no pile", which is an outcome
  // too): this checks the command's tasks, not the physics.
  const fs::path d = fresh("rolling");
  const std::string args = rolling_args(d / "out", fmt::format("--ledger '{}' --quiet", (d / "l.csv").string()));
  const auto first = test::run_pastemix(args);
  INFO(first.output);
  REQUIRE((first.exit_code == 0 || first.exit_code == 3));
  CHECK(first.output.find("runs: 6 in all, 6 computed now, 0 read back") != std::string::npos);
  CHECK(lines_in(d / "l.csv") == 7);
  const std::string before = angles(d / "out" / "points.csv");
  REQUIRE(!before.empty());
  // No run records this time: the ledger alone gives every outcome back, the same to every bit.
  const auto again = test::run_pastemix(args + " --no-cache");
  CHECK(again.exit_code == first.exit_code);
  CHECK(again.output.find("runs: 6 in all, 0 computed now, 6 read back") != std::string::npos);
  CHECK(angles(d / "out" / "points.csv") == before);
}

TEST_CASE("--task-index runs one task and records it, and the gathering run reads it back and writes the ledger") {
  const fs::path d = fresh("index");
  const std::string sweep = fmt::format("sweep '{}' --vary dt --qoi peak_force --values 1.28e-5 6.4e-6 3.2e-6 --out '{}'",
                                        test::source_path("datasets/scenes/hertz_impact_m1.toml"), (d / "out").string());
  const auto one = test::run_pastemix(sweep + fmt::format(" --task-index 1 --ledger '{}'", (d / "l.csv").string()));
  INFO(one.output);
  REQUIRE(one.exit_code == 0);
  CHECK(one.output.find("task 1 of 3 (dt = 6.4e-06 seed 1") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "l.csv"));  // array jobs never append to the ledger
  const auto past = test::run_pastemix(sweep + " --task-index 7");
  CHECK(past.exit_code == 0);
  CHECK(past.output.find("nothing to do") != std::string::npos);
  const auto gather = test::run_pastemix(sweep + fmt::format(" --ledger '{}'", (d / "l.csv").string()));
  REQUIRE(gather.exit_code == 0);
  CHECK(gather.output.find("runs: 2 done now, 1 read back") != std::string::npos);
  CHECK(lines_in(d / "l.csv") == 4);
  // An array job of a study that is all finished does nothing and writes nothing.
  fs::remove(d / "out" / "sweep.csv");
  const auto late = test::run_pastemix(sweep + fmt::format(" --task-index 0 --ledger '{}'", (d / "l.csv").string()));
  CHECK(late.exit_code == 0);
  CHECK(late.output.find("every task of the study is finished") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "out" / "sweep.csv"));
}

TEST_CASE("the Slurm job-array script passes bash -n and runs its array index as --task-index") {
  const std::string script = test::source_path("app/study/slurm_array.sh");
  REQUIRE(fs::exists(script));
  CHECK(std::system(("bash -n '" + script + "'").c_str()) == 0);
  const fs::path d = fresh("slurm");
  const std::string cmd = fmt::format(
      "SLURM_ARRAY_TASK_ID=2 PASTEMIX='{}' bash '{}' sweep '{}' --vary dt --qoi peak_force --values 1.28e-5 6.4e-6 "
      "3.2e-6 --out '{}' > '{}' 2>&1",
      PASTEMIX_BINARY, script, test::source_path("datasets/scenes/hertz_impact_m1.toml"), (d / "out").string(),
      (d / "log").string());
  CHECK(std::system(cmd.c_str()) == 0);
  INFO(slurp(d / "log"));
  CHECK(slurp(d / "log").find("task 2 of 3 (dt = 3.2e-06 seed 1") != std::string::npos);
  std::size_t records = 0;
  for (const auto& e : fs::directory_iterator(d / "out" / "runs")) records += e.path().extension() == ".toml";
  CHECK(records == 1);
  // Without the array variable it refuses, saying how to submit it.
  CHECK(std::system(("bash '" + script + "' sweep x >/dev/null 2>&1").c_str()) != 0);
}
