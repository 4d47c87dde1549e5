// SPDX-License-Identifier: MIT
// asin_poly / asin8 (model/fluid/asin_poly.h): within 2 ulp of libm's asin over [-1, 1], odd, exact at the ends,
// and the eight-lane form gives the scalar form's bits.
#include "model/fluid/asin_poly.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "base/rng.h"

using namespace pastemix;
using namespace pastemix::model::fluid;

namespace {

// Distance in units in the last place between two finite doubles of the same sign (or both zero).
std::int64_t ulps(double a, double b) {
  std::int64_t ia = 0, ib = 0;
  std::memcpy(&ia, &a, sizeof a);
  std::memcpy(&ib, &b, sizeof b);
  if (ia < 0) ia = std::numeric_limits<std::int64_t>::min() - ia;  // two's-complement order of the doubles
  if (ib < 0) ib = std::numeric_limits<std::int64_t>::min() - ib;
  return ia > ib ? ia - ib : ib - ia;
}

// Test points: uniform over [-1, 1], and dense around the two branches' seam (1/2), near 1 and near 0.
std::vector<double> points() {
  std::vector<double> x{0.0, -0.0, 1.0, -1.0, 0.5, -0.5, std::nextafter(0.5, 1.0), std::nextafter(0.5, 0.0),
                        std::nextafter(1.0, 0.0), 1e-300, 1e-20, 1e-8, 0.125, 0.25, 0.75};
  Rng rng(20261206);
  for (int k = 0; k < 400000; ++k) x.push_back(rng.uniform(-1.0, 1.0));
  for (int k = 0; k < 50000; ++k) x.push_back(0.5 + rng.uniform(-1e-3, 1e-3));
  for (int k = 0; k < 50000; ++k) x.push_back(1.0 - std::pow(10.0, rng.uniform(-16.0, -1.0)));
  for (int k = 0; k < 50000; ++k) x.push_back(std::pow(10.0, rng.uniform(-300.0, -1.0)));
  return x;
}

}  // namespace

TEST_CASE("asin_poly: within 2 ulp of std::asin over [-1, 1], odd, exact at 0 and +-1") {
  std::int64_t worst = 0;
  double at = 0.0;
  for (double x : points()) {
    const double got = asin_poly(x), ref = std::asin(x);
    REQUIRE(std::signbit(got) == std::signbit(ref));
    const std::int64_t d = ulps(got, ref);
    if (d > worst) worst = d, at = x;
    CHECK(asin_poly(-x) == -got);
  }
  INFO("worst at x = ", at);
  CHECK(worst <= 2);
  CHECK(asin_poly(1.0) == kPio2Hi);
  CHECK(asin_poly(-1.0) == -kPio2Hi);
  CHECK(asin_poly(0.0) == 0.0);
  CHECK(std::signbit(asin_poly(-0.0)));
  CHECK(std::isnan(asin_poly(NAN)));
}

#if defined(__AVX512F__)
TEST_CASE("asin8: the scalar form's bits in every lane") {
  const std::vector<double> x = points();
  long differ = 0;
  for (std::size_t k = 0; k + 8 <= x.size(); k += 8) {
    alignas(64) double out[8];
    _mm512_store_pd(out, asin8(_mm512_loadu_pd(x.data() + k)));
    for (int l = 0; l < 8; ++l) {
      const double one = asin_poly(x[k + static_cast<std::size_t>(l)]);
      differ += std::memcmp(&out[l], &one, sizeof one) != 0;
    }
  }
  CHECK(differ == 0);
}
#elif defined(__AVX2__) && defined(__FMA__)
TEST_CASE("asin4: the scalar form's bits in every lane") {
  const std::vector<double> x = points();
  long differ = 0;
  for (std::size_t k = 0; k + 4 <= x.size(); k += 4) {
    alignas(32) double out[4];
    _mm256_store_pd(out, asin4(_mm256_loadu_pd(x.data() + k)));
    for (int l = 0; l < 4; ++l) {
      const double one = asin_poly(x[k + static_cast<std::size_t>(l)]);
      differ += std::memcmp(&out[l], &one, sizeof one) != 0;
    }
  }
  CHECK(differ == 0);
}
#endif
