// SPDX-License-Identifier: MIT
// Studies resume (app/study/run_cache.h, issue 20): a finished run is never recomputed, a kill at any moment
// leaves either no record or a whole one, and a damaged record is ignored with a warning and redone.
#include "app/study/run_cache.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "app/study/sweep.h"
#include "base/error.h"
#include "tests/fresh_dir.h"
#include "tests/run_command.h"

namespace fs = std::filesystem;
using namespace pastemix;
using namespace pastemix::app::study;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / fmt::format("pastemix_run_cache_{}_{}", name, getpid());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

SweepOptions hertz_sweep(const fs::path& runs) {
  SweepOptions o;
  o.vary = "dt";
  o.qoi = "peak_force";
  o.values = {1.28e-5, 6.4e-6, 3.2e-6, 1.6e-6};
  o.quiet = true;
  o.runs = runs;
  return o;
}

std::string slurp(const fs::path& p) { return test::file_text(p); }

std::size_t records_in(const fs::path& dir) {
  std::size_t n = 0;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() == ".toml";
  return n;
}

}  // namespace

TEST_CASE("run cache: a record reads back exactly what was stored, a failure with its message") {
  const fs::path dir = fresh_dir("roundtrip");
  const RunCache cache(dir);
  RunRecord done;
  done.qoi = {35780.738975427441, 0.1}, done.wall_s = 1.5, done.work = 50, done.particles = 2, done.engine = "test";
  cache.store("0123456789abcdef", done, "s.toml", "dt = 1e-6 seed 1");
  const auto back = cache.find("0123456789abcdef");
  REQUIRE(back);
  CHECK_FALSE(back->failed);
  CHECK(std::memcmp(back->qoi.data(), done.qoi.data(), 2 * sizeof(double)) == 0);  // %.17g: every bit
  CHECK(back->work == 50);
  CHECK(back->particles == 2);
  RunRecord bad;
  bad.failed = true;
  bad.failure = "blow-up: particle 3 at t = 0.1 s\n\"quoted\" \\ and a tab\t";
  cache.store("fedcba9876543210", bad, "s.toml", "x");
  const auto f = cache.find("fedcba9876543210");
  REQUIRE(f);
  CHECK(f->failed);
  CHECK(f->failure == bad.failure);
  CHECK_FALSE(cache.find("0000000000000000"));
  CHECK_FALSE(RunCache({}).find("0123456789abcdef"));  // no folder: no cache
}

TEST_CASE("run cache: a damaged record, or one under another key's name, is ignored and the run redone") {
  const fs::path dir = fresh_dir("damaged");
  const RunCache cache(dir);
  std::ofstream(dir / "1111111111111111.toml") << "key = \"1111111111111111\"\nstatus = \"done\"\nqoi = \n";
  CHECK_FALSE(cache.find("1111111111111111"));
  RunRecord r;
  r.qoi = {1.0};
  cache.store("2222222222222222", r, "s.toml", "x");
  fs::rename(dir / "2222222222222222.toml", dir / "3333333333333333.toml");
  CHECK_FALSE(cache.find("3333333333333333"));
  std::ofstream(dir / "4444444444444444.toml") << "key = \"4444444444444444\"\nstatus = \"done\"\nqoi = [1]\n"
                                                   "wall_s = 0\nwork = 1\nparticles = 1\nbogus = 2\n";
  CHECK_FALSE(cache.find("4444444444444444"));  // an unknown key: not a record this code wrote
}

