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

// Recovery within 2 sigma, checked as a calibration over `seeds` independent noise draws: each coefficient's
// z = (fitted - true) / sd must lie within 2 in at least 80 % of the draws (95 % expected for a correct
// covariance; 5 correlated coefficients make a single draw's "all within 2 sigma" a coin with p ~ 0.8), and the
// mean z^2 must be near 1 (a covariance too large or too small by 1.6x in sd fails).
void check_recovery(const DragCurve& truth, FitTarget target, double sigma, int seeds) {
  FitOptions o;
  o.target = target;
  const auto n_coef = truth.coefficients.size();
  int within = 0, total = 0;
  double z2 = 0.0;
  for (int seed = 1; seed <= seeds; ++seed) {
    const auto noise = target == FitTarget::log_cd ? Noise::on_cd : Noise::on_velocity;
    const auto fit = fit_drag_curve(truth.id, synthetic(truth, noise, sigma, 1000 + seed), o, g);
    REQUIRE(fit.covariance_ok);
    CHECK(fit.rms == doctest::Approx(sigma).epsilon(0.2));  // the residual scatter is the noise put in
    for (std::size_t i = 0; i < n_coef; ++i) {
      REQUIRE_MESSAGE(!fit.at_bound[i], "seed ", seed, " coefficient ", i, " ended on its bound");
      const double z = (fit.curve.coefficients[i] - truth.coefficients[i]) / fit.sd[i];
      within += std::abs(z) <= 2.0;
      z2 += z * z;
      ++total;
    }
  }
  MESSAGE(std::string(truth.info().name), " ", std::string(to_string(target)), ": ", within, " of ", total, " within 2 sigma, mean z^2 ",
          z2 / total);
  CHECK(within >= 0.8 * total);
  CHECK(z2 / total == doctest::Approx(1.0).epsilon(0.6));
}

// Interior truths where every coefficient is identifiable. (Near b -> 1 the k/Re' and a Re'^-b terms of
// power_blend become nearly collinear: with k = 10, a = 12, b = 0.75 a 5 % noise draw puts k on its bound in
// about half the draws. The real-data fit sits in that corner; its curve is determined, k and a are not
// separately.)
const DragCurve kTruthSum{CurveId::power_sum, {22.0, 4.0, 0.6, 0.35}};
const DragCurve kTruthBlend{CurveId::power_blend, {20.0, 5.0, 0.5, 0.4, 3.0}};

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
  check_recovery(kTruthSum, FitTarget::log_cd, 0.05, 10);
  check_recovery(kTruthBlend, FitTarget::log_cd, 0.05, 10);
}

TEST_CASE("drag fit: noisy synthetic data recover the parameters within 2 sigma (velocity target)") {
  check_recovery(kTruthSum, FitTarget::velocity, 0.03, 10);
  check_recovery(kTruthBlend, FitTarget::velocity, 0.03, 10);
}

TEST_CASE("drag fit: fixed curves and too few spheres are refused") {
  const auto data = read_settling_dataset(pastemix::test::source_path("datasets/thesis"));
  CHECK_THROWS_AS(fit_drag_curve(CurveId::published_4_19, data.spheres, {}, g), pastemix::RuntimeFailure);
  const std::vector<SettlingSphere> four(data.spheres.begin(), data.spheres.begin() + 4);
  CHECK_THROWS_AS(fit_drag_curve(CurveId::power_sum, four, {}, g), pastemix::RuntimeFailure);
}
