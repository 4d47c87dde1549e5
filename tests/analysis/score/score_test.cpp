// SPDX-License-Identifier: MIT
#include "analysis/score/score.h"

#include <cmath>

#include <doctest/doctest.h>

#include "analysis/maps/result_file.h"
#include "base/error.h"
#include "tests/analysis/result_fixture.h"
#include "base/units.h"

using namespace pastemix::analysis;
using namespace pastemix::test;

namespace {

// Rock in a few known blocks: a big rock in M_111 (capped S), a small one across M_221/M_321, one above.
ResultSpec synthetic_result() {
  ResultSpec s;
  s.final = {{{0.025, 0.0275, 0.085}, 0.010}, {{0.10, 0.0825, 0.08}, 0.006}, {{0.10, 0.0825, 0.12}, 0.006}};
  return s;
}

MixingMap map_of(const std::filesystem::path& p, double K) {
  const auto r = read_result(p, {});
  MixingInputs in;
  in.surface_z = r.surface_z.value;
  in.paste_density = r.paste_density.value;
  in.solids_fraction = r.solids_fraction.value;
  in.K = K;
  return mixing_map(in, ParticleView{r.position, r.radius, r.density});
}

// A lab spec whose grid equals `m` plus `offset` (fraction) on every C.
LabSpec lab_equal_to(const MixingMap& m, double offset) {
  LabSpec s;
  for (std::size_t b = 0; b < 36; ++b) {
    s.C.push_back(m.C[b] + offset);
    s.S.push_back(m.S[b]);
    s.flag.push_back(m.flag[b]);
    s.M_wr.push_back(m.rock_mass[b]);
    s.M_paste.push_back(m.paste_dried_mass[b]);
  }
  return s;
}

}  // namespace

TEST_CASE("score: a result equal to the lab grid scores 0 error and every S class agrees") {
  ScratchDir d("score_zero");
  write_result(d / "r.h5", synthetic_result());
  const MixingMap m = map_of(d / "r.h5", 3570);
  write_lab(d / "lab.h5", lab_equal_to(m, 0.0));
  const LabCase lab = read_lab_case(d / "lab.h5", 3, true);
  const Score s = score_against_lab(lab, {m}, {Realization{}});
  CHECK(s.blocks_compared == 36);
  CHECK(s.mae_pp == 0.0);
  CHECK(s.max_abs_error_pp == 0.0);
  CHECK(s.centre_mae_pp == 0.0);
  CHECK(s.classes_compared == 36);
  CHECK(s.classes_agree == 36);
  CHECK(!s.model_cone);  // the synthetic M_221 holds little rock
  CHECK(!s.lab_cone);
  CHECK(s.unmixed.mean == doctest::Approx(2760 * 4.0 / 3.0 * pastemix::units::pi * 2.16e-7).epsilon(1e-12));
  CHECK(s.lab_recovered_rock == doctest::Approx(m.in_blocks).epsilon(1e-12));
  // The block table, csv and toml carry the same numbers.
  CHECK(score_table(s).find("mean absolute C error: 0.00 pp over 36 blocks") != std::string::npos);
  CHECK(score_csv(s).find("M_111,1,1,1,") != std::string::npos);
  CHECK(score_toml(s, "sw", "cmd", "t", "lab.h5").find("C_mean_abs_error_pp = 0.0") != std::string::npos);
}

TEST_CASE("score: a lab grid 10 pp above the model gives 10 pp everywhere, centre column included") {
  ScratchDir d("score_ten");
  write_result(d / "r.h5", synthetic_result());
  const MixingMap m = map_of(d / "r.h5", 3570);
  write_lab(d / "lab.h5", lab_equal_to(m, 0.10));
  const Score s = score_against_lab(read_lab_case(d / "lab.h5", 3, true), {m}, {Realization{}});
  CHECK(s.mae_pp == doctest::Approx(10.0).epsilon(1e-9));
  REQUIRE(s.centre.size() == 3);
  for (const auto& c : s.centre) CHECK(c.error_pp == doctest::Approx(-10.0).epsilon(1e-9));
  CHECK(s.blocks[0].id == "M_111");
  CHECK(s.blocks[0].error_pp == doctest::Approx(-10.0).epsilon(1e-9));
}

TEST_CASE("score: the lab case reader tells unknown cases from cases without a grid") {
  ScratchDir d("score_cases");
  write_result(d / "r.h5", synthetic_result());
  write_lab(d / "lab.h5", lab_equal_to(map_of(d / "r.h5", 3570), 0.0));
  CHECK_THROWS_WITH_AS(read_lab_case(d / "lab.h5", 9, true), doctest::Contains("case 9 is not a mixing case"),
                       pastemix::InputError);
  CHECK_THROWS_WITH_AS(read_lab_case(d / "lab.h5", 6, true), doctest::Contains("case 6 has no lab block grid"),
                       pastemix::InputError);
  const LabCase six = read_lab_case(d / "lab.h5", 6, false);  // maps only need K: fine without a grid
  CHECK(!six.has_grid);
  CHECK(std::isnan(six.K));
}