TEST_CASE("sweep resumes: a rerun recomputes nothing, and a run lost to a kill is the only one redone") {
  const fs::path dir = fresh_dir("sweep");
  const auto base = model::SceneDoc::parse_file(test::source_path("datasets/scenes/hertz_impact_m1.toml"));
  const SweepResult first = sweep(base, hertz_sweep(dir / "runs"));
  CHECK(first.executed == 4);
  CHECK(first.read_back == 0);
  CHECK(records_in(dir / "runs") == 4);

  const SweepResult again = sweep(base, hertz_sweep(dir / "runs"));
  CHECK(again.executed == 0);
  CHECK(again.read_back == 4);
  REQUIRE(again.points.size() == first.points.size());
  for (std::size_t k = 0; k < first.points.size(); ++k) {
    CHECK(std::memcmp(&again.points[k].qoi, &first.points[k].qoi, sizeof(double)) == 0);
    CHECK(again.points[k].work == first.points[k].work);
  }
  CHECK(again.choice.index == first.choice.index);

  // A kill while the third run's record was being written leaves its partial (of a dead process) and no
  // record: the rerun does that one run alone, cleans the partial, and gives the same answer.
  fs::path third;
  for (const auto& e : fs::directory_iterator(dir / "runs"))
    if (slurp(e.path()).find("dt = 3.2e-06") != std::string::npos) third = e.path();
  REQUIRE_FALSE(third.empty());
  const fs::path partial = third.string() + ".partial-999999";  // no such process
  fs::rename(third, partial);
  const SweepResult resumed = sweep(base, hertz_sweep(dir / "runs"));
  CHECK(resumed.executed == 1);
  CHECK(resumed.read_back == 3);
  CHECK(fs::exists(third));
  CHECK_FALSE(fs::exists(partial));
  for (std::size_t k = 0; k < first.points.size(); ++k)
    CHECK(std::memcmp(&resumed.points[k].qoi, &first.points[k].qoi, sizeof(double)) == 0);
}

TEST_CASE("sweep resumes: a failed point is kept as failed, not rerun") {
  const fs::path dir = fresh_dir("failed");
  auto base = model::SceneDoc::parse_file(test::source_path("datasets/scenes/hertz_impact_m1.toml"));
  SweepOptions o = hertz_sweep(dir / "runs");
  o.qoi = "repose_angle";  // two spheres in free flight: not a pile, a RuntimeFailure at every point
  o.values = {1.28e-5};
  CHECK_THROWS_AS(sweep(base, o), RuntimeFailure);
  REQUIRE(records_in(dir / "runs") == 1);
  try {
    sweep(base, o);
    FAIL("the recorded failure was not thrown again");
  } catch (const RuntimeFailure& e) {
    CHECK(std::string(e.what()).find("every run failed") != std::string::npos);
  }
  CHECK(records_in(dir / "runs") == 1);
}

TEST_CASE("pastemix sweep killed with SIGKILL part-way: the rerun reads back what was finished") {
  const fs::path dir = fresh_dir("kill");
  // 6 points of ~160,000 steps (~1 s) each: long enough to be killed in the middle.
  std::string values;
  for (int k = 0; k < 6; ++k) values += fmt::format(" {:.6g}", 5e-10 * (1.0 + 0.01 * k));
  const std::string common = fmt::format("sweep '{}' --vary dt --qoi peak_force --tol 0.5 --values{}",
                                         test::source_path("datasets/scenes/hertz_impact_m1.toml"), values);
  const std::string args = common + fmt::format(" --out '{}'", (dir / "out").string());
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", (std::string("exec '") + PASTEMIX_BINARY + "' " + args + " >/dev/null 2>&1").c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto t0 = std::chrono::steady_clock::now();
  while (records_in(dir / "out" / "runs") < 2 && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  const std::size_t kept = records_in(dir / "out" / "runs");
  REQUIRE(kept >= 2);
  if (WIFEXITED(status)) {
    MESSAGE("the sweep finished before the kill; the test only shows the read-back");
  }
  const auto r = test::run_pastemix(args);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find(fmt::format("read back from")) != std::string::npos);
  const auto n_read = r.output.substr(r.output.find("done now, ") + 10);
  CHECK(std::stoul(n_read) >= kept);  // every record there at the kill was read back, not rerun
  CHECK(records_in(dir / "out" / "runs") == 6);
  // The same table as one uninterrupted sweep without records (the QoI column; wall seconds differ).
  const auto fresh = test::run_pastemix(common + fmt::format(" --no-cache --out '{}'", (dir / "fresh").string()));
  REQUIRE(fresh.exit_code == 0);
  auto qoi_column = [](const fs::path& csv) {
    std::ifstream f(csv);
    std::string line, out;
    while (std::getline(f, line)) out += line.substr(0, line.find(',', line.find(',', line.find(',') + 1) + 1)) + "\n";
    return out;
  };
  CHECK(qoi_column(dir / "out" / "sweep.csv") == qoi_column(dir / "fresh" / "sweep.csv"));
  CHECK_FALSE(fs::exists(dir / "fresh" / "runs"));
}
