// SPDX-License-Identifier: MIT
#include "lab/drag/drag_fit.h"

#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include "base/error.h"
#include "base/rng.h"
#include "base/units.h"
#include "lab/drag/terminal_velocity.h"
#include "tests/run_command.h"

using namespace pastemix::lab::drag;
using pastemix::drag::CurveId;
using pastemix::units::g;

namespace {

enum class Noise { on_cd, on_velocity };

// Synthetic spheres: the 121 real spheres' sizes, densities and fluids, with the terminal velocity the
// `truth` curve gives. Noise (seeded, lognormal, `sigma` in ln units) goes where the target assumes it:
// on Cd at the true Re' for log_cd, on the measured velocity for the velocity target.
std::vector<SettlingSphere> synthetic(const DragCurve& truth, Noise noise, double sigma, std::uint64_t seed) {
  const auto real = read_settling_dataset(pastemix::test::source_path("datasets/thesis"));
  pastemix::Rng rng(seed);
  std::vector<SettlingSphere> out;
  for (auto s : real.spheres) {
    const auto tv = solve_terminal_velocity(truth, s.sphere, g);
    REQUIRE(tv.outcome == SettlingOutcome::settling);
    const double z = rng.normal();
    s.v = tv.v * (noise == Noise::on_velocity ? std::exp(sigma * z) : 1.0);
    s.re = pastemix::drag::bingham_reynolds(s.sphere.rho_f, s.v, s.sphere.tau_y, s.sphere.eta_B, s.sphere.d);
    s.cd = noise == Noise::on_cd ? truth.cd(s.re) * std::exp(sigma * z)
                                 : pastemix::drag::settling_drag_coefficient(s.sphere, s.v, g);
    out.push_back(s);
  }
  return out;
}

void check_recovery(const CurveFit& fit, const DragCurve& truth, double sigmas) {
  REQUIRE(fit.covariance_ok);
  for (std::size_t i = 0; i < truth.coefficients.size(); ++i) {
    const double err = fit.curve.coefficients[i] - truth.coefficients[i];
    CHECK_MESSAGE(std::abs(err) <= sigmas * fit.sd[i], "coefficient ", truth.info().coefficient_names[i], " = ",
                  fit.curve.coefficients[i], " +- ", fit.sd[i], ", true ", truth.coefficients[i]);
  }
}

const DragCurve kTruthSum{CurveId::power_sum, {22.0, 4.0, 0.6, 0.35}};
const DragCurve kTruthBlend{CurveId::power_blend, {10.0, 12.0, 0.75, 0.4, 3.0}};

}  // namespace

TEST_CASE("drag fit: noise-free synthetic data give back the curve (both targets)") {
  for (const auto& truth : {kTruthSum, kTruthBlend}) {
    for (FitTarget target : {FitTarget::log_cd, FitTarget::velocity}) {
      FitOptions o;
      o.target = target;
      const auto fit = fit_drag_curve(truth.id, synthetic(truth, Noise::on_cd, 0.0, 1), o, g);
      CHECK(fit.rms < 1e-7);
      for (std::size_t i = 0; i < truth.coefficients.size(); ++i)
        CHECK(fit.curve.coefficients[i] == doctest::Approx(truth.coefficients[i]).epsilon(1e-4));
    }
  }
}

TEST_CASE("drag fit: noisy synthetic data recover the parameters within 2 sigma (log Cd target)") {
  FitOptions o;
  o.target = FitTarget::log_cd;
  for (const auto& truth : {kTruthSum, kTruthBlend}) {
    const auto fit = fit_drag_curve(truth.id, synthetic(truth, Noise::on_cd, 0.05, 20261122), o, g);
    CHECK(fit.rms == doctest::Approx(0.05).epsilon(0.2));  // the residual scatter is the noise put in
    check_recovery(fit, truth, 2.0);
  }
}

TEST_CASE("drag fit: noisy synthetic data recover the parameters within 2 sigma (velocity target)") {
  FitOptions o;
  o.target = FitTarget::velocity;
  for (const auto& truth : {kTruthSum, kTruthBlend}) {
    const auto fit = fit_drag_curve(truth.id, synthetic(truth, Noise::on_velocity, 0.03, 20261123), o, g);
    CHECK(fit.rms == doctest::Approx(0.03).epsilon(0.2));
    check_recovery(fit, truth, 2.0);
  }
}

TEST_CASE("drag fit: fixed curves and too few spheres are refused") {
  const auto data = read_settling_dataset(pastemix::test::source_path("datasets/thesis"));
  CHECK_THROWS_AS(fit_drag_curve(CurveId::published_4_19, data.spheres, {}, g), pastemix::RuntimeFailure);
  const std::vector<SettlingSphere> four(data.spheres.begin(), data.spheres.begin() + 4);
  CHECK_THROWS_AS(fit_drag_curve(CurveId::power_sum, four, {}, g), pastemix::RuntimeFailure);
}
