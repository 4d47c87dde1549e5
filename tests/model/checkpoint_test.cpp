// SPDX-License-Identifier: MIT
// Checkpoint and resume (model/checkpoint.h, issue 20 item 5): a case-3 pour (funnel, plate removed, paste
// with the collective rule, outflow, at-rest rule), shrunk to 50 g of rock (at rest, by a stricter rule, at t = 0.54 s), killed (SIGKILL / SIGTERM) at a
// seeded random moment after its first checkpoint, then `--resume`d: the result must equal, bit for bit, that
// of a run that was never stopped and wrote no checkpoint (every snapshot, series, escape and stop attribute;
// only the wall-clock timings may differ), at 1 and 2 threads.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "base/h5.h"
#include "model/checkpoint.h"
#include "model/run.h"
#include "model/scene.h"
#include "tests/model/scene_text.h"
#include "tests/run_command.h"

namespace fs = std::filesystem;
using pastemix::H5Reader;

namespace {

// measure: the [stop] rule's speed measure (model/stop_rule.h); "displacement" keeps positions between checks,
// which the checkpoint must carry.
std::string g_measure = "velocity";

std::vector<std::string> scene_args() {
  return {pastemix::test::source_path("datasets/scenes/mixing_case3.toml"), "--overrides",
          pastemix::test::source_path("datasets/scenes/mixing_fast.overrides.toml"), "--set", "factory.0.mass=0.05",
          "--set", "end_time=1.0", "--set", "output.interval=0.05", "--set", "stop.moving_mass=1e-6",
          "--set", "stop.measure=\"" + g_measure + "\"", "--quiet"};
}

std::string quoted(const std::vector<std::string>& args) {
  std::string s;
  for (const auto& a : args) s += " '" + a + "'";
  return s;
}

// Starts `pastemix run ...` as a child (its output to log); returns its pid.
pid_t spawn(const std::vector<std::string>& args, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1), dup2(fd, 2);
    std::vector<char*> argv{const_cast<char*>(PASTEMIX_BINARY), const_cast<char*>("run")};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(PASTEMIX_BINARY, argv.data());
    _exit(127);
  }
  return pid;
}

// Every dataset under `group` (recursively) equal byte for byte, as doubles or ints (by their stored type).
void same_tree(const H5Reader& a, const H5Reader& b, const std::string& group) {
  const auto ca = a.children(group), cb = b.children(group);
  REQUIRE(ca == cb);
  for (const auto& c : ca) {
    const std::string path = group + "/" + c;
    bool is_group = true;
    try {
      (void)a.children(path);
    } catch (const std::exception&) {
      is_group = false;  // a dataset
    }
    if (is_group) {
      same_tree(a, b, path);
      continue;
    }
    INFO(path);
    std::vector<double> da, db;
    try {
      da = a.read_doubles(path), db = b.read_doubles(path);
    } catch (const std::exception&) {
      CHECK(a.read_strings(path) == b.read_strings(path));
      continue;
    }
    REQUIRE(da.size() == db.size());
    CHECK(std::memcmp(da.data(), db.data(), da.size() * sizeof(double)) == 0);
  }
}

// The result files of the two runs: the same bits but for the profile's wall-clock seconds.
void same_result(const fs::path& x, const fs::path& y) {
  const H5Reader a(x), b(y);
  for (const char* g : {"/snapshots", "/timeseries", "/escaped"}) same_tree(a, b, g);
  CHECK(a.read_doubles("/material_density") == b.read_doubles("/material_density"));
  for (const char* s : {"scene_text", "scene_hash", "stop_rule"}) CHECK(a.attribute_string("/", s) == b.attribute_string("/", s));
  for (const char* k : {"stop_time_s", "moving_mass_kg", "in_flight_mass_kg", "max_speed_m_s", "escaped_mass",
                        "fluid_surface_z"}) {
    INFO(k);
    const double va = a.attribute_double("/", k), vb = b.attribute_double("/", k);
    CHECK(std::memcmp(&va, &vb, sizeof va) == 0);
  }
  for (const char* k : {"stop_fired", "moving_count", "escaped_count", "particle_count"})
    CHECK(a.attribute_int("/", k) == b.attribute_int("/", k));
  // No neighbour rebuild and no step more: the checkpoints and the restart forced nothing.
  CHECK(a.attribute_int("/profile", "steps") == b.attribute_int("/profile", "steps"));
  CHECK(a.attribute_int("/profile", "rebuilds") == b.attribute_int("/profile", "rebuilds"));
}

