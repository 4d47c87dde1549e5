// SPDX-License-Identifier: MIT
#include "base/units.h"

#include <doctest/doctest.h>

TEST_CASE("units: known factors and unknown units") {
  CHECK(*pastemix::si_factor("mm") == doctest::Approx(1e-3));
  CHECK(*pastemix::si_factor("GPa") == doctest::Approx(1e9));
  CHECK(*pastemix::si_factor("%") == doctest::Approx(0.01));
  CHECK(pastemix::si_unit("cm") == "m");
  CHECK_FALSE(pastemix::si_factor("furlong").has_value());
  CHECK(pastemix::si_unit("furlong").empty());
}
