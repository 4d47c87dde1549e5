// SPDX-License-Identifier: MIT
// Is a result's state at rest (analysis/maps/motion.h): the census of the engine's [stop] rule, from the
// snapshot's velocities or, where the run's rule measured by displacement, from its mean speeds.
#include "analysis/maps/motion.h"

#include <limits>

#include <doctest/doctest.h>

#include "analysis/maps/result_file.h"
#include "tests/analysis/result_fixture.h"
#include "tests/input_error.h"

using namespace pastemix::analysis;
using pastemix::test::ResultSpec;
using pastemix::test::ScratchDir;
using pastemix::test::write_result;

namespace {

// Two 8 mm rocks under the paste surface (z = 0.10 m); the first oscillates in place at 3 cm/s (its velocity at
// the snapshot), the second crept 2 mm in the rule's last 0.01 s check interval (0.2 m/s mean speed, no velocity
// at the snapshot).
ResultSpec two_rocks() {
  ResultSpec s;
  s.final = {{{0.05, 0.05, 0.05}, 0.004}, {{0.1, 0.1, 0.02}, 0.004}};
  s.velocity = {{0.0, 0.0, 0.03}, {0.0, 0.0, 0.0}};
  return s;
}

}  // namespace

TEST_CASE("motion: without mean speeds the census is of the velocities, with them of the mean speeds") {
  ScratchDir d("motion_mean");
  const double rock = 2760 * 4.0 / 3.0 * 3.141592653589793 * 0.004 * 0.004 * 0.004;  // kg
  ResultSpec s = two_rocks();
  write_result(d / "v.h5", s);
  const Motion by_velocity = motion_of(read_result(d / "v.h5", {}), {});
  CHECK_FALSE(by_velocity.mean);
  CHECK(by_velocity.moving_count == 1);
  CHECK(by_velocity.moving_mass == doctest::Approx(rock));
  CHECK(by_velocity.max_speed == doctest::Approx(0.03));

  s.mean_speed = {0.0, 0.2};
  write_result(d / "m.h5", s);
  const ResultSnapshot r = read_result(d / "m.h5", {});
  REQUIRE(r.mean_speed.size() == 2);
  const Motion by_mean = motion_of(r, {});
  CHECK(by_mean.mean);
  CHECK(by_mean.known);
  CHECK(by_mean.moving_count == 1);
  CHECK(by_mean.max_speed == doctest::Approx(0.2));
  CHECK(by_mean.at_rest());  // a 0.74 g rock is under the 1 g default limit
  CHECK_FALSE(motion_of(r, {0.01, 1e-4}).at_rest());
  CHECK(by_mean.line(r).find("mean over the stop rule's last check interval") != std::string::npos);
  // Both at rest by their mean speed: the oscillating rock is not moving.
  s.mean_speed = {1e-4, 2e-3};
  write_result(d / "rest.h5", s);
  CHECK(motion_of(read_result(d / "rest.h5", {}), {0.01, 1e-4}).at_rest());
}

TEST_CASE("motion: a mean_speed of the wrong length or a negative speed names the file and the dataset") {
  ScratchDir d("motion_bad");
  ResultSpec s = two_rocks();
  s.mean_speed = {0.0};
  write_result(d / "short.h5", s);
  CHECK(pastemix::test::input_error_of([&] { read_result(d / "short.h5", {}); })
            .find("mean_speed") != std::string::npos);
  s.mean_speed = {0.0, -1.0};
  write_result(d / "neg.h5", s);
  const std::string e = pastemix::test::input_error_of([&] { read_result(d / "neg.h5", {}); });
  CHECK(e.find("neg.h5") != std::string::npos);
  CHECK(e.find("must be >= 0") != std::string::npos);
  // +inf (a rock the rule had no earlier position of) is a speed: moving.
  s.mean_speed = {0.0, std::numeric_limits<double>::infinity()};
  write_result(d / "inf.h5", s);
  CHECK(motion_of(read_result(d / "inf.h5", {}), {}).moving_count == 1);
}
