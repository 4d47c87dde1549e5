// SPDX-License-Identifier: MIT
#include "lab/drag/settling.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <doctest/doctest.h>

#include "base/error.h"
#include "tests/run_command.h"
#include "base/units.h"

using namespace pastemix::lab::drag;
namespace fs = std::filesystem;

namespace {

const std::string kSuspensions =
    "suspension,density_kg_m3,plastic_viscosity_Pa_s,yield_stress_Pa\n1,1280,0.0131,30.5\n2,1254,0.0095,22.5\n";
const std::string kHeader =
    "row_id,suspension,diameter_m,sphere_density_kg_m3,terminal_velocity_m_s,Re_prime_printed,Cd_printed\n";

fs::path write(const std::string& name, const std::string& text) {
  const auto dir = fs::temp_directory_path() / "pastemix_settling_test";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

// Expects read_settling_data to throw an InputError whose message contains `where` and `what`.
void expect_error(const std::string& spheres, const std::string& where, const std::string& what) {
  const auto sus = write("sus.csv", kSuspensions), sph = write("sph.csv", spheres);
  try {
    read_settling_data(sph, sus);
    FAIL("expected an InputError");
  } catch (const pastemix::InputError& e) {
    const std::string msg = e.what();
    CHECK_MESSAGE(msg.find(where) != std::string::npos, msg);
    CHECK_MESSAGE(msg.find(what) != std::string::npos, msg);
  }
}

}  // namespace

TEST_CASE("settling: Re' (4.18) and Cd (4.17) reproduce Table 4.3 within 1.5 % for all 121 spheres") {
  const auto d = read_settling_dataset(pastemix::test::source_path("datasets/thesis"));
  REQUIRE(d.spheres.size() == 121);
  int count[7] = {};
  for (const auto& s : d.spheres) {
    ++count[s.suspension];
    CHECK_MESSAGE(std::abs(s.re / s.re_printed - 1.0) <= 0.015, "row ", s.row_id);
    CHECK_MESSAGE(std::abs(s.cd / s.cd_printed - 1.0) <= 0.015, "row ", s.row_id);
  }
  CHECK(count[1] == 27);
  CHECK(count[2] == 16);
  CHECK(count[3] == 18);
  CHECK(count[4] == 17);
  CHECK(count[5] == 19);
  CHECK(count[6] == 24);
  // The dataset README's verification: max differences 0.82 % (Re') and 1.28 % (Cd).
  CHECK(d.max_re_error == doctest::Approx(0.0082).epsilon(0.01));
  CHECK(d.max_cd_error == doctest::Approx(0.0128).epsilon(0.01));
  // Row 1 by hand: rho_f 1280, eta 0.0131, tau 30.5, d 0.0159, rho_p 6450, v 0.1.
  const auto& r1 = d.spheres.front();
  CHECK(r1.re == doctest::Approx(1280 * 0.01 / (30.5 + 0.0131 * 0.1 / 0.0159)));
  CHECK(r1.cd == doctest::Approx(2 / (0.01 * 1280) * (2.0 / 3 * (6450 - 1280) * 0.0159 * 9.81 - pastemix::units::pi * 30.5)));
}

TEST_CASE("settling: bad rows are InputErrors naming file:line and column") {
  expect_error(kHeader + "1,3,0.0159,6450,0.1,0.42,69.03\n", "sph.csv:2", "unknown suspension id 3");
  expect_error(kHeader + "1,1,0.0159,6450,0.1,0.42,69.03\n1,1,0.019,5832,0.21,1.84,16.65\n", "sph.csv:3",
               "duplicate row_id");
  expect_error(kHeader + "1,1,-0.0159,6450,0.1,0.42,69.03\n", "sph.csv:2", "diameter_m");
  expect_error(kHeader + "1,1,0.0159,6450,nan,0.42,69.03\n", "sph.csv:2", "terminal_velocity_m_s");
  expect_error(kHeader + "1,1,0.0159,1000,0.1,0.42,69.03\n", "sph.csv:2", "cannot settle");
  expect_error(kHeader + "1,1,0.001,6450,0.1,0.42,69.03\n", "sph.csv:2", "could not settle");  // yield > weight
  expect_error("row_id,suspension,diameter_m,sphere_density_kg_m3,terminal_velocity_m_s,Re_prime_printed,Cd_printed,x\n"
               "1,1,0.0159,6450,0.1,0.42,69.03,3\n",
               "sph.csv:1", "'x'");
  const auto sus = write("sus_dup.csv", kSuspensions + "1,1200,0.01,3\n");
  CHECK_THROWS_WITH_AS(read_suspensions(sus), doctest::Contains("sus_dup.csv:4"), pastemix::InputError);
}

TEST_CASE("settling: the thesis model table joins and its clay properties are checked") {
  const auto dir = fs::path(pastemix::test::source_path("datasets/thesis"));
  const auto sus = read_suspensions(dir / "valentik_whitmore_1965_suspensions.csv");
  const auto rows = read_thesis_model(dir / "valentik_whitmore_1965_thesis_model.csv", sus);
  REQUIRE(rows.size() == 93);
  int both = 0;
  for (const auto& r : rows) both += r.v_measured && r.v_model;
  CHECK(both == 90);
  // A row whose printed clay yield stress disagrees with its suspension is rejected.
  std::ifstream in(dir / "valentik_whitmore_1965_thesis_model.csv");
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  const auto pos = first.find(",30.5,");
  REQUIRE(pos != std::string::npos);
  first.replace(pos, 6, ",31.5,");
  const auto bad = write("model.csv", header + "\n" + first + "\n");
  CHECK_THROWS_WITH_AS(read_thesis_model(bad, sus), doctest::Contains("model.csv:2: column 'clay_yield_stress_Pa'"),
                       pastemix::InputError);
}
