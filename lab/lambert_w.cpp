// SPDX-License-Identifier: MIT
#include "lab/lambert_w.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace pastemix::lab {

double lambert_w_minus1(double x) {
  constexpr double e = 2.718281828459045235;
  const double branch = -1.0 / e;
  if (!(x >= branch - 1e-15 && x < 0.0))
    throw std::domain_error(fmt::format("lambert_w_minus1: x = {} is outside [-1/e, 0)", x));
  // p -> 0 at the branch point, where w = -1 exactly and Halley's step would divide by w + 1 = 0.
  const double p2 = 2.0 * (1.0 + e * x);
  if (p2 <= 0.0) return -1.0;
  double w;
  if (x < -0.25) {
    // Branch-point series (Corless et al. 1996), lower branch: p = -sqrt(2 (1 + e x)).
    const double p = -std::sqrt(p2);
    w = -1.0 + p - p * p / 3.0 + 11.0 / 72.0 * p * p * p;
  } else {
    // Asymptote for x -> 0-: w ~ L1 - L2 + L2 / L1, L1 = ln(-x), L2 = ln(-L1).
    const double l1 = std::log(-x);
    const double l2 = std::log(-l1);
    w = l1 - l2 + l2 / l1;
  }
  for (int iter = 0; iter < 50; ++iter) {
    const double ew = std::exp(w);
    const double f = w * ew - x;
    const double wp1 = w + 1.0;
    if (wp1 == 0.0) break;
    // Halley: w <- w - f / (e^w (w + 1) - (w + 2) f / (2 w + 2)).
    const double step = f / (ew * wp1 - (w + 2.0) * f / (2.0 * wp1));
    w -= step;
    if (w > -1.0) w = -1.0;  // stay on the lower branch
    if (std::abs(step) <= 4e-16 * std::abs(w)) break;
  }
  return w;
}

}  // namespace pastemix::lab
