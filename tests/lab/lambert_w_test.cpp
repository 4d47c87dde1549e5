// SPDX-License-Identifier: MIT
#include "lab/lambert_w.h"

#include <cmath>
#include <stdexcept>

#include <doctest/doctest.h>

using pastemix::lab::lambert_w_minus1;

TEST_CASE("lambert_w_minus1: closed-form points") {
  const double e = std::exp(1.0);
  CHECK(lambert_w_minus1(-1.0 / e) == doctest::Approx(-1.0).epsilon(1e-7));  // branch point
  // w e^w at w = -2, -3, -2 ln 2, -10 (exact by construction).
  for (double w : {-1.001, -1.5, -2.0, -2.0 * std::log(2.0), -3.0, -10.0, -40.0})
    CHECK(lambert_w_minus1(w * std::exp(w)) == doctest::Approx(w).epsilon(1e-13));
  CHECK(lambert_w_minus1(-0.1) == doctest::Approx(-3.577152063957297).epsilon(1e-14));  // tabulated value
}

TEST_CASE("lambert_w_minus1: residual w e^w - x at machine precision over the whole branch") {
  const double e = std::exp(1.0);
  for (int k = 1; k < 2000; ++k) {
    // Points clustered at both ends: near the branch point and near 0-.
    const double t = static_cast<double>(k) / 2000.0;
    const double x = -1.0 / e * std::pow(t, 6.0) - 1e-300;
    const double w = lambert_w_minus1(x);
    CHECK(w <= -1.0);
    CHECK(std::abs(w * std::exp(w) - x) <= 1e-14 * std::abs(x));
  }
}

TEST_CASE("lambert_w_minus1: x outside -1/e .. 0 is a domain error") {
  CHECK_THROWS_AS(lambert_w_minus1(0.0), std::domain_error);
  CHECK_THROWS_AS(lambert_w_minus1(0.5), std::domain_error);
  CHECK_THROWS_AS(lambert_w_minus1(-0.37), std::domain_error);
  CHECK_THROWS_AS(lambert_w_minus1(std::nan("")), std::domain_error);
}
