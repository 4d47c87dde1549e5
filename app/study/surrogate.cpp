// SPDX-License-Identifier: MIT
#include "app/study/surrogate.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <ceres/ceres.h>
#include <fmt/format.h>

namespace pastemix::app::study {
namespace {

// g(x; k) = (1 - exp(-k x)) / k, its series where k x is tiny (no 0/0 as k -> 0).
template <typename T>
T bend(const T& x, const T& k) {
  using std::abs;
  using std::expm1;
  if (abs(k * x) < T(1e-6)) return x * (T(1.0) - T(0.5) * k * x);
  return -expm1(-k * x) / k;
}

template <typename T>
T curve(const T* p, double x) {
  using std::exp;
  return p[0] + exp(p[1]) * bend(T(x), p[2]);
}

struct AngleResidual {
  double x, angle, sd;
  template <typename T>
  bool operator()(const T* p, T* r) const {
    r[0] = (T(angle) - curve(p, x)) / T(sd);
    return true;
  }
};

double curve_value(const double* p, double x) { return curve(p, x); }

// x solving a + exp(beta) g(x; k) = target, or NaN when none.
double inverse_x(const double* p, double target) {
  const double y = (target - p[0]) / std::exp(p[1]);
  if (std::abs(p[2] * y) < 1e-12) return y;
  if (1.0 - p[2] * y <= 0.0) return std::nan("");
  return -std::log1p(-p[2] * y) / p[2];
}

}  // namespace

double MonotoneFit::angle(double mu) const {
  const double p[3] = {a, beta, k};
  return curve_value(p, mu - mu_ref);
}

double MonotoneFit::slope(double mu) const { return std::exp(beta) * std::exp(-k * (mu - mu_ref)); }

double MonotoneFit::angle_sd(double mu) const {
  Eigen::Vector3d g;
  const double p0[3] = {a, beta, k};
  for (int i = 0; i < 3; ++i) {
    double hi[3] = {a, beta, k}, lo[3] = {a, beta, k};
    const double h = 1e-6 * std::max(1.0, std::abs(p0[i]));
    hi[i] += h, lo[i] -= h;
    g(i) = (curve_value(hi, mu - mu_ref) - curve_value(lo, mu - mu_ref)) / (2 * h);
  }
  return std::sqrt(std::max(0.0, g.dot(cov * g)));
}

MonotoneFit fit_monotone(const std::vector<double>& mu, const std::vector<double>& angle) {
  MonotoneFit f;
  f.runs = static_cast<int>(mu.size());
  std::map<double, std::vector<double>> at;
  for (std::size_t i = 0; i < mu.size(); ++i) at[mu[i]].push_back(angle[i]);
  f.points = static_cast<int>(at.size());
  if (f.points < 3) {
    f.why = fmt::format("{} distinct mu_r value(s): the surrogate has 3 parameters and needs 3", f.points);
    return f;
  }
  f.mu_lo = at.begin()->first, f.mu_hi = at.rbegin()->first;
  double ss = 0.0, sum_mu = 0.0;
  int dof = 0;
  for (const auto& [m, v] : at) {
    double mean = 0.0;
    for (double x : v) mean += x / static_cast<double>(v.size());
    for (double x : v) ss += (x - mean) * (x - mean);
    dof += static_cast<int>(v.size()) - 1;
  }
  for (double m : mu) sum_mu += m;
  f.mu_ref = sum_mu / static_cast<double>(mu.size());
  // A start from the least-squares line (k = 0).
  double sxx = 0.0, sxy = 0.0, ybar = 0.0;
  for (double y : angle) ybar += y / static_cast<double>(angle.size());
  for (std::size_t i = 0; i < mu.size(); ++i) {
    sxx += (mu[i] - f.mu_ref) * (mu[i] - f.mu_ref);
    sxy += (mu[i] - f.mu_ref) * (angle[i] - ybar);
  }
  const double slope0 = sxy / sxx;
  if (!(slope0 > 0.0)) {
    f.why = fmt::format("the angle does not rise with mu_r over the points (least-squares slope {:.3g} deg per unit "
                        "mu_r): no monotone surrogate; check the runs or widen the range", slope0);
    return f;
  }
  if (dof > 0) {
    f.noise_sd = std::sqrt(ss / dof), f.noise_dof = dof;
    f.noise_from = fmt::format("seed spread, pooled over {} points ({} dof)", f.points, dof);
  }
  double p[3] = {ybar, std::log(slope0), 0.0};
  const double range = f.mu_hi - f.mu_lo;
  // Without replicates, a first pass with unit weights gives the residual sd as the noise.
  for (int pass = 0; pass < 2; ++pass) {
    const double sd = f.noise_sd > 0.0 ? f.noise_sd : 1.0;
    ceres::Problem problem;
    for (std::size_t i = 0; i < mu.size(); ++i)
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<AngleResidual, 1, 3>(
                                   new AngleResidual{mu[i] - f.mu_ref, angle[i], sd}),
                               nullptr, p);
    problem.SetParameterLowerBound(p, 2, -50.0 / range);
    problem.SetParameterUpperBound(p, 2, 50.0 / range);
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = 200;
    so.function_tolerance = so.gradient_tolerance = so.parameter_tolerance = 1e-14;
    ceres::Solver::Summary sum;
    ceres::Solve(so, &problem, &sum);
    if (!sum.IsSolutionUsable()) {
      f.why = "the Ceres fit failed: " + sum.message;
      return f;
    }
    if (f.noise_sd == 0.0) {
      if (f.runs <= 3) {
        f.why = "no replicates and no more runs than parameters: no noise estimate";
        return f;
      }
      f.noise_dof = f.runs - 3;
      f.noise_sd = std::sqrt(2.0 * sum.final_cost / f.noise_dof);  // cost = 1/2 sum r^2, unit weights
      f.noise_from = fmt::format("residual sd ({} dof; no replicates: one seed per point)", f.noise_dof);
      if (!(f.noise_sd > 0.0)) {
        f.why = "the runs lie exactly on the curve: no noise estimate";
        return f;
      }
      continue;
    }
    if (std::abs(std::abs(p[2]) - 50.0 / range) < 1e-9 / range) {
      f.why = "the surrogate's bend k is at its bound: the points do not follow a smooth monotone curve";
      return f;
    }
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    ceres::Covariance cov(co);
    std::vector<std::pair<const double*, const double*>> blocks{{p, p}};
    if (!cov.Compute(blocks, &problem)) {
      f.why = "the fit's covariance is singular (points too few or too close)";
      return f;
    }
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> c;
    cov.GetCovarianceBlock(p, p, c.data());
    f.cov = c;
    break;
  }
  f.a = p[0], f.beta = p[1], f.k = p[2];
  // Lack of fit: the point means against the curve, each with sd noise / sqrt(n).
  double chi2 = 0.0;
  for (const auto& [m, v] : at) {
    double mean = 0.0;
    for (double x : v) mean += x / static_cast<double>(v.size());
    const double r = (mean - f.angle(m)) / (f.noise_sd / std::sqrt(static_cast<double>(v.size())));
    chi2 += r * r;
  }
  f.chi2_dof = f.points > 3 ? chi2 / (f.points - 3) : 0.0;
  f.ok = true;
  return f;
}