void kill_and_resume(const fs::path& root, const fs::path& reference, int threads, int sig, unsigned seed) {
  const fs::path dir = root / fmt::format("t{}_sig{}", threads, sig);
  fs::create_directories(dir);
  auto args = scene_args();
  args.insert(args.end(), {"--out", dir.string(), "--threads", std::to_string(threads), "--checkpoint-every", "0.2"});
  const pid_t pid = spawn(args, dir / "killed.log");
  const fs::path ck = dir / "mixing_case3.checkpoint.h5";
  const auto t0 = std::chrono::steady_clock::now();
  // Until a checkpoint past t = 0.2 s (the rock has left the funnel: contacts, wall contacts, rock in the
  // paste with its collective factors; earlier the loose fill has hardly a contact to carry over).
  double t_ck = 0.0;
  while (t_ck < 0.2 && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(300)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (!fs::exists(ck)) continue;
    t_ck = H5Reader(ck).attribute_double("/checkpoint", "time_s");  // replaced by rename: always whole
  }
  REQUIRE(t_ck >= 0.2);
  std::mt19937 rng(seed);  // a random moment after that checkpoint, the same at every test run
  std::this_thread::sleep_for(std::chrono::milliseconds(std::uniform_int_distribution<int>(0, 300)(rng)));
  ::kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  REQUIRE_MESSAGE(WIFSIGNALED(status), "the run ended before the kill: make the test scene longer");
  // The result so far is readable from the checkpoint, which says how to go on.
  {
    const H5Reader r(ck);
    CHECK(r.exists("/snapshots/000000/position"));
    CHECK(r.attribute_string("/checkpoint", "resume_with").find("--resume") != std::string::npos);
  }
  // A fresh start would throw the progress away: refused, with the command that resumes.
  const auto fresh = pastemix::test::run_pastemix("run" + quoted(scene_args()) + " --out '" + dir.string() + "'");
  INFO(fresh.output);
  CHECK(fresh.exit_code == 2);
  CHECK(fresh.output.find("--resume") != std::string::npos);
  auto resume = scene_args();
  resume.insert(resume.end(), {"--resume", dir.string(), "--threads", std::to_string(threads)});
  const auto r = pastemix::test::run_pastemix("run" + quoted(resume));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("resumed at step") != std::string::npos);
  same_result(reference, dir / "mixing_case3.h5");
  // Published: the checkpoint is gone; no partial is left (the killed run's were removed).
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    CHECK_MESSAGE((name == "mixing_case3.h5" || name == "mixing_case3.xmf" || name == "killed.log"), name);
  }
}

// The uninterrupted reference run of scene_args() in root/ref (one thread: the engine's bits do not depend on
// the thread count, so it serves every resumed run).
fs::path reference_run(const fs::path& root) {
  // Two threads on a loaded machine: sleeping, not spinning, at the barriers (as scripts/test.sh sets),
  // or a 2-thread run here crawls.
  ::setenv("OMP_WAIT_POLICY", "passive", 0);
  fs::remove_all(root);
  fs::create_directories(root / "ref");
  auto args = scene_args();
  args.insert(args.end(), {"--out", (root / "ref").string(), "--threads", "1"});
  const auto ref = pastemix::test::run_pastemix("run" + quoted(args));
  INFO(ref.output);
  REQUIRE(ref.exit_code == 0);
  return root / "ref" / "mixing_case3.h5";
}

}  // namespace

TEST_CASE("run: killed at a random point then resumed gives the bits of an uninterrupted run at 1 and 2 threads") {
  const fs::path root = fs::absolute(fmt::format("model_checkpoint_{}", ::getpid()));
  const fs::path reference = reference_run(root);
  kill_and_resume(root, reference, 1, SIGKILL, 1);
  kill_and_resume(root, reference, 2, SIGKILL, 2);
  kill_and_resume(root, reference, 2, SIGTERM, 3);
  fs::remove_all(root);
}

TEST_CASE("run: with the [stop] displacement measure, killed and resumed gives the bits of an uninterrupted run") {
  g_measure = "displacement";
  const fs::path root = fs::absolute(fmt::format("model_checkpoint_disp_{}", ::getpid()));
  const fs::path reference = reference_run(root);
  {
    H5Reader h5(reference.string());
    CHECK(h5.attribute_string("/", "stop_measure") == "displacement");
    CHECK(h5.attribute_int("/", "stop_fired") == 1);
  }
  kill_and_resume(root, reference, 1, SIGKILL, 4);
  g_measure = "velocity";
  fs::remove_all(root);
}

