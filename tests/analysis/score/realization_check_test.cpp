// SPDX-License-Identifier: MIT
#include "analysis/score/realization_check.h"

#include <doctest/doctest.h>

#include "base/error.h"

using namespace pastemix::analysis;

namespace {

// A case-3-like lab case (75 % solids, rock 2.5-5 mm) and a result of `solids` with `diameter` spheres.
LabCase case_of(int id, double solids, double d_min, double d_max) {
  LabCase c;
  c.case_id = id;
  c.lab_path = "lab.h5";
  c.solids_fraction = solids;
  c.d_min = d_min;
  c.d_max = d_max;
  return c;
}

ResultSnapshot result(double solids, double diameter, const char* solids_source = "file attribute") {
  ResultSnapshot r;
  r.path = "case3.h5";
  r.seed = 1;
  r.scene_hash = "abc";
  r.ensemble_key = "abc";  // the scene without its seed line (read_result)
  r.solids_fraction = {solids, solids_source};
  r.radius = {0.5 * diameter, 0.5 * diameter, 0.5 * diameter};
  return r;
}

}  // namespace

TEST_CASE("realizations: a case-3 result (75 %, 2.5-5 mm) fits case 3 and not cases 5, 2 or 4") {
  const ResultSnapshot r = result(0.75, 0.004);
  CHECK_NOTHROW(check_realizations(case_of(3, 0.75, 0.0025, 0.005), {r}));
  // Case 5: 72.5 % and 8-9.5 mm; case 2: 72.5 %, same rock; case 4: 72.5 %, 5-8 mm.
  CHECK_THROWS_WITH_AS(check_realizations(case_of(5, 0.725, 0.008, 0.0095), {r}),
                       doctest::Contains("paste of 75.0 % solids, but lab case 5 had 72.5 %"), pastemix::InputError);
  CHECK_THROWS_AS(check_realizations(case_of(2, 0.725, 0.0025, 0.005), {r}), pastemix::InputError);
  const ResultSnapshot r4 = result(0.725, 0.004);
  CHECK_THROWS_WITH_AS(check_realizations(case_of(4, 0.725, 0.005, 0.008), {r4}),
                       doctest::Contains("median rock diameter 4 mm is outside lab case 4's sizes 5-8 mm"),
                       pastemix::InputError);
  // A paste given on the command line (--solids) is the user's choice: not compared.
  CHECK_NOTHROW(check_realizations(case_of(2, 0.725, 0.0025, 0.005), {result(0.75, 0.004, "command line --solids")}));
  // 5 % margin on the sieve range (a PSD cut, a rounded size).
  CHECK_NOTHROW(check_realizations(case_of(3, 0.75, 0.0025, 0.005), {result(0.75, 0.00524)}));
}

TEST_CASE("realizations: same path, same seed of one scene, or different scenes are refused") {
  const LabCase c = case_of(3, 0.75, 0.0025, 0.005);
  ResultSnapshot a = result(0.75, 0.004), b = a;
  CHECK_THROWS_WITH_AS(check_realizations(c, {a, b}), doctest::Contains("given twice"), pastemix::InputError);
  b.path = "copy.h5";
  CHECK_THROWS_WITH_AS(check_realizations(c, {a, b}), doctest::Contains("the same realization twice"),
                       pastemix::InputError);
  b.seed = 2;
  CHECK_NOTHROW(check_realizations(c, {a, b}));
  b.scene_hash = "def";
  b.ensemble_key = "def";
  CHECK_THROWS_WITH_AS(check_realizations(c, {a, b}), doctest::Contains("an ensemble must be realizations of one"),
                       pastemix::InputError);
}