Inverse invert(const MonotoneFit& f, double target, double target_sd) {
  Inverse r;
  if (!f.ok) {
    r.why = f.why;
    return r;
  }
  const double lo = f.angle(f.mu_lo), hi = f.angle(f.mu_hi);
  if (target < lo || target > hi) {
    r.why = fmt::format("the target {:.2f} deg lies outside the surrogate's angles over the runs' mu_r "
                        "([{:.2f}, {:.2f}] deg at mu_r {:.4g} .. {:.4g}): widen the range, no extrapolation",
                        target, lo, hi, f.mu_lo, f.mu_hi);
    return r;
  }
  const double p[3] = {f.a, f.beta, f.k};
  r.mu = f.mu_ref + inverse_x(p, target);
  Eigen::Vector3d g;
  for (int i = 0; i < 3; ++i) {
    double up[3] = {f.a, f.beta, f.k}, dn[3] = {f.a, f.beta, f.k};
    const double h = 1e-6 * std::max(1.0, std::abs(p[i]));
    up[i] += h, dn[i] -= h;
    g(i) = (inverse_x(up, target) - inverse_x(dn, target)) / (2 * h);
  }
  r.sd_fit = std::sqrt(std::max(0.0, g.dot(f.cov * g)));
  r.sd_target = target_sd / f.slope(r.mu);
  r.sd = std::hypot(r.sd_fit, r.sd_target);
  r.ok = std::isfinite(r.mu) && std::isfinite(r.sd);
  if (!r.ok) r.why = "the inverse is not finite";
  return r;
}

}  // namespace pastemix::app::study
