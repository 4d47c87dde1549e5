// SPDX-License-Identifier: MIT
#include "model/coupling/drag.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

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

namespace {

// Gauss-Legendre nodes and weights on [-1, 1], 16 points.
constexpr std::array<double, 8> kGlX{0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                                     0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
constexpr std::array<double, 8> kGlW{0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                                     0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};
template <class F>
double gauss(double lo, double hi, F&& f) {  // 16-point Gauss-Legendre of f over [lo, hi]
  const double m = 0.5 * (lo + hi), r = 0.5 * (hi - lo);
  double sum = 0.0;
  for (std::size_t k = 0; k < kGlX.size(); ++k) sum += kGlW[k] * (f(m - r * kGlX[k]) + f(m + r * kGlX[k]));
  return sum * r;
}

// Density of E1 - E2 at u in [0, 2], E_i the unit Epanechnikov kernel: a polynomial of degree 5, exact.
double epanechnikov_difference(double u) {
  return gauss(u - 1.0, 1.0, [u](double x) { return 0.5625 * (1.0 - x * x) * (1.0 - (x - u) * (x - u)); });
}

// E exp(-t^2 (u + B)^2) over B = B1 - B2 (the triangle of half-width q): closed form with erf.
double triangle_mean(double u, double t, double q) {
  if (q == 0.0) return std::exp(-t * t * u * u);
  if (t == 0.0) return 1.0;
  const double sp = std::sqrt(std::numbers::pi) / 2.0;
  // int_0^q (q - b) exp(-t^2 (u + b)^2) db and its mirror, y = t (u + b).
  auto half = [&](double uu) {
    const double y1 = t * uu, y2 = t * (uu + q);
    return ((q + uu) * sp * (std::erf(y2) - std::erf(y1)) - 0.5 / t * (std::exp(-y1 * y1) - std::exp(-y2 * y2))) / t;
  };
  return (half(u) + half(-u)) / (q * q);
}

// phi(t) = E exp(-t^2 Z^2) per axis, Z = E1 - E2 + B1 - B2 (unit kernel, cell q); symmetric in Z.
double axis_mean(double t, double q) {
  const double w = std::min(2.0, 6.0 / std::max(t, 1e-300) + q);  // where the integrand lives
  auto f = [&](double u) { return epanechnikov_difference(u) * triangle_mean(u, t, q); };
  return 2.0 * (w < 2.0 ? gauss(0.0, w, f) + gauss(w, 2.0, f) : gauss(0.0, 2.0, f));
}

}  // namespace

double kernel_inverse_distance(double q) {
  // E[1/r] = (2 / sqrt(pi)) int_0^inf phi(t)^3 dt; panels in t over the distribution's scale L = max(1, q), the
  // tail beyond T from phi ~ sqrt(pi) f_Z(0) / t.
  const std::array<double, 9> edge{0.0, 0.5, 1.5, 3.0, 6.0, 12.0, 25.0, 50.0, 100.0};
  const double L = std::max(1.0, q);
  double sum = 0.0;
  for (std::size_t k = 0; k + 1 < edge.size(); ++k)
    sum += gauss(edge[k] / L, edge[k + 1] / L, [q](double t) { return std::pow(axis_mean(t, q), 3); });
  const double T = edge.back() / L;
  const double tail = std::pow(axis_mean(T, q) * T, 3) / (2.0 * T * T);  // int_T^inf (phi(T) T / t)^3 dt
  return 2.0 / std::sqrt(std::numbers::pi) * (sum + tail);
}

double self_mobility(double diameter, double width_factor, const std::array<double, 3>& cell, double viscosity) {
  // Scale-free in q = h / a: a table over log q, filled once (the values depend on nothing else).
  constexpr int kPoints = 97;
  constexpr double kLo = -3.0, kHi = 3.0;  // log10 q
  static const std::array<double, kPoints> table = [] {
    std::array<double, kPoints> t{};
    for (int i = 0; i < kPoints; ++i) t[i] = kernel_inverse_distance(std::pow(10.0, kLo + (kHi - kLo) * i / (kPoints - 1)));
    return t;
  }();
  const double a = 0.5 * width_factor * diameter;  // m, the kernel's half-width
  const double h = std::cbrt(cell[0] * cell[1] * cell[2]);
  const double lq = std::log10(h / a);
  const double x = std::clamp((lq - kLo) / (kHi - kLo) * (kPoints - 1), 0.0, kPoints - 1.0);
  const int i = std::min(static_cast<int>(x), kPoints - 2);
  double e = table[i] + (x - i) * (table[i + 1] - table[i]);  // E[1/r] of the unit kernel
  if (lq > kHi) e *= std::pow(10.0, kHi - lq);  // a cell 1000 kernels wide: the cube's 1.8823 / q
  return e / a / (6.0 * std::numbers::pi * viscosity);
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

double own_pressure_share(const flow::Grid& g, const Stencil& s, double diameter) {
  if (s.empty()) return 0.0;
  std::array<double, 3> cells{}, faces{};  // per axis: sum w^2 over the cells, over the faces normal to it
  for (int d = 0; d < 3; ++d) {
    std::vector<double> face(static_cast<std::size_t>(g.n[d]) + 1, 0.0);
    for (const auto& [i, w] : s.axis[d]) {
      cells[d] += w * w;
      face[i] += 0.5 * w;
      face[g.periodic(d) ? (i + 1) % g.n[d] : i + 1] += 0.5 * w;
    }
    for (double w : face) faces[d] += w * w;
  }
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) sum += faces[c] * cells[(c + 1) % 3] * cells[(c + 2) % 3];
  const double volume = std::numbers::pi * diameter * diameter * diameter / 6.0;  // m3
  return volume * sum / 3.0 / g.cell_volume() / 3.0;
}

DragCoefficients drag_coefficients(const SphereDrag& law, double diameter, double width_factor, double slip, double eps,
                                   double viscosity, const std::array<double, 3>& cell, const DragClosure& closure,
                                   double own_pressure, std::optional<double> mobility) {
  if (!(slip >= 0.0) || !std::isfinite(slip) || !(eps > 0.0) || !std::isfinite(eps) || !(law.rest >= 0.0) ||
      !(law.rest_speed >= 0.0 && law.rest_speed < 0.5 * kSlopeSpeed) || !(own_pressure >= 0.0) ||
      !std::isfinite(own_pressure))
    throw std::invalid_argument(fmt::format("coupling drag: slip {} m/s, fluid fraction {}, rest drag {} N at {} m/s, own "
                                            "pressure share {} (need a finite slip >= 0, fluid fraction > 0, rest drag >= 0 "
                                            "at a speed below 5e-10 m/s, share >= 0)",
                                            slip, eps, law.rest, law.rest_speed, own_pressure));
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
    // the minimum width on cells much smaller than the sphere. The disturbance's own pressure adds k F_p
    // (drag.h): F_p (1 + k) = beta (u_f + g0 F_p - v).
    const double g0 = mobility ? *mobility : self_mobility(diameter, width_factor, cell, viscosity);
    if (!(g0 > 0.0) || !std::isfinite(g0))
      throw std::invalid_argument(fmt::format("coupling drag: self-mobility {} m/(N s) is not positive and finite", g0));
    const bool held = beta * g0 >= 0.9;
    beta /= 1.0 + own_pressure - (held ? 0.9 : beta * g0);
    return {beta, law.rest, held ? 0.0 : g0};
  }
  return {beta, law.rest, 0.0};
}

}  // namespace pastemix::coupling
