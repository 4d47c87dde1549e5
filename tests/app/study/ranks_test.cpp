// SPDX-License-Identifier: MIT
// A study over 2 MPI ranks (app/study/ranks.h) gives the QoIs of the same study with --jobs 2, bit for bit:
// a sweep (`pastemix sweep ... --mpi`) and a calibration (`mpirun -np 2 pastemix calibrate rheology ...`,
// MPI implied by the launch), each writing its ledger from rank 0 alone. Skipped, saying so, only when
// mpirun is absent; a build without MPI must then refuse --mpi.
#include "app/study/ranks.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/params.h"
#include "lab/parameters_toml.h"
#include "lab/rheology/paste_rheology.h"
#include "tests/fresh_dir.h"
#include "tests/run_command.h"

namespace fs = std::filesystem;
using namespace pastemix;
using pastemix::app::study::Ranks;
namespace rh = pastemix::lab::rheology;

namespace {

fs::path fresh(const std::string& name) {
  return test::fresh_dir(fs::temp_directory_path() / fmt::format("pastemix_ranks_{}_{}", name, getpid()));
}

std::string slurp(const fs::path& p) { return test::file_text(p); }

bool have_mpirun() { return std::system("command -v mpirun >/dev/null 2>&1") == 0; }

// Open MPI refuses root without these; --oversubscribe: 2 ranks on a machine that may have fewer free cores.
const char* kMpirun = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 mpirun -np 2 "
                      "--oversubscribe";

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

// The ledger's key and qoi columns, sorted (rows come in finishing order).
std::string ledger_qois(const fs::path& csv) {
  std::istringstream in(slurp(csv));
  std::vector<std::string> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> c;
    std::stringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) c.push_back(cell);
    if (c.size() >= 5) rows.push_back(c[0] + " " + c[4]);
  }
  std::sort(rows.begin(), rows.end());
  std::string out;
  for (const auto& r : rows) out += r + "\n";
  return out;
}

}  // namespace

TEST_CASE("mpirun -np 2: a sweep and a calibration give the QoIs of --jobs 2, the ledger written by rank 0") {
  if (!have_mpirun()) {
    MESSAGE("SKIPPED: mpirun is not installed (apt-get install openmpi-bin libopenmpi-dev; scripts/install-deps.sh)");
    return;
  }
  REQUIRE_MESSAGE(Ranks::built_in(), "mpirun is here but this pastemix was built without MPI: "
                                             "install libopenmpi-dev and reconfigure");
  const fs::path d = fresh("sweep");
  const std::string sweep = fmt::format(
      "sweep '{}' --vary dt --qoi peak_force --values 1.28e-5 6.4e-6 3.2e-6 1.6e-6 --tol 0.5",
      test::source_path("datasets/scenes/hertz_impact_m1.toml"));
  const auto mpi = test::run_pastemix(
      sweep + fmt::format(" --mpi --out '{0}/mpi' --ledger '{0}/mpi.csv'", d.string()), kMpirun);
  INFO(mpi.output);
  REQUIRE(mpi.exit_code == 0);
  const auto jobs = test::run_pastemix(sweep + fmt::format(" --jobs 2 --out '{0}/jobs' --ledger '{0}/jobs.csv'", d.string()));
  REQUIRE(jobs.exit_code == 0);
  CHECK(qoi_columns(d / "mpi" / "sweep.csv") == qoi_columns(d / "jobs" / "sweep.csv"));
  CHECK(ledger_qois(d / "mpi.csv") == ledger_qois(d / "jobs.csv"));
  CHECK(std::count(mpi.output.begin(), mpi.output.end(), '\n') > 0);
  // One table: rank 1 prints nothing of its own.
  const std::string title = "sweep dt on";
  CHECK(mpi.output.find(title) == mpi.output.rfind(title));
  // A rerun under MPI reads every task back from the ledger.
  const auto again = test::run_pastemix(
      sweep + fmt::format(" --mpi --out '{0}/mpi2' --ledger '{0}/mpi.csv'", d.string()), kMpirun);
  CHECK(again.output.find("runs: 0 done now, 4 read back") != std::string::npos);

  // The rheology calibration on its tiny scene, MPI from the launch alone (no --mpi).
  rh::Model m;
  m.anchor.yield_stress = 137.97, m.anchor.yield_stress_sd = 6.03;
  m.anchor.plastic_viscosity = 0.7, m.anchor.curve = "published_4_19", m.anchor.density = 1843.0;
  const rh::Prior p = rh::prior(m.family, m.anchor);
  m.shape = p.mid(), m.shape_sd = p.sd();
  lab::ReduceResult rr;
  rr.parameters = rh::store_parameters(m, {}, {0.725}, {"2"}, "test anchor");
  const std::string store = (d / "parameters.toml").string();
  std::ofstream(store) << lab::parameters_toml(rr, {"test", "test", "now"});
  auto cal = [&](const std::string& out) {
    return fmt::format(
        "calibrate rheology --case 2 --scene '{}' --set fluid.0.rheology_from='\"{}\"' --params '{}' --seeds 2 "
        "--points 3 --refine 0 --values 0.3 0.45 0.6 --layer-thickness 0.005 --target-layers 0.002,0.004,0.002 "
        "--out '{}/{}' --ledger '{}/{}.csv' --no-store --quiet",
        test::source_path("tests/app/study/data/rheology_tiny.toml"), store, store, d.string(), out, d.string(), out);
  };
  const auto cal_mpi = test::run_pastemix(cal("cal_mpi"), kMpirun);
  INFO(cal_mpi.output);
  const auto cal_jobs = test::run_pastemix(cal("cal_jobs") + " --jobs 2");
  REQUIRE((cal_mpi.exit_code == 0 || cal_mpi.exit_code == 3));
  CHECK(cal_mpi.exit_code == cal_jobs.exit_code);
  CHECK(cal_mpi.output.find("runs: 6 in all, 6 computed now") != std::string::npos);
  CHECK(ledger_qois(d / "cal_mpi.csv") == ledger_qois(d / "cal_jobs.csv"));
  const std::string ledger = slurp(d / "cal_mpi.csv");
  CHECK(std::count(ledger.begin(), ledger.end(), '\n') == 7);
  fs::remove_all(d);
}

TEST_CASE("without MPI built in, --mpi is refused with a clear message") {
  if (Ranks::built_in()) {
    MESSAGE("this build has MPI: the refusal is not reachable here");
    return;
  }
  const auto r = test::run_pastemix(fmt::format("sweep '{}' --vary dt --qoi peak_force --values 1e-5 --mpi --out /tmp/x",
                                                test::source_path("datasets/scenes/hertz_impact_m1.toml")));
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("built without MPI") != std::string::npos);
}
