// SPDX-License-Identifier: MIT
// `pastemix maps` and `pastemix score` through the built command (app/cmd_analysis.cpp): good runs write
// their outputs; bad inputs exit 2, name the file and the field, and write nothing.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "analysis/maps/mixing_map.h"
#include "analysis/maps/result_file.h"
#include "analysis/score/score.h"
#include "base/rng.h"
#include "tests/analysis/result_fixture.h"
#include "tests/run_command.h"
#include "base/units.h"

namespace fs = std::filesystem;
using namespace pastemix::test;
using namespace pastemix::analysis;

namespace {

ResultSpec rock_result(double r1) {
  ResultSpec s;
  s.final = {{{0.075, 0.0825, 0.085}, r1}, {{0.125, 0.0825, 0.085}, 0.011}, {{0.02, 0.02, 0.04}, 0.008},
             {{0.10, 0.0825, 0.115}, 0.008}};
  return s;
}

// A scratch folder with two result files and a lab.h5 whose case 3 equals the first result's map.
struct Fixture : ScratchDir {
  Fixture(const std::string& name) : ScratchDir(name) {
    write_result(dir / "r1.h5", rock_result(0.010));
    auto s2 = rock_result(0.0105);
    s2.seed = 8;
    write_result(dir / "r2.h5", s2);
    const auto r = read_result(dir / "r1.h5", {});
    MixingInputs in;
    in.surface_z = 0.10;
    in.paste_density = 1843;
    in.solids_fraction = 0.75;
    in.K = 3570;
    const MixingMap m = mixing_map(in, ParticleView{r.position, r.radius, r.density});
    LabSpec lab;
    lab.C = m.C;
    lab.S = m.S;
    lab.flag = m.flag;
    lab.M_wr = m.rock_mass;
    lab.M_paste = m.paste_dried_mass;
    write_lab(dir / "lab.h5", lab);
  }
  std::string p(const std::string& n) const { return fmt::format("'{}'", (dir / n).string()); }
  // Runs a command that must fail with exit 2, mention every `needles`, and write nothing under out/.
  void expect_bad(const std::string& args, const std::vector<std::string>& needles) const {
    const auto r = run_pastemix(fmt::format("{} --out {}", args, p("out")));
    INFO(args);
    INFO(r.output);
    CHECK(r.exit_code == 2);
    for (const auto& n : needles) CHECK(r.output.find(n) != std::string::npos);
    CHECK(!fs::exists(dir / "out"));
  }
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("cli: maps writes maps.h5 and a PNG, with the accounting and the seed copied") {
  Fixture f("cli_maps");
  const auto r = run_pastemix(fmt::format("maps {} --lab 3 --lab-h5 {} --out {}", f.p("r1.h5"), f.p("lab.h5"),
                                          f.p("out")));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("relative error") != std::string::npos);
  CHECK(r.output.find("K = 3570 kg/m3") != std::string::npos);
  pastemix::H5Reader h5(f.dir / "out" / "maps.h5");
  CHECK(h5.attribute_int("/", "seed") == 7);
  CHECK(h5.attribute_string("/", "scene_hash") == "00000000deadbeef");
  CHECK(h5.attribute_double("/accounting", "conservation_relative_error") < 1e-9);
  CHECK(h5.dims("/blocks/C") == std::vector<std::uint64_t>{4, 3, 3});
  CHECK(fs::exists(f.dir / "out" / "maps.png"));
}

TEST_CASE("cli: score of a result equal to the lab grid is 0 pp and two realizations show the spread") {
  Fixture f("cli_score");
  auto r = run_pastemix(fmt::format("score {} --lab 3 --lab-h5 {} --out {}", f.p("r1.h5"), f.p("lab.h5"), f.p("one")));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("mean absolute C error: 0.00 pp over 36 blocks") != std::string::npos);
  CHECK(r.output.find("36 of 36 compared blocks agree") != std::string::npos);
  r = run_pastemix(fmt::format("score {} {} --lab 3 --lab-h5 {} --out {}", f.p("r1.h5"), f.p("r2.h5"),
                               f.p("lab.h5"), f.p("two")));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("2 realizations (seeds 7, 8)") != std::string::npos);
  const std::string toml = read_text(f.dir / "two" / "score.toml");
  CHECK(toml.find("realizations = 2") != std::string::npos);
  CHECK(read_text(f.dir / "two" / "score.csv").find("M_221,2,2,1,") != std::string::npos);
  for (int k = 1; k <= 3; ++k) CHECK(fs::exists(f.dir / "two" / fmt::format("score_layer_{}.png", k)));
}