TEST_CASE("run --resume: without a checkpoint it starts from 0, stale partials go, a damaged one is exit 2 naming the file") {
  const fs::path dir = fs::absolute(fmt::format("model_checkpoint_bad_{}", ::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = pastemix::test::source_path("datasets/scenes/hertz_impact_m1.toml");
  // A checkpoint half written when its run was killed (pid 999999999 does not exist): removed by the next run.
  const fs::path stale = dir / "hertz_impact_m1.checkpoint.h5.partial-999999999";
  std::ofstream(stale) << "half a checkpoint";
  // Nothing to resume: the run starts from t = 0 (as the realizations of an ensemble not begun yet).
  auto r = pastemix::test::run_pastemix(fmt::format("run '{}' --resume '{}' --quiet", scene, dir.string()));
  CHECK(r.exit_code == 0);
  CHECK(r.output.find("starting from t = 0") != std::string::npos);
  CHECK(!fs::exists(stale));
  // Not an HDF5 file.
  std::ofstream(dir / "hertz_impact_m1.checkpoint.h5") << "half a file";
  r = pastemix::test::run_pastemix(fmt::format("run '{}' --resume '{}' --quiet", scene, dir.string()));
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK(r.output.find((dir / "hertz_impact_m1.checkpoint.h5").string()) != std::string::npos);
  fs::remove_all(dir);
}

namespace {

// The small pour of tests/model/data (2 g of 2.5-5 mm rock into the box: contacts, walls, rolling), 0.15 s.
std::string small_pour(const std::string& extra_output) {
  std::ifstream in(pastemix::test::source_path("tests/model/data/pour_box_small.toml"));
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  const std::string key = "end_time = 1.0";
  text.replace(text.find(key), key.size(), "end_time = 0.15");
  const std::string out = "[output]\n";
  text.replace(text.find(out), out.size(), out + extra_output);
  return text;
}

}  // namespace

TEST_CASE("run: checkpoints by [output] checkpoint_interval change no bit and force no neighbour rebuild") {
  using namespace pastemix::model;
  const fs::path dir = fs::absolute(fmt::format("model_checkpoint_interval_{}", ::getpid()));
  fs::remove_all(dir);
  RunOptions ro;
  ro.progress = false;
  ro.stem = "plain";
  const RunSummary plain = run_scene(parse_scene(small_pour(""), (dir / "pour.toml").string()), dir, ro);
  ro.stem = "ckpt";
  // Every 2.2 ms of simulated time = 440 steps of 5e-6 s: a checkpoint at the first of the loop's stops at or
  // after each (its 50-step checks, snapshots, samples), 68 in the 0.15 s.
  const RunSummary ck =
      run_scene(parse_scene(small_pour("checkpoint_interval = 2.2e-3\n"), (dir / "pour.toml").string()), dir, ro);
  CHECK(plain.checkpoints == 0);
  CHECK(ck.checkpoints >= 60);
  CHECK(ck.steps == plain.steps);
  CHECK(ck.profile.rebuilds == plain.profile.rebuilds);
  CHECK(!fs::exists(checkpoint_path(dir, "ckpt")));  // removed once the result is out
  const H5Reader a(plain.h5), b(ck.h5);
  same_tree(a, b, "/snapshots");
  same_tree(a, b, "/timeseries");
  fs::remove_all(dir);
}

// A run that stops on a RuntimeFailure keeps its last checkpoint under another name (failed_checkpoint_path):
// nothing resumes it by itself, and renamed back it resumes to the same failure. Two spheres fall through the
// open bottom of the domain (no floor): 50 % of the mass leaves, above max_escaped_fraction = 5 %, at t ~ 0.11 s,
// after the checkpoints every 0.02 s of simulated time.
TEST_CASE("run: a failed run keeps its last checkpoint for a diagnosis, and it resumes to the same failure") {
  using namespace pastemix::model;
  const fs::path dir = fs::absolute(fmt::format("model_checkpoint_failed_{}", ::getpid()));
  fs::remove_all(dir);
  const std::string text =
      "seed = 3\ntime_step = 1e-4\nend_time = 1.0\n[domain]\nmin = [-0.5, -0.5, -0.05]\nmax = [0.5, 0.5, 1.0]\n"
      "on_exit = \"remove\"\n[physics]\ngravity = [0, 0, -9.81]\n[contact]\nlaw = \"hertz_mindlin\"\n" +
      test::material("rock", 2760, 4.68e7, 0.19) + test::interaction("rock/rock", 0.5, 0.0) +
      "[[particle]]\nmaterial = \"rock\"\nradius = 0.005\nposition = [0, 0, 0.01]\n"
      "[[particle]]\nmaterial = \"rock\"\nradius = 0.005\nposition = [0.2, 0, 0.3]\n"
      "[output]\ninterval = 0.5\ncheckpoint_interval = 0.02\n";
  const Scene scene = parse_scene(text, (dir / "fall.toml").string());
  RunOptions ro;
  ro.progress = false;
  auto failure = [&] {
    try {
      run_scene(scene, dir, ro);
    } catch (const pastemix::RuntimeFailure& e) {
      return std::string(e.what());
    }
    return std::string("(no failure)");
  };
  const std::string first = failure();
  CAPTURE(first);
  CHECK(first.find("left the domain") != std::string::npos);
  CHECK(first.find("the last checkpoint is kept as") != std::string::npos);
  CHECK(!fs::exists(checkpoint_path(dir, "fall")));
  REQUIRE(fs::exists(failed_checkpoint_path(dir, "fall")));
  // A fresh run is not stopped by it, and meets the same failure (the kept file is replaced).
  CHECK(failure() == first);
  // Renamed to the checkpoint's own name, it resumes: the same failure, the same particle and time.
  fs::rename(failed_checkpoint_path(dir, "fall"), checkpoint_path(dir, "fall"));
  ro.resume = true;
  const std::string resumed = failure();
  CHECK(resumed.substr(0, resumed.find('\n')) == first.substr(0, first.find('\n')));
  fs::remove_all(dir);
}
