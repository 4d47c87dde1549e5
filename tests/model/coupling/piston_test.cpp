// SPDX-License-Identifier: MIT
// `piston` (model/coupling/piston.h): a block of glued spheres pushed into the paste raises the surface by the
// displaced volume over the free area (2 %), the paste volume is kept (1e-8); without d eps_f/dt in the
// projection (the toy coupling) the surface does not rise.
#include "model/coupling/piston.h"

#include <doctest/doctest.h>

#include <cstdio>

using namespace pastemix::coupling;

namespace {
void print(const char* what, const PistonResult& r) {
  std::printf("piston %s: rise %.4f mm (expected %.4f mm, error %.3g), paste volume error %.3g, free surface spread "
              "%.3g mm, alpha in [%.3g, %.6g], max speed at the end %.3g m/s, max relative divergence %.3g, %ld steps, "
              "%.2f s\n",
              what, r.rise_measured * 1e3, r.rise_expected * 1e3, r.relative_error, r.volume_error,
              r.surface_spread * 1e3, r.alpha_min, r.alpha_max, r.max_speed_end, r.max_relative_divergence, r.steps,
              r.seconds);
}
}  // namespace

TEST_CASE("piston: the surface rises by the displaced volume over the free area, the paste volume is kept") {
  PistonSettings s;
  s.cell = 0.01;
  s.max_time_step = 1e-2;
  const PistonResult r = run_piston(s);
  print("10 mm cells", r);
  CHECK(r.rise_expected > 5e-4);  // a rise of ~1 mm is being measured
  CHECK(r.relative_error <= 0.02);
  CHECK(r.volume_error <= 1e-8);
  CHECK(r.alpha_max <= 1.0 + 1e-6);
  CHECK(r.alpha_min >= -1e-6);
}

TEST_CASE("piston: a coupling without d eps_f/dt in the projection displaces no paste, and the test says so") {
  PistonSettings s;
  s.cell = 0.01;
  s.max_time_step = 1e-2;
  s.with_rate = false;
  const PistonResult r = run_piston(s);
  print("10 mm cells, no d eps_f/dt", r);
  CHECK(r.relative_error > 0.5);
}
