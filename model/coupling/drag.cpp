// SPDX-License-Identifier: MIT
#include "model/coupling/drag.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace pastemix::coupling {

namespace {
// Below this superficial slip the slope k(s) is the one-sided difference at it (as fluid/drag_kick.h's 1e-9 m/s):
// a particle at rest relative to the paste still gets the Stokes-branch coefficient of the law.
constexpr double kSlopeSpeed = 1e-9;  // m/s
}  // namespace

double di_felice_chi(double re) {
  if (!(re > 0.0)) return 3.7;  // the exponential vanishes as log10 Re -> -inf
  const double x = 1.5 - std::log10(re);
  return 3.7 - 0.65 * std::exp(-0.5 * x * x);
}

double self_mobility(double diameter, double width_factor, const std::array<double, 3>& cell, double viscosity) {
  const double a = 0.5 * width_factor * diameter;  // m, the kernel's half-width
  const double h2 = (cell[0] * cell[0] + cell[1] * cell[1] + cell[2] * cell[2]) / 3.0;
  const double sigma = std::sqrt(a * a / 5.0 + h2 / 12.0);  // m
  return 1.0 / (6.0 * std::pow(std::numbers::pi, 1.5) * viscosity * sigma);
}

double own_solid_fraction(const flow::Grid& g, const Stencil& s, double diameter) {
  if (s.empty()) return 0.0;
  double prod = 1.0;  // sum_c w_c^2 of the product kernel = the product over the axes of sum_i w_i^2
  for (const auto& axis : s.axis) {
    double sum = 0.0;
    for (const auto& [i, w] : axis) sum += w * w;
    prod *= sum;
  }
  const double volume = std::numbers::pi * diameter * diameter * diameter / 6.0;  // m3
  return volume * prod / g.cell_volume();
}

DragCoefficients drag_coefficients(const SphereDrag& law, double diameter, double width_factor, double slip, double eps,
                                   double viscosity, const std::array<double, 3>& cell, const DragClosure& closure) {
  if (!(slip >= 0.0) || !std::isfinite(slip) || !(eps > 0.0) || !std::isfinite(eps) || !(law.rest >= 0.0) ||
      !(law.rest_speed >= 0.0 && law.rest_speed < 0.5 * kSlopeSpeed))
    throw std::invalid_argument(fmt::format("coupling drag: slip {} m/s, fluid fraction {}, rest drag {} N at {} m/s (need a finite "
                                            "slip >= 0, fluid fraction > 0, rest drag >= 0 at a speed below 5e-10 m/s)",
                                            slip, eps, law.rest, law.rest_speed));
  eps = std::min(eps, 1.0);
  const double e = closure.voidage ? eps : 1.0;
  const double s = std::max(e * slip, kSlopeSpeed);  // m/s, the superficial slip the law is evaluated at
  const double D = law.magnitude(s);
  if (!std::isfinite(D) || D < law.rest * (1.0 - 1e-12))
    throw std::invalid_argument(fmt::format("coupling drag: the law's drag {} N at {} m/s is below its rest value {} N "
                                            "or not finite", D, s, law.rest));
  double beta = std::max(0.0, D - law.rest) / (s - law.rest_speed);  // kg/s against the superficial slip
  if (closure.voidage) beta *= std::pow(eps, 1.0 - di_felice_chi(law.reynolds(s)));
  if (closure.disturbance && beta > 0.0) {
    if (!(viscosity > 0.0) || !std::isfinite(viscosity))
      throw std::invalid_argument(fmt::format("coupling drag: local viscosity {} Pa s is not positive and finite", viscosity));
    // The particle's own reaction drags the fluid at it along: u_f = u_undisturbed - g0 F_p, so
    // F_p = beta (u_f + g0 F_p - v) and beta_c = beta / (1 - beta g0). beta g0 = r / a_eff for Stokes drag
    // (a_eff = sigma sqrt(pi), Maxey & Patel's radius of the smoothed force): singular when the smoothing is no
    // wider than the sphere (the grid would then resolve it). Held at 0.9 (a factor 10), for kernels near
    // the minimum width on cells much smaller than the sphere.
    beta /= 1.0 - std::min(0.9, beta * self_mobility(diameter, width_factor, cell, viscosity));
  }
  return {beta, law.rest};
}

}  // namespace pastemix::coupling