TEST_CASE("cli: bad inputs exit 2, name the file and field, and write nothing") {
  Fixture f("cli_bad");
  const std::string lab = fmt::format(" --lab-h5 {}", f.p("lab.h5"));
  f.expect_bad("maps " + f.p("missing.h5"), {"missing.h5", "no such file"});
  std::ofstream(f.dir / "text.h5") << "not an HDF5 file\n";
  f.expect_bad("score " + f.p("text.h5") + " --lab 3" + lab, {"text.h5", "HDF5"});
  auto s = rock_result(0.01);
  s.material_density = false;
  write_result(f.dir / "nodens.h5", s);
  f.expect_bad("maps " + f.p("nodens.h5"), {"nodens.h5", "/material_density"});
  s = rock_result(0.01);
  s.surface = false;
  write_result(f.dir / "nosurf.h5", s);
  f.expect_bad("score " + f.p("r1.h5") + " " + f.p("nosurf.h5") + " --lab 3" + lab,
               {"nosurf.h5", "fluid_surface_z", "--surface-z"});
  f.expect_bad("score " + f.p("r1.h5") + " --lab 9" + lab, {"lab.h5", "case 9 is not a mixing case"});
  f.expect_bad("score " + f.p("r1.h5") + " --lab 6" + lab, {"lab.h5", "case 6 has no lab block grid", "maps"});
  f.expect_bad("score " + f.p("r1.h5") + " --lab 3 --lab-h5 " + f.p("nolab.h5"), {"nolab.h5", "lab reduce"});
  f.expect_bad("maps " + f.p("r1.h5") + " --solids 75", {"--solids", "(0, 1]"});
  f.expect_bad("score " + f.p("r1.h5") + " --lab 3 --blocks 3,3" + lab, {"--blocks", "4 x 3"});
  // With the override the missing surface is fine, and the output says where it came from.
  const auto r = run_pastemix("maps " + f.p("nosurf.h5") + " --surface-z 0.1 --out " + f.p("ok"));
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(r.output.find("command line --surface-z") != std::string::npos);
  CHECK(r.output.find("K = unknown") != std::string::npos);
}

TEST_CASE("cli: score refuses a file given twice, a copied realization and an ensemble of different scenes") {
  Fixture f("cli_ensemble");
  const std::string lab = fmt::format(" --lab 3 --lab-h5 {}", f.p("lab.h5"));
  f.expect_bad("score " + f.p("r1.h5") + " " + f.p("r1.h5") + lab, {"r1.h5", "given twice (as result 1 and 2)"});
  fs::copy_file(f.dir / "r1.h5", f.dir / "copy.h5");
  f.expect_bad("score " + f.p("r1.h5") + " " + f.p("copy.h5") + lab,
               {"copy.h5", "seed 7 of scene 00000000deadbeef is also the seed of", "the same realization twice"});
  auto other = rock_result(0.0105);
  other.seed = 9;
  other.scene_hash = "1111111111111111";
  other.scene_text = "# another scene\n";
  write_result(f.dir / "other.h5", other);
  // Seeded realizations of one scene differ only in the top-level seed line (and so in scene_hash): one ensemble.
  auto seeded = rock_result(0.0105);
  seeded.seed = 11;
  seeded.scene_hash = "2222222222222222";
  seeded.scene_text = "seed = 11\n# synthetic scene for the analysis tests\n";
  write_result(f.dir / "seeded.h5", seeded);
  {
    auto base = rock_result(0.010);
    base.scene_text = "seed = 7\n# synthetic scene for the analysis tests\n";
    write_result(f.dir / "seeded7.h5", base);
  }
  const auto ok = run_pastemix("score " + f.p("seeded7.h5") + " " + f.p("seeded.h5") + lab + " --out " + f.p("ens"));
  INFO(ok.output);
  CHECK(ok.exit_code == 0);
  CHECK(ok.output.find("2 realizations (seeds 7, 11)") != std::string::npos);
  f.expect_bad("score " + f.p("r1.h5") + " " + f.p("other.h5") + lab,
               {"other.h5", "scene_hash", "scene 1111111111111111 differs", "realizations of one scene"});
}

TEST_CASE("cli: repose measures the last snapshot of result files, with the mean over seeds") {
  Fixture f("cli_repose");
  // Two cone piles of 35 deg (base radius 6 cm, 3 mm spheres filling the cone).
  for (int k = 0; k < 2; ++k) {
    pastemix::test::ResultSpec spec;
    spec.seed = 11 + k;
    pastemix::Rng rng(static_cast<std::uint64_t>(3 + k));
    const double R = 0.06, t = std::tan(35.0 * pastemix::units::pi / 180.0), d = 0.003;
    while (spec.final.size() < 20000) {
      const double x = rng.uniform(-R, R), y = rng.uniform(-R, R), top = rng.uniform(d, R * t);
      if (top > R * t - std::hypot(x, y) * t) continue;
      spec.final.push_back({{x, y, top - d / 2}, d / 2});
    }
    pastemix::test::write_result(f.dir / fmt::format("pile{}.h5", k), spec);
  }
  const auto r = run_pastemix(fmt::format("repose {} {}", f.p("pile0.h5"), f.p("pile1.h5")));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("seed 11") != std::string::npos);
  const auto at = r.output.find("mean over 2 files: ");
  REQUIRE(at != std::string::npos);
  const double mean = std::stod(r.output.substr(at + 19));
  CHECK(std::abs(mean - 35.0) < 1.0);
  // A file that is not a result is exit 2 naming it.
  std::ofstream(f.dir / "text.h5") << "not an HDF5 file\n";
  const auto bad = run_pastemix("repose " + f.p("text.h5"));
  CHECK(bad.exit_code == 2);
  CHECK(bad.output.find("text.h5") != std::string::npos);
}

