// SPDX-License-Identifier: MIT
// Fitting a drag-curve family to settling spheres with Ceres.
//
// Two targets, one residual block per sphere, AutoDiff throughout:
//  * log_cd:   r_i = ln Cd(Re'_i; c) - ln Cd_i  (both from the measured velocity, eqs. 4.17/4.18);
//  * velocity: r_i = ln(v_pred,i(c) / v_i), v_pred from the implicit force balance G(v, c) = 0. Ceres Jets
//    cannot flow through a bisection, so the velocity residual solves in doubles and differentiates the
//    root implicitly, dv/dc = -(dG/dc)/(dG/dv), both partials by Jets. It starts from the log_cd fit.
// Coefficients are bounded to the family's admissible box (base/drag_curves.h), so every fitted curve is
// continuous, monotone and gives a unique terminal velocity. The covariance is Ceres's (J^T J)^-1 scaled by
// the residual variance s^2 = sum r^2 / (n - p) (the residuals carry no measurement weights); a coefficient
// that ends on its bound is held there (an active constraint) and the covariance is that of the others.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "base/drag_curves.h"
#include "lab/drag/settling.h"

namespace pastemix::lab::drag {

using pastemix::drag::DragCurve;

enum class FitTarget { log_cd, velocity };
const char* to_string(FitTarget t);

enum class FitLoss { none, cauchy };  // cauchy: robust, scale loss_scale in residual units (ln)

struct FitOptions {
  FitTarget target = FitTarget::velocity;
  FitLoss loss = FitLoss::none;
  double loss_scale = 0.1;
  int max_iterations = 200;
  bool covariance = true;  // off in the LOSO refits, which only predict
};

struct CurveFit {
  DragCurve curve;
  FitOptions options;
  int n = 0;                    // residuals (spheres)
  double cost = 0.0;            // Ceres final cost, 1/2 sum rho(r^2)
  double rms = 0.0;             // sqrt(sum r^2 / n) of the raw residuals
  bool converged = false;
  int iterations = 0;
  bool covariance_ok = false;
  Eigen::MatrixXd covariance;   // of the coefficients (scaled by s^2); empty if not ok
  std::vector<double> sd;       // NaN where unknown or held at a bound
  std::vector<bool> at_bound;   // ended on its admissible bound: held there for the covariance (sd NaN)
  std::string brief_report;     // Ceres's one-line summary
};

// Fits `family` (a fitted family of base/drag_curves.h) to `spheres`. g in m/s2.
CurveFit fit_drag_curve(pastemix::drag::CurveId family, std::span<const SettlingSphere> spheres,
                        const FitOptions& options, double g);

}  // namespace pastemix::lab::drag
