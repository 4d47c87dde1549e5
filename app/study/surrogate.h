// SPDX-License-Identifier: MIT
// The rolling-resistance calibration's surrogate: a smooth, monotone angle(mu_r) fitted over every run of
// the study, and the mu_r of a target angle with its uncertainty from the fit.
//
//   angle(mu) = a + exp(beta) g(mu - mu_ref; k),   g(x; k) = (1 - exp(-k x)) / k   (g -> x as k -> 0)
//
// Its slope exp(beta) exp(-k x) is positive for every parameter value, so the curve is monotone by
// construction; k bends it (k > 0: saturating, as a pile's angle does at high rolling resistance; k < 0:
// steepening; k = 0: a line), and the form stays well conditioned when the points are nearly on a line.
// mu_ref is the mean of the points' mu. Three parameters: five points of mu leave room to see a lack of fit.
//
// The noise is the seed spread: the pooled within-point sd of the angle over the runs at the same mu (common
// random numbers: the same seeds at every mu; dof = runs - points), so the weights come from replicates, not
// from the misfit. Without replicates (one seed everywhere) it falls back to the residual sd (dof = runs - 3),
// and says so. Fit: Ceres (AutoDiff, Levenberg-Marquardt, k bounded to |k| <= 50 / (mu range)), parameter
// covariance from ceres::Covariance of the residuals scaled by that noise. The lack-of-fit chi2/dof of the
// point means is reported (>> 1: the form does not fit those points; it is not used to inflate the sd).
//
// Inverse: mu* solves angle(mu*) = target, x = -log1p(-k y) / k with y = (target - a) / exp(beta); a target
// outside the fitted curve's range over the points' mu is refused (no extrapolation). sd(mu*) by the delta
// method over (a, beta, k) with the fit's covariance, plus (dmu/dangle)^2 sd_target^2 for the target's own
// measurement sd. tests/app/study/surrogate_test.cpp checks that sd by coverage over synthetic draws.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

namespace pastemix::app::study {

struct MonotoneFit {
  double a = 0.0, beta = 0.0, k = 0.0;  // deg, log(deg per unit mu), 1 / unit mu
  double mu_ref = 0.0;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double noise_sd = 0.0;                 // deg
  int noise_dof = 0;
  std::string noise_from;                // "seed spread (pooled over N points)" or "residual sd (no replicates)"
  double chi2_dof = 0.0;                 // lack of fit of the point means
  int runs = 0, points = 0;
  double mu_lo = 0.0, mu_hi = 0.0;       // the points' range
  bool ok = false;
  std::string why;                       // when not ok

  double angle(double mu) const;         // deg
  double slope(double mu) const;         // deg per unit mu
  double angle_sd(double mu) const;      // deg: the fitted curve's sd at mu (delta method)
};

struct Inverse {
  double mu = 0.0, sd = 0.0;             // the answer and its total sd
  double sd_fit = 0.0, sd_target = 0.0;  // its parts (combined in quadrature)
  bool ok = false;
  std::string why;
};

// One (mu, angle) per run; runs at the same mu are replicates.
MonotoneFit fit_monotone(const std::vector<double>& mu, const std::vector<double>& angle);
Inverse invert(const MonotoneFit& f, double target_deg, double target_sd_deg = 0.0);

}  // namespace pastemix::app::study
