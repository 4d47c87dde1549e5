// SPDX-License-Identifier: MIT
// The funnel pour of the thesis's multi-ball test (validation/fluid/ball_pour.*) on a reduced size, and the
// `pastemix validate ball-pour` command that runs it (app/cmd_fluid_pour.cpp).
#include "validation/fluid/ball_pour.h"

#include <doctest/doctest.h>

#include <array>
#include <filesystem>

#include "tests/run_command.h"

using namespace pastemix::validation;

namespace {
std::filesystem::path source_dir() { return PASTEMIX_SOURCE_DIR; }
}  // namespace

TEST_CASE("fluid engine: 12 balls poured from the funnel: none left in it, all at rest, suspended in Z 8.5-13.5 cm") {
  // Reduced from 68 balls x 15 seeds (`pastemix validate ball-pour`): 12 balls x 2 seeds, same funnel, fall,
  // paste and time step.
  FunnelPour p;
  p.balls = 12;
  for (std::uint64_t seed : {1, 2}) {
    const BallPourResult b = ball_pour(p, seed);
    INFO("seed " << seed << ": Z " << b.z_min << " - " << b.z_max << ", rest " << b.at_rest << ", funnel "
                 << b.in_funnel << ", t " << b.t_end);
    CHECK(b.ids_ok);
    CHECK(b.in_funnel == 0);
    CHECK(b.on_floor == 0);
    CHECK(b.at_rest == 12);
    CHECK(b.t_end < p.end_time);  // stopped because every ball rests
    CHECK(b.z_min > 0.085);
    CHECK(b.z_max < 0.135);
  }
}

TEST_CASE("ball pour with flow: 6 balls through the funnel into the moving paste rest suspended in it") {
  // Issue 22's ball pour with dynamics = "flow", reduced: 6 balls, 2 cm cells (10 x 8 x 9: nearly cubic, the
  // 16.5 cm side in 8 cells of 2.06 cm), the same funnel, fall, paste and step. The paste is regularised, so
  // "at rest" is |v| < 0.1 mm/s held for 0.1 s (ball_pour.h), and the run ends there, not at end_time.
  FunnelPour p;
  p.balls = 6;
  p.end_time = 2.0;
  p.flow = PourFlow{};
  p.flow->cell = 0.02;
  const auto n = pour_flow_cells(p, *p.flow);
  CHECK(n == std::array<int, 3>{10, 8, 9});
  CHECK(ball_pour_scene(p, 1).find("dynamics = \"flow\"\ncells = [10, 8, 9]\ntop = 0.18") != std::string::npos);
  const BallPourResult b = ball_pour(p, 1);
  MESSAGE("Z " << b.z_min << " - " << b.z_max << ", rest " << b.at_rest << ", funnel " << b.in_funnel << ", floor "
            << b.on_floor << ", t " << b.t_end << ", cycles " << b.flow_cycles << ", surface " << b.surface);
  CHECK(b.ids_ok);
  CHECK(b.flow_cycles > 0);
  CHECK(b.in_funnel == 0);
  CHECK(b.on_floor == 0);
  CHECK(b.at_rest == 6);
  CHECK(b.t_end < p.end_time);
  CHECK(b.z_max < p.paste_depth);  // below the rim: in the paste, not floating on it
  CHECK(b.z_min > 0.0063 + 1e-4);
  // The area-mean surface: the paste's volume and the balls' over the frame's area, a 0.19 mm rise for 6 balls.
  CHECK(b.surface == doctest::Approx(0.15 + 6 * 1.0474e-6 / (0.2 * 0.165)).epsilon(2e-3));
}

TEST_CASE("fluid CLI: validate ball-pour writes the positions and the maps, all balls out of the funnel") {
  const std::string fixture = (source_dir() / "tests/model/fluid/data/parameters.toml").string();
  const auto dir = std::filesystem::temp_directory_path() / "pastemix_ball_pour_test";
  std::filesystem::remove_all(dir);
  const auto r = pastemix::test::run_pastemix("validate ball-pour --seeds 1 --balls 6 --params " + fixture + " --out " +
                                              dir.string());
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(r.output.find("suspended at rest 6/6 (100.0 %)") != std::string::npos);
  CHECK(r.output.find("on the floor 0; left in the funnel 0; ids conserved") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "ball_pour.csv"));
  if (r.output.find("no PNG maps written") == std::string::npos) {  // matplotlib present
    CHECK(std::filesystem::exists(dir / "ball_pour_maps.png"));
    CHECK(std::filesystem::exists(dir / "ball_pour_z.png"));
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("fluid CLI: validate ball-pour --first-seed runs the later seeds alone, each the same run as in the full set") {
  const std::string fixture = (source_dir() / "tests/model/fluid/data/parameters.toml").string();
  const auto dir = std::filesystem::temp_directory_path() / "pastemix_ball_pour_seeds";
  std::filesystem::remove_all(dir);
  const std::string base = "validate ball-pour --balls 4 --params " + fixture + " --out " + dir.string();
  const auto both = pastemix::test::run_pastemix(base + " --seeds 2");
  const auto second = pastemix::test::run_pastemix(base + " --seeds 1 --first-seed 2");
  INFO(both.output << "\n---\n" << second.output);
  REQUIRE(both.exit_code == 0);
  REQUIRE(second.exit_code == 0);
  // Seed 2's table row (seed, Z range, counts, exit times; the wall and CPU columns differ) is the same in both.
  auto row = [](const std::string& out) {
    const auto at = out.find("\n    2 ");
    return at == std::string::npos ? std::string() : out.substr(at, 70);
  };
  CHECK_FALSE(row(second.output).empty());
  CHECK(row(second.output) == row(both.output));
  CHECK(second.output.find("\n    1 ") == std::string::npos);
  const auto bad = pastemix::test::run_pastemix(base + " --first-seed 0");
  CHECK(bad.exit_code == 2);
  CHECK(bad.output.find("--first-seed") != std::string::npos);
  std::filesystem::remove_all(dir);
}