TEST_CASE("score: a grain below the lab's 0.1 g weighing resolution counts as no rock in the S classes") {
  ScratchDir d("score_grain");
  ResultSpec r = synthetic_result();
  write_result(d / "lab_like.h5", r);
  const MixingMap without = map_of(d / "lab_like.h5", 3570);
  r.final.push_back({{0.175, 0.1375, 0.015}, 0.001});  // 0.0116 g in M_433
  write_result(d / "r.h5", r);
  const MixingMap with = map_of(d / "r.h5", 3570);
  write_lab(d / "lab.h5", lab_equal_to(without, 0.0));
  const LabCase lab = read_lab_case(d / "lab.h5", 3, true);
  const std::size_t b = static_cast<std::size_t>(pastemix::lab::block_index(4, 3, 3));
  CHECK(with.flag[b] == static_cast<int>(pastemix::lab::SFlag::capped));  // the lab formula itself is unchanged
  const Score s = score_against_lab(lab, {with}, {Realization{}});
  CHECK(s.blocks[b].model_class == SClass::no_rock);
  CHECK(s.classes_agree == 36);
  const Score strict = score_against_lab(lab, {with}, {Realization{}}, 0.0);
  CHECK(strict.blocks[b].model_class == SClass::capped);
  CHECK(strict.classes_agree == 35);
}

TEST_CASE("score: rock per layer and the deep share, lab and model") {
  ScratchDir d("score_layers");
  write_result(d / "r.h5", synthetic_result());
  const MixingMap m = map_of(d / "r.h5", 3570);
  LabSpec spec = lab_equal_to(m, 0.0);
  // Lab: put 0.3 kg in M_112 (layer 2) and 0.1 kg in M_113 (layer 3) on top of the model's layer-1 rock.
  spec.M_wr[static_cast<std::size_t>(pastemix::lab::block_index(1, 1, 2))] = 0.3;
  spec.M_wr[static_cast<std::size_t>(pastemix::lab::block_index(1, 1, 3))] = 0.1;
  write_lab(d / "lab.h5", spec);
  const LabCase lab = read_lab_case(d / "lab.h5", 3, true);
  const Score s = score_against_lab(lab, {m, m}, {Realization{}, Realization{}});
  REQUIRE(s.lab_layer_rock.size() == 3);
  REQUIRE(s.model_layer_rock.size() == 3);
  // All the synthetic rock in blocks is in layer 1 (the third rock, above the surface, counts there too).
  CHECK(s.model_layer_rock[0].mean == doctest::Approx(m.in_blocks).epsilon(1e-12));
  CHECK(s.model_layer_rock[0].sd == 0.0);
  CHECK(s.model_layer_rock[1].mean == 0.0);
  CHECK(s.model_deep_share.mean == 0.0);
  CHECK(s.lab_layer_rock[0] == doctest::Approx(m.in_blocks).epsilon(1e-12));
  CHECK(s.lab_layer_rock[1] == doctest::Approx(0.3).epsilon(1e-12));
  CHECK(s.lab_layer_rock[2] == doctest::Approx(0.1).epsilon(1e-12));
  CHECK(s.lab_deep_share == doctest::Approx(0.4 / (0.4 + m.in_blocks)).epsilon(1e-12));
  CHECK(score_toml(s, "sw", "cmd", "t", "lab.h5").find("lab_deep_share = ") != std::string::npos);
  CHECK(score_table(s).find("deep share (rock in layers 2-3 / rock in all blocks): lab ") != std::string::npos);
}

TEST_CASE("score: S values are scored where lab and model both have one") {
  ScratchDir d("score_S");
  write_result(d / "r.h5", synthetic_result());
  const MixingMap m = map_of(d / "r.h5", 100.0);  // a small K: S below its cap in the rock blocks
  int defined = 0;
  for (std::size_t b = 0; b < 36; ++b) defined += std::isfinite(m.S[b]) && m.rock_mass[b] >= kLabMassResolution;
  REQUIRE(defined >= 2);
  write_lab(d / "lab.h5", lab_equal_to(m, 0.0));
  const Score same = score_against_lab(read_lab_case(d / "lab.h5", 3, true), {m}, {Realization{}});
  CHECK(same.S_compared == defined);
  CHECK(same.S_mae_pp == 0.0);
  // The lab's S 0.2 lower in every block that has one (and cannot go below 0): 20 pp off, by block and in all.
  LabSpec shifted = lab_equal_to(m, 0.0);
  double want = 0.0;
  int n = 0;
  for (std::size_t b = 0; b < 36; ++b)
    if (std::isfinite(shifted.S[b]) && m.rock_mass[b] >= kLabMassResolution) {
      shifted.S[b] = std::max(0.0, shifted.S[b] - 0.2);
      want += 100.0 * (m.S[b] - shifted.S[b]);
      ++n;
    }
  write_lab(d / "lab2.h5", shifted);
  const Score s = score_against_lab(read_lab_case(d / "lab2.h5", 3, true), {m}, {Realization{}});
  CHECK(s.S_compared == n);
  CHECK(s.S_mae_pp == doctest::Approx(want / n).epsilon(1e-9));
  CHECK(score_table(s).find("S values (void filling") != std::string::npos);
  CHECK(score_toml(s, "sw", "cmd", "t", "lab.h5").find("S_values_compared = " + std::to_string(n)) != std::string::npos);
  CHECK(score_csv(s).find("S_error_pp") != std::string::npos);
}
