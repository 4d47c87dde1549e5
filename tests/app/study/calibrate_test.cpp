// SPDX-License-Identifier: MIT
// The rolling-resistance bracketing on known monotone angle(mu) curves, and the scene edit it makes.
#include "app/study/calibrate.h"

#include <doctest/doctest.h>

#include <cmath>

#include "base/error.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::app::study;

TEST_CASE("bracketing finds mu_r of a known monotone angle curve within the angle tolerance") {
  // A saturating curve like a pile's: 25 deg at mu = 0 rising towards 45 deg.
  auto f = [](double mu) { return Evaluation{mu, 25.0 + 20.0 * (1 - std::exp(-mu / 0.1)), 0.3}; };
  const double target = 36.41;
  const double exact = -0.1 * std::log(1 - (target - 25.0) / 20.0);  // 0.0845
  const BracketResult r = bracket_root(f, 0.0, 0.4, target, 0.1, 1e-4, 20);
  CHECK(r.converged);
  CHECK(std::abs(r.best.angle - target) <= 0.1);
  CHECK(r.mu == doctest::Approx(exact).epsilon(0.02));
  CHECK(r.best.sd == 0.3);
  // Budget-limited: stops after max_evaluations and says it did not converge.
  const BracketResult short_run = bracket_root(f, 0.0, 0.4, target, 1e-6, 1e-9, 4);
  CHECK(short_run.history.size() == 4);
  CHECK_FALSE(short_run.converged);
  // A target outside the bracket's angles is an error, not an extrapolation.
  CHECK_THROWS_AS(bracket_root(f, 0.2, 0.4, target, 0.1, 1e-4, 20), RuntimeFailure);
}

TEST_CASE("every interaction's rolling_friction is set") {
  const auto base = model::SceneDoc::parse_file(test::source_path("datasets/scenes/repose_ch5.toml"));
  const auto d = with_rolling_resistance(base, 0.14);
  CHECK(std::stod(d.get("interaction.rock/rock.rolling_friction")) == 0.14);
  CHECK(std::stod(d.get("interaction.rock/steel.rolling_friction")) == 0.14);
  CHECK(d.load().pairs[0].rolling_friction == 0.14);
}
