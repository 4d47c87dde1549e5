// SPDX-License-Identifier: MIT
#include "base/rng.h"

#include <doctest/doctest.h>

TEST_CASE("rng: same seed same sequence, different seed different sequence, sane moments") {
  pastemix::Rng a(123), b(123), c(124);
  bool differs = false;
  for (int k = 0; k < 100; ++k) {
    auto x = a.next_u64();
    CHECK(x == b.next_u64());
    differs = differs || (x != c.next_u64());
  }
  CHECK(differs);
  pastemix::Rng r(1);
  double sum = 0, sum2 = 0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    double z = r.normal();
    sum += z;
    sum2 += z * z;
  }
  CHECK(sum / n == doctest::Approx(0.0).epsilon(0.01).scale(1.0));
  CHECK(sum2 / n == doctest::Approx(1.0).epsilon(0.01));
}
