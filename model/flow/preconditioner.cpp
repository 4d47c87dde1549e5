// SPDX-License-Identifier: MIT
#include "model/flow/preconditioner.h"

#include <algorithm>
#include <cmath>

namespace pastemix::flow {

namespace {
constexpr double kTau = 0.97;   // share of the dropped fill moved to the diagonal
constexpr double kSigma = 0.25;  // the modification may take at most 3/4 of a pivot; beyond, plain IC(0)'s
}  // namespace

// Right-looking: column k is scaled by its pivot, then its outer products update the columns to its right.
// An update that lands outside the pattern is dropped and (MIC) taken off the two diagonals instead. The
// safeguard compares the modified pivot with the unmodified one (`d` minus `moved`, against `d`), not with
// A's diagonal: at a density jump of 1800 an exact pivot is 1/1800 of its diagonal, and must stay so.
void MicPreconditioner::factor() const {
  const auto n = static_cast<std::size_t>(n_);
  lval_ = val_;
  ldiag_.assign(n, 0.0);
  std::vector<double> d = diag_, moved(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    double pivot = d[k] - moved[k];
    if (!(pivot >= kSigma * d[k])) pivot = d[k];
    if (!(pivot > 0.0)) pivot = diag_[k];  // IC(0) exists for an M-matrix; this only guards round-off
    const double lkk = std::sqrt(pivot);
    ldiag_[k] = lkk;
    const auto b = static_cast<std::size_t>(ptr_[k]), e = static_cast<std::size_t>(ptr_[k + 1]);
    for (std::size_t p = b; p < e; ++p) {
      lval_[p] /= lkk;
      d[static_cast<std::size_t>(idx_[p])] -= lval_[p] * lval_[p];
    }
    for (std::size_t p = b; p < e; ++p)
      for (std::size_t q = p + 1; q < e; ++q) {
        const Eigen::Index lo = std::min(idx_[p], idx_[q]), hi = std::max(idx_[p], idx_[q]);
        const double fill = lval_[p] * lval_[q];
        const auto first = idx_.begin() + ptr_[static_cast<std::size_t>(lo)];
        const auto last = idx_.begin() + ptr_[static_cast<std::size_t>(lo) + 1];
        const auto it = std::lower_bound(first, last, hi);
        if (it != last && *it == hi) {
          lval_[static_cast<std::size_t>(it - idx_.begin())] -= fill;
        } else {
          moved[static_cast<std::size_t>(lo)] += kTau * fill;
          moved[static_cast<std::size_t>(hi)] += kTau * fill;
        }
      }
  }
  factored_ = true;
}

const std::vector<double>& MicPreconditioner::pivots() const {
  if (!factored_) factor();
  return ldiag_;
}

Eigen::VectorXd MicPreconditioner::solve(const Eigen::VectorXd& r) const {
  if (!factored_) factor();
  Eigen::VectorXd y = r;
  const auto n = static_cast<std::size_t>(n_);
  for (std::size_t k = 0; k < n; ++k) {  // L y = r, by columns
    const double yk = (y[static_cast<Eigen::Index>(k)] /= ldiag_[k]);
    for (auto p = static_cast<std::size_t>(ptr_[k]); p < static_cast<std::size_t>(ptr_[k + 1]); ++p)
      y[idx_[p]] -= lval_[p] * yk;
  }
  for (std::size_t k = n; k-- > 0;) {  // L^T x = y, by rows of L^T (= columns of L)
    double s = y[static_cast<Eigen::Index>(k)];
    for (auto p = static_cast<std::size_t>(ptr_[k]); p < static_cast<std::size_t>(ptr_[k + 1]); ++p)
      s -= lval_[p] * y[idx_[p]];
    y[static_cast<Eigen::Index>(k)] = s / ldiag_[k];
  }
  return y;
}

}  // namespace pastemix::flow

namespace pastemix::flow {

Eigen::VectorXd MicPreconditioner::apply_factors(const Eigen::VectorXd& x) const {
  if (!factored_) factor();
  const auto n = static_cast<std::size_t>(n_);
  Eigen::VectorXd y(x.size());  // y = L^T x
  for (std::size_t k = 0; k < n; ++k) {
    double s = ldiag_[k] * x[static_cast<Eigen::Index>(k)];
    for (auto p = static_cast<std::size_t>(ptr_[k]); p < static_cast<std::size_t>(ptr_[k + 1]); ++p)
      s += lval_[p] * x[idx_[p]];
    y[static_cast<Eigen::Index>(k)] = s;
  }
  Eigen::VectorXd z = Eigen::VectorXd::Zero(x.size());  // z = L y
  for (std::size_t k = 0; k < n; ++k) {
    const double yk = y[static_cast<Eigen::Index>(k)];
    z[static_cast<Eigen::Index>(k)] += ldiag_[k] * yk;
    for (auto p = static_cast<std::size_t>(ptr_[k]); p < static_cast<std::size_t>(ptr_[k + 1]); ++p)
      z[idx_[p]] += lval_[p] * yk;
  }
  return z;
}

}  // namespace pastemix::flow
