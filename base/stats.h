// SPDX-License-Identifier: MIT
// Summary statistics for repeated trials.
#pragma once

#include <cmath>
#include <span>

namespace pastemix {

struct Summary {
  double mean = 0.0;
  double sd = 0.0;  // sample standard deviation (n - 1); 0 for n < 2
  int n = 0;
};

inline Summary summarize(std::span<const double> values) {
  Summary s;
  s.n = static_cast<int>(values.size());
  if (s.n == 0) return s;
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / s.n;
  if (s.n > 1) {
    double ss = 0.0;
    for (double v : values) ss += (v - s.mean) * (v - s.mean);
    s.sd = std::sqrt(ss / (s.n - 1));
  }
  return s;
}

}  // namespace pastemix
