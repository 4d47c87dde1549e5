// SPDX-License-Identifier: MIT
// `pastemix flow run`: the HDF5 holds the snapshots the schema names, and the XDMF points at datasets that
// exist with the dimensions it declares.
#include "model/flow/flow_output.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "base/h5.h"
#include "tests/fresh_dir.h"
#include "tests/run_command.h"

using namespace pastemix;

TEST_CASE("flow output: flow run writes HDF5 + XDMF that agree") {
  const std::string dir = pastemix::test::fresh_dir("model_flow_output_test_out").string();
  {
    std::ofstream f(dir + "/small.toml");
    f << "[flow]\nname = \"small\"\nbox = [0.04, 0.03, 0.05]\ncell = 0.01\nend_time = 0.04\noutput_interval = 0.02\n"
         "[flow.boundary]\nz_hi = \"open\"\n[flow.paste]\ndensity = 1850.0\nviscosity = 1.0\n"
         "[flow.initial]\npaste_below = 0.023\n";
  }
  const auto r = pastemix::test::run_pastemix("flow run " + dir + "/small.toml --out " + dir);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  H5Reader h5(dir + "/small.h5");
  const std::vector<double> times = h5.read_doubles("/flow/snapshots/time");
  REQUIRE(times.size() == 3);
  CHECK(times.back() == doctest::Approx(0.04));
  CHECK(h5.dims("/flow/snapshots/000002/velocity") == std::vector<std::uint64_t>{5, 3, 4, 3});
  const std::vector<double> alpha = h5.read_doubles("/flow/snapshots/000002/paste_fraction");
  double vol = 0.0;
  for (double a : alpha) vol += a * 1e-6;
  CHECK(vol == doctest::Approx(0.04 * 0.03 * 0.023).epsilon(1e-10));
  CHECK(h5.attribute_int("/flow", "nz") == 5);

  std::ifstream in(dir + "/small.xmf");
  std::stringstream buf;
  buf << in.rdbuf();
  const std::string x = buf.str();
  CHECK(x.find("3DCoRectMesh") != std::string::npos);
  const std::regex item("Dimensions=\"([0-9 ]+)\"[^>]*Format=\"HDF\">small.h5:([^<]+)<");
  int count = 0;
  for (auto it = std::sregex_iterator(x.begin(), x.end(), item); it != std::sregex_iterator(); ++it, ++count) {
    const std::string path = (*it)[2];
    REQUIRE(h5.exists(path));
    std::string dims;
    for (auto d : h5.dims(path)) {
      if (!dims.empty()) dims += ' ';
      dims += std::to_string(d);
    }
    CHECK(dims == (*it)[1].str());
  }
  CHECK(count == 12);  // 3 snapshots x 4 fields
}
