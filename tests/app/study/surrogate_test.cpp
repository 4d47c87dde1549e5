// SPDX-License-Identifier: MIT
// The rolling-resistance surrogate (app/study/surrogate.h) on synthetic data of known answer: angles drawn
// from a known monotone curve with a known seed sd (1.5 deg, the repose runs' seed sd of issue 21) at 5 mu_r
// x 3 seeds, as the calibration's design. Exact data give the true mu_r to round-off; noisy draws give it
// without bias, and the sd is honest: over 200 draws the true mu_r lies within 1 sd in ~68 % of them.
#include "app/study/surrogate.h"

#include <cmath>
#include <random>

#include <doctest/doctest.h>

using namespace pastemix::app::study;

namespace {

// The "true" curve: a saturating rise of 10 deg from 30 deg at mu_r = 0.05 to 40 deg at 0.30 (about the size
// of Table 6.1's effect), with the surrogate's own form (so that only the noise is unknown).
double truth(double mu) {
  const double k = 5.0, b = 10.0 * k / (1.0 - std::exp(-k * 0.25));  // deg per unit mu_r at mu_r = 0.05
  return 30.0 + b * (1.0 - std::exp(-k * (mu - 0.05))) / k;
}

struct Draw {
  std::vector<double> mu, angle;
};

Draw draw(std::mt19937_64& rng, double sd, int seeds) {
  std::normal_distribution<double> noise(0.0, sd);
  Draw d;
  for (int i = 0; i < 5; ++i) {
    const double mu = 0.05 + 0.0625 * i;
    // Common random numbers would share a seed effect across mu; independent noise is the harder case
    // for the sd (no cancellation), and the one the fit's noise model assumes.
    for (int s = 0; s < seeds; ++s) d.mu.push_back(mu), d.angle.push_back(truth(mu) + noise(rng));
  }
  return d;
}

// mu_r with truth(mu) = target, by bisection on the exact curve.
double true_mu(double target) {
  double lo = 0.05, hi = 0.30;
  for (int k = 0; k < 100; ++k) ((truth(0.5 * (lo + hi)) < target) ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("surrogate: exact data of its own form give the curve and the inverse to round-off") {
  std::vector<double> mu, angle;
  for (int i = 0; i < 5; ++i)
    for (int s = 0; s < 3; ++s) {
      mu.push_back(0.05 + 0.0625 * i);
      angle.push_back(truth(mu.back()) + (s - 1) * 0.5);  // replicates +-0.5 deg about the curve: sd 0.5
    }
  const MonotoneFit f = fit_monotone(mu, angle);
  REQUIRE_MESSAGE(f.ok, f.why);
  CHECK(f.noise_sd == doctest::Approx(0.5).epsilon(1e-12));
  CHECK(f.noise_dof == 10);
  for (double m : {0.05, 0.1, 0.2, 0.3}) CHECK(f.angle(m) == doctest::Approx(truth(m)).epsilon(1e-8));
  const Inverse r = invert(f, 35.0);
  REQUIRE(r.ok);
  CHECK(r.mu == doctest::Approx(true_mu(35.0)).epsilon(1e-7));
  // The target's own sd adds (dmu/dangle) sd_target in quadrature.
  const Inverse t = invert(f, 35.0, 1.0);
  CHECK(t.sd_target == doctest::Approx(1.0 / f.slope(r.mu)).epsilon(1e-9));
  CHECK(t.sd == doctest::Approx(std::hypot(r.sd_fit, t.sd_target)).epsilon(1e-12));
}

TEST_CASE("surrogate: recovers the known mu_r without bias, and its sd covers it in ~68 % of 200 draws") {
  std::mt19937_64 rng(2026);
  const double target = 35.0, mu_true = true_mu(target);
  int covered = 0, n = 0;
  double first_err = 0.0, first_sd = 0.0, sum_err = 0.0, sum_sd = 0.0;
  for (int k = 0; k < 200; ++k) {
    const Draw d = draw(rng, 1.5, 3);
    const MonotoneFit f = fit_monotone(d.mu, d.angle);
    REQUIRE_MESSAGE(f.ok, f.why);
    const Inverse r = invert(f, target);
    REQUIRE_MESSAGE(r.ok, r.why);
    if (k == 0) first_err = r.mu - mu_true, first_sd = r.sd;
    covered += std::abs(r.mu - mu_true) <= r.sd;
    sum_err += r.mu - mu_true, sum_sd += r.sd;
    ++n;
  }
  const double coverage = static_cast<double>(covered) / n;
  const double bias = sum_err / n, mean_sd = sum_sd / n;
  MESSAGE("true mu_r ", mu_true, "; first draw: error ", first_err, ", sd ", first_sd, "; over ", n,
          " draws: mean error ", bias, ", mean sd ", mean_sd, ", coverage of +-1 sd ", coverage);
  // Recovered: no bias beyond a small part of one sd (the standard error of the mean error over 200 draws is
  // ~0.07 sd), and the first draw (not chosen) within 2 sd (95 %).
  CHECK(std::abs(bias) <= 0.2 * mean_sd);
  CHECK(std::abs(first_err) <= 2.0 * first_sd);
  // 68 % nominal; the noise sd is estimated with 10 dof (t-distribution: 66 %); the binomial sd of 200
  // draws is 3.3 points, so [0.58, 0.76] is about +-2.5 of them.
  CHECK(coverage >= 0.58);
  CHECK(coverage <= 0.76);
}

TEST_CASE("surrogate: no monotone rise, too few points, or a target outside the curve are refused") {
  CHECK_FALSE(fit_monotone({0.1, 0.2}, {30, 31}).ok);
  const MonotoneFit down = fit_monotone({0.1, 0.1, 0.2, 0.2, 0.3, 0.3}, {36, 35, 33, 34, 30, 31});
  CHECK_FALSE(down.ok);
  CHECK(down.why.find("does not rise") != std::string::npos);
  const MonotoneFit f = fit_monotone({0.1, 0.1, 0.2, 0.2, 0.3, 0.3}, {30, 31, 33, 34, 35, 36});
  REQUIRE(f.ok);
  const Inverse out = invert(f, 45.0);
  CHECK_FALSE(out.ok);
  CHECK(out.why.find("no extrapolation") != std::string::npos);
}