TEST_CASE("cli: maps and score refuse a state that is not at rest, and --allow-moving marks it") {
  Fixture f("cli_moving");
  auto s = rock_result(0.010);
  s.velocity = {{0.0, 0.0, -0.5}};  // the 10 mm sphere (11.56 g at 2760 kg/m3, centre below the surface) still sinks
  s.velocity.push_back({0.0, 0.0, 0.0});
  s.velocity.push_back({0.0, 0.0, 0.0});
  s.velocity.push_back({0.0, 0.005, 0.0});  // below the 0.01 m/s limit: at rest
  write_result(f.dir / "moving.h5", s);
  const double moving_g = 1e3 * 2760.0 * 4.0 / 3.0 * pastemix::units::pi * 1e-6;
  f.expect_bad("maps " + f.p("moving.h5"), {"moving.h5", "not at rest", fmt::format("{:.4g} g of rock moving", moving_g),
                                             "--allow-moving", "at_rest"});
  f.expect_bad("score " + f.p("moving.h5") + " --lab 3 --lab-h5 " + f.p("lab.h5"), {"moving.h5", "not at rest"});
  // A raised limit accepts it; --allow-moving maps it, marked in the output, maps.h5 and score.toml.
  auto r = run_pastemix("maps " + f.p("moving.h5") + " --moving-mass 12 --out " + f.p("limit"));
  INFO(r.output);
  CHECK(r.exit_code == 0);
  r = run_pastemix("maps " + f.p("moving.h5") + " --allow-moving --out " + f.p("allowed"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("NOT AT REST") != std::string::npos);
  pastemix::H5Reader h5(f.dir / "allowed" / "maps.h5");
  CHECK(h5.attribute_int("/", "at_rest") == 0);
  CHECK(h5.attribute_double("/", "moving_mass_kg") == doctest::Approx(1e-3 * moving_g).epsilon(1e-9));
  r = run_pastemix("score " + f.p("moving.h5") + " --allow-moving --lab 3 --lab-h5 " + f.p("lab.h5") + " --out " +
                   f.p("scored"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("HEADLINE: mixing case 3, 1 realization (seed 7), NOT AT REST") != std::string::npos);
  CHECK(read_text(f.dir / "scored" / "score.toml").find("state = \"NOT AT REST (--allow-moving)\"") !=
        std::string::npos);
  // A snapshot without velocities: unknown motion is refused too.
  s.velocities = false;
  write_result(f.dir / "novel.h5", s);
  f.expect_bad("maps " + f.p("novel.h5"), {"novel.h5", "no velocities"});
}

TEST_CASE("cli: the score's headline comes first and its per-layer masses sum to the blocks' total") {
  Fixture f("cli_headline");
  const auto r = run_pastemix(fmt::format("score {} {} --lab 3 --lab-h5 {} --out {}", f.p("r1.h5"), f.p("r2.h5"),
                                          f.p("lab.h5"), f.p("out")));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("HEADLINE: mixing case 3, 2 realizations (seeds 7, 8), scored at rest") <
        r.output.find("mean absolute C error: 0"));
  // The lab grid is r1's own map: every layer matches, with r2's spread in the tolerance.
  CHECK(r.output.find("3 of 3 layers matched") != std::string::npos);
  const std::string toml = read_text(f.dir / "out" / "score.toml");
  CHECK(toml.find("[headline]") < toml.find("[score]"));
  // Per-layer sums against the maps' blocks, per realization.
  for (const char* name : {"r1.h5", "r2.h5"}) {
    const auto res = read_result(f.dir / name, {});
    MixingInputs in;
    in.surface_z = 0.10;
    in.paste_density = 1843;
    in.solids_fraction = 0.75;
    in.K = 3570;
    const MixingMap m = mixing_map(in, ParticleView{res.position, res.radius, res.density});
    double blocks = 0.0;
    for (double x : m.rock_mass) blocks += x;
    const auto s = score_against_lab(read_lab_case(f.dir / "lab.h5", 3, true), {m}, {Realization{}});
    double layers = 0.0;
    for (const auto& h : s.headline) layers += h.model.mean;
    CHECK(layers == doctest::Approx(blocks).epsilon(1e-12));
    CHECK(blocks > 0.0);
  }
}
