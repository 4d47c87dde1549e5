// SPDX-License-Identifier: MIT
#include "model/flow/plic.h"

#include <algorithm>
#include <cmath>

namespace pastemix::flow::plic {

namespace {

// Scardovelli & Zaleski's five branches for m1 <= m2 <= m3, m1 + m2 + m3 = 1, 0 <= a <= 1/2.
double lower_half(double m1, double m2, double m3, double a) {
  const double m12 = m1 + m2;
  if (a < m1) return a * a * a / (6.0 * m1 * m2 * m3);
  if (a < m2) return a * (a - m1) / (2.0 * m2 * m3) + m1 * m1 / (6.0 * m2 * m3);
  if (a < std::min(m12, m3))
    return (a * a * (3.0 * m12 - a) + m1 * m1 * (m1 - 3.0 * a) + m2 * m2 * (m2 - 3.0 * a)) / (6.0 * m1 * m2 * m3);
  if (m3 < m12)
    return (a * a * (3.0 - 2.0 * a) + m1 * m1 * (m1 - 3.0 * a) + m2 * m2 * (m2 - 3.0 * a) +
            m3 * m3 * (m3 - 3.0 * a)) /
           (6.0 * m1 * m2 * m3);
  return (2.0 * a - m12) / (2.0 * m3);
}

}  // namespace

double cube_fraction(std::array<double, 3> m, double a) {
  const double s = m[0] + m[1] + m[2];
  a /= s;
  for (double& v : m) v /= s;
  if (a <= 0.0) return 0.0;
  if (a >= 1.0) return 1.0;
  std::sort(m.begin(), m.end());
  // A component this small against the others changes the volume by less than round-off; dropping it keeps
  // the branches that divide by it out of reach (they need m1 > 0 to be selected).
  for (double& v : m)
    if (v < 1e-12) v = 0.0;
  const double t = m[0] + m[1] + m[2];
  for (double& v : m) v /= t;
  if (a <= 0.5) return std::clamp(lower_half(m[0], m[1], m[2], a), 0.0, 1.0);
  return std::clamp(1.0 - lower_half(m[0], m[1], m[2], 1.0 - a), 0.0, 1.0);
}

namespace {

// n . x <= a over the cube, flipped so that the normal is non-negative: m = |n|, a' = a - sum_{n_i<0} n_i.
double fraction_signed(const std::array<double, 3>& n, double a) {
  std::array<double, 3> m{};
  for (int i = 0; i < 3; ++i) {
    m[i] = std::abs(n[i]);
    if (n[i] < 0.0) a -= n[i];
  }
  return cube_fraction(m, a);
}

}  // namespace

double plane_constant(const std::array<double, 3>& n, double alpha) {
  double lo = 0.0, hi = 0.0;  // the plane constant spans [sum of negative n_i, sum of positive n_i]
  for (double v : n) (v < 0.0 ? lo : hi) += v;
  // Bisection: 200 halvings at most, stopped when the bracket no longer shrinks (round-off reached).
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (fraction_signed(n, mid) < alpha ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double box_fraction(const std::array<double, 3>& n, double a, const std::array<double, 3>& lo,
                    const std::array<double, 3>& hi) {
  // x = lo + c y, y in the unit cube: n . x <= a  <=>  (n c) . y <= a - n . lo.
  std::array<double, 3> m{};
  double vol = 1.0, b = a;
  for (int i = 0; i < 3; ++i) {
    const double c = hi[i] - lo[i];
    if (!(c > 0.0)) return 0.0;
    vol *= c;
    m[i] = n[i] * c;
    b -= n[i] * lo[i];
  }
  if (m[0] == 0.0 && m[1] == 0.0 && m[2] == 0.0) return b >= 0.0 ? vol : 0.0;
  return vol * fraction_signed(m, b);
}

}  // namespace pastemix::flow::plic
