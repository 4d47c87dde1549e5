// SPDX-License-Identifier: MIT
// A study's ledger (app/study/ledger.h): rows read back bit for bit, bad rows named by file, line and
// column, a torn last line (a kill during an append) dropped, and the ledger alone enough to skip a task.
#include "app/study/ledger.h"

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

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

fs::path fresh(const std::string& name) {
  return test::fresh_dir(fs::temp_directory_path() / fmt::format("pastemix_ledger_{}_{}", name, getpid()));
}

std::string slurp(const fs::path& p) { return test::file_text(p); }

std::string error_of(const fs::path& p) {
  try {
    Ledger l(p);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kHeader = "key,study,task,status,qoi,wall_s,particle_steps,particles,engine,failure\n";

}  // namespace

TEST_CASE("ledger: rows read back every bit, failures with their reason, a key appended once") {
  const fs::path p = fresh("roundtrip") / "sub" / "study.csv";
  RunRecord done;
  done.qoi = {0.1 + 0.2, 35780.738975427441, 1e-300};
  done.wall_s = 1.5, done.work = 4.1e10, done.particles = 21044;
  done.engine = std::string("pastemix 0.9 (abc, dirty)");
  RunRecord bad;
  bad.failed = true;
  bad.failure = std::string("blow-up: particle 3, \"quoted\", at t = 0.1 s");
  bad.engine = std::string("e");
  {
    Ledger l(p);
    l.append("0123456789abcdef", "sweep dt peak_force", "dt = 1e-06 seed 1", done);
    l.append("fedcba9876543210", "sweep dt peak_force", "dt = 2e-06, seed 1", bad);
    l.append("0123456789abcdef", "sweep dt peak_force", "again", done);  // known: not appended twice
  }
  CHECK(slurp(p).find(kHeader) == 0);
  const Ledger back(p);
  REQUIRE(back.size() == 2);
  const LedgerRow* a = back.find("0123456789abcdef");
  REQUIRE(a);
  CHECK(std::memcmp(a->outcome.qoi.data(), done.qoi.data(), 3 * sizeof(double)) == 0);
  CHECK(a->outcome.work == 4.1e10);
  CHECK(a->outcome.particles == 21044);
  CHECK(a->outcome.engine == done.engine);
  CHECK(a->task == "dt = 1e-06 seed 1");
  CHECK(a->line == 2);
  const LedgerRow* f = back.find("fedcba9876543210");
  REQUIRE(f);
  CHECK(f->outcome.failed);
  CHECK(f->outcome.failure == bad.failure);
  CHECK(f->task == "dt = 2e-06, seed 1");
  CHECK(back.other_engine("e") == 1);
  CHECK_FALSE(back.find("0000000000000000"));
}

TEST_CASE("ledger: its header alone (every row taken out to be rerun) is an empty ledger that takes new rows") {
  const fs::path p = fresh("header_only") / "study.csv";
  std::ofstream(p) << kHeader << "\n";
  RunRecord done;
  done.qoi = {1.25};
  done.engine = std::string("e");
  {
    Ledger l(p);
    CHECK(l.size() == 0);
    l.append("0123456789abcdef", "sweep dt repose_angle", "dt = 1e-05 seed 1", done);
  }
  CHECK(slurp(p) == std::string(kHeader) + "\n0123456789abcdef,sweep dt repose_angle,dt = 1e-05 seed 1,done,1.25,0,0,0,e,\n");
  const Ledger back(p);
  CHECK(back.size() == 1);
}

TEST_CASE("ledger: a bad row is an error naming file, line and column, and a torn last line is dropped") {
  const fs::path d = fresh("bad");
  const std::string good = "0123456789abcdef,s,t,done,1.5,1,2,3,e,\n";
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(d / name) << text;
    return d / name;
  };
  std::string e = error_of(write("nan.csv", std::string(kHeader) + good + "1123456789abcdef,s,t,done,nan,1,2,3,e,\n"));
  CHECK(e.find("nan.csv:3") != std::string::npos);
  CHECK(e.find("qoi") != std::string::npos);
  e = error_of(write("key.csv", std::string(kHeader) + "xyz,s,t,done,1,1,2,3,e,\n"));
  CHECK(e.find("key.csv:2") != std::string::npos);
  CHECK(e.find("16 hex") != std::string::npos);
  e = error_of(write("status.csv", std::string(kHeader) + "0123456789abcdef,s,t,finished,1,1,2,3,e,\n"));
  CHECK(e.find("status") != std::string::npos);
  e = error_of(write("neg.csv", std::string(kHeader) + "0123456789abcdef,s,t,done,1,-1,2,3,e,\n"));
  CHECK(e.find("wall_s") != std::string::npos);
  e = error_of(write("ragged.csv", std::string(kHeader) + "0123456789abcdef,s,t,done,1\n"));
  CHECK(e.find("ragged.csv:2") != std::string::npos);
  e = error_of(write("column.csv", "key,study,task,status,qoi,wall_s,particle_steps,particles,engine,failure,extra\n"
                                   "0123456789abcdef,s,t,done,1.5,1,2,3,e,,x\n"));
  INFO(e);
  CHECK(e.find("extra") != std::string::npos);
  e = error_of(write("twice.csv", std::string(kHeader) + good + "0123456789abcdef,s,t,done,1.6,1,2,3,e,\n"));
  CHECK(e.find("twice.csv:3") != std::string::npos);
  CHECK(e.find("lines 2 and 3") != std::string::npos);
  // A kill during an append: the last line has no newline. Dropped, the rest kept, the file repaired.
  const fs::path torn = write("torn.csv", std::string(kHeader) + good + "1123456789abcdef,s,t,do");
  const Ledger l(torn);
  CHECK(l.size() == 1);
  CHECK(slurp(torn) == std::string(kHeader) + good);
}

TEST_CASE("ledger: the ledger alone (no run records) is enough to skip every finished task of a sweep") {
  const fs::path d = fresh("skip");
  const auto base = model::SceneDoc::parse_file(test::source_path("datasets/scenes/hertz_impact_m1.toml"));
  SweepOptions o;
  o.vary = "dt";
  o.qoi = "peak_force";
  o.values = {1.28e-5, 6.4e-6, 3.2e-6};
  o.quiet = true;
  o.runs = d / "runs";
  SweepResult first;
  {
    Ledger l(d / "ledger.csv");
    o.ledger = &l;
    first = sweep(base, o);
    CHECK(first.executed == 3);
    CHECK(l.size() == 3);
  }
  fs::remove_all(d / "runs");  // another machine: only the committed ledger came along
  Ledger l(d / "ledger.csv");
  o.ledger = &l;
  const SweepResult again = sweep(base, o);
  CHECK(again.executed == 0);
  CHECK(again.read_back == 3);
  CHECK_FALSE(fs::exists(d / "runs"));
  for (std::size_t k = 0; k < first.points.size(); ++k)
    CHECK(std::memcmp(&again.points[k].qoi, &first.points[k].qoi, sizeof(double)) == 0);
}
