// SPDX-License-Identifier: MIT
#include "lab/drag/drag_fit.h"

#include <cmath>
#include <limits>
#include <memory>

#include <ceres/ceres.h>
#include <fmt/format.h>

#include "base/error.h"
#include "lab/drag/terminal_velocity.h"

namespace pastemix::lab::drag {

namespace {

using pastemix::drag::CurveId;

inline double value_of(double x) { return x; }
template <int N>
double value_of(const ceres::Jet<double, N>& x) {
  return x.a;
}

struct LogCdResidual {
  CurveId id;
  double re, cd;
  template <typename T>
  bool operator()(const T* c, T* r) const {
    using std::log;
    r[0] = log(pastemix::drag::drag_coefficient(id, c, T(re))) - T(std::log(cd));
    return true;
  }
};

// A sphere the candidate curve holds suspended predicts v = 0; its residual is floored at ln(1e-6 m/s / v)
// (a large, flat penalty: the optimiser will not step into suspending a sphere that settled).
constexpr double kSuspendedVelocity = 1e-6;  // m/s

struct VelocityResidual {
  CurveId id;
  int n_coef;
  BinghamSphere sphere;
  double v_measured, g;
  template <typename T>
  bool operator()(const T* c, T* r) const {
    using std::log;
    DragCurve curve{id, std::vector<double>(n_coef)};
    for (int i = 0; i < n_coef; ++i) curve.coefficients[i] = value_of(c[i]);
    const auto tv = solve_terminal_velocity_monotone(curve, sphere, g);
    if (tv.outcome == SettlingOutcome::suspended) {
      r[0] = T(std::log(kSuspendedVelocity / v_measured));
      return true;
    }
    // dG/dv at the root, by a one-slot Jet in v with the coefficients held at their values.
    using J1 = ceres::Jet<double, 1>;
    std::vector<J1> cj(n_coef);
    for (int i = 0; i < n_coef; ++i) cj[i] = J1(curve.coefficients[i]);
    const J1 vj(tv.v, 0);
    const double dG_dv = -pastemix::drag::dedegil_drag(id, cj.data(), sphere, vj).v[0];
    if (!(dG_dv < 0.0)) return false;  // G must fall through its root for a well-posed curve
    // One Newton step in T: its value refines the root, its derivative part is -(dG/dc)/(dG/dv).
    const T G = T(pastemix::drag::net_weight(sphere, g)) - pastemix::drag::dedegil_drag(id, c, sphere, T(tv.v));
    const T v = T(tv.v) - G / dG_dv;
    r[0] = log(v / v_measured);
    return true;
  }
};

template <int N>
ceres::CostFunction* make_cost(CurveId id, const SettlingSphere& s, const FitOptions& o, double g) {
  if (o.target == FitTarget::log_cd)
    return new ceres::AutoDiffCostFunction<LogCdResidual, 1, N>(new LogCdResidual{id, s.re, s.cd});
  return new ceres::AutoDiffCostFunction<VelocityResidual, 1, N>(
      new VelocityResidual{id, N, s.sphere, s.v, g});
}

ceres::CostFunction* make_cost(CurveId id, const SettlingSphere& s, const FitOptions& o, double g) {
  switch (pastemix::drag::curve_info(id).n_coefficients) {
    case 4: return make_cost<4>(id, s, o, g);
    case 5: return make_cost<5>(id, s, o, g);
    default: throw RuntimeFailure("drag fit: family has no fittable coefficients");
  }
}

// One Ceres solve of `problem` (empty on entry) from the values in `coef`; fills all but the covariance.
CurveFit solve(CurveId id, std::span<const SettlingSphere> spheres, const FitOptions& o, double g,
               ceres::Problem* problem, std::vector<double>* coef) {
  const auto& info = pastemix::drag::curve_info(id);
  for (const auto& s : spheres) {
    ceres::LossFunction* loss = o.loss == FitLoss::cauchy ? new ceres::CauchyLoss(o.loss_scale) : nullptr;
    problem->AddResidualBlock(make_cost(id, s, o, g), loss, coef->data());
  }
  for (int i = 0; i < info.n_coefficients; ++i) {
    problem->SetParameterLowerBound(coef->data(), i, info.lower[i]);
    problem->SetParameterUpperBound(coef->data(), i, info.upper[i]);
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = o.max_iterations;
  so.function_tolerance = 1e-12;
  so.parameter_tolerance = 1e-12;
  so.gradient_tolerance = 1e-14;
  so.num_threads = 1;  // tiny problems; reproducible
  ceres::Solver::Summary summary;
  ceres::Solve(so, problem, &summary);

  CurveFit fit;
  fit.curve = DragCurve{id, *coef};
  fit.options = o;
  fit.n = static_cast<int>(spheres.size());
  fit.cost = summary.final_cost;
  fit.converged = summary.termination_type == ceres::CONVERGENCE;
  fit.iterations = static_cast<int>(summary.iterations.size());
  fit.brief_report = summary.BriefReport();
  double ss = 0.0;
  std::vector<double> r;
  ceres::Problem::EvaluateOptions eo;
  eo.apply_loss_function = false;
  problem->Evaluate(eo, nullptr, &r, nullptr, nullptr);
  for (double x : r) ss += x * x;
  fit.rms = std::sqrt(ss / static_cast<double>(std::max<std::size_t>(1, r.size())));
  return fit;
}

}  // namespace

const char* to_string(FitTarget t) { return t == FitTarget::log_cd ? "log_cd" : "velocity"; }

CurveFit fit_drag_curve(CurveId family, std::span<const SettlingSphere> spheres, const FitOptions& options,
                        double g) {
  const auto& info = pastemix::drag::curve_info(family);
  const int p = info.n_coefficients;
  if (p == 0) throw RuntimeFailure(fmt::format("drag fit: '{}' has no coefficients to fit", info.name));
  if (static_cast<int>(spheres.size()) <= p)
    throw RuntimeFailure(fmt::format("drag fit: {} spheres cannot determine {} coefficients", spheres.size(), p));

  // Declared before the problems that point into it.
  std::vector<double> coef(info.start.begin(), info.start.begin() + p);
  if (options.target == FitTarget::velocity) {
    // The velocity residual needs a curve that already settles most spheres: start from the log_cd fit.
    FitOptions first = options;
    first.target = FitTarget::log_cd;
    ceres::Problem pre;
    solve(family, spheres, first, g, &pre, &coef);
  }
  ceres::Problem problem;
  CurveFit fit = solve(family, spheres, options, g, &problem, &coef);

  fit.sd.assign(p, std::numeric_limits<double>::quiet_NaN());
  fit.at_bound.assign(p, false);
  for (int i = 0; i < p; ++i) {
    const double span = info.upper[i] - info.lower[i];
    fit.at_bound[i] = coef[i] - info.lower[i] <= 1e-9 * span || info.upper[i] - coef[i] <= 1e-9 * span;
  }
  if (!options.covariance) return fit;
  // A coefficient that ended on its bound is an active constraint, not a free estimate: hold it there so the
  // covariance describes the free ones (otherwise (J^T J)^-1 reports a meaningless, huge, unconstrained sd).
  std::vector<int> fixed;
  for (int i = 0; i < p; ++i)
    if (fit.at_bound[i]) fixed.push_back(i);
  if (static_cast<int>(fixed.size()) == p) return fit;
  if (!fixed.empty()) problem.SetManifold(coef.data(), new ceres::SubsetManifold(p, fixed));
  const int free = p - static_cast<int>(fixed.size());
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::DENSE_SVD;
  ceres::Covariance cov(co);
  std::vector<std::pair<const double*, const double*>> blocks{{coef.data(), coef.data()}};
  if (cov.Compute(blocks, &problem)) {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m(p, p);
    cov.GetCovarianceBlock(coef.data(), coef.data(), m.data());
    const double s2 = fit.rms * fit.rms * fit.n / (fit.n - free);
    fit.covariance = m * s2;
    fit.covariance_ok = true;
    for (int i = 0; i < p; ++i)
      if (!fit.at_bound[i]) fit.sd[i] = std::sqrt(std::max(0.0, fit.covariance(i, i)));
  }
  return fit;
}

}  // namespace pastemix::lab::drag
