// SPDX-License-Identifier: MIT
#include "analysis/geometry/sphere_box.h"

#include <algorithm>
#include <cmath>
#include <vector>
#include "base/units.h"

namespace pastemix::analysis {

namespace {


// Antiderivative of sqrt(r^2 - x^2) on [-r, r].
double sqrt_antiderivative(double r, double x) {
  x = std::clamp(x, -r, r);
  const double s = std::sqrt(std::max(0.0, r * r - x * x));
  return 0.5 * (x * s + r * r * std::asin(x / r));
}

// Integral of the chord half-length s(x) = sqrt(r^2 - x^2) over [x0, x1] (clamped to the disc).
double integral_s(double r, double x0, double x1) {
  if (x1 <= x0) return 0.0;
  return sqrt_antiderivative(r, x1) - sqrt_antiderivative(r, x0);
}

// Area of the disc intersected with the quadrant {x < a, y < b}.
double disc_quadrant_area(double r, double a, double b) {
  const double xa = std::min(a, r);
  if (xa <= -r || b <= -r) return 0.0;
  if (b >= r) return 2.0 * integral_s(r, -r, xa);  // the half-plane x < a
  // For |x| < c the vertical chord [-s, s] is cut at b: length b + s. For |x| > c the chord lies wholly
  // below b (b > 0: length 2s) or wholly above it (b < 0: nothing).
  const double c = std::sqrt(r * r - b * b);
  double area = 0.0;
  const double m0 = -c, m1 = std::min(c, xa);
  if (m1 > m0) area += b * (m1 - m0) + integral_s(r, m0, m1);
  if (b > 0.0) {
    area += 2.0 * integral_s(r, -r, std::min(-c, xa));
    if (xa > c) area += 2.0 * integral_s(r, c, xa);
  }
  return area;
}

// Tanh-sinh quadrature of f on [a, b]. The integrand here is bounded, with square-root behaviour of its
// derivative at the ends; the double-exponential node clustering makes that converge exponentially.
// Nodes that round onto an end point are harmless because f itself is finite there.
template <class F>
double tanh_sinh(F&& f, double a, double b) {
  if (b <= a) return 0.0;
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  constexpr double h = 1.0 / 16.0;  // step in t; |t| <= 3.5 (113 nodes) reaches the ends to ~1e-16
  double sum = 0.0;
  for (int k = -56; k <= 56; ++k) {
    const double t = k * h;
    const double u = 0.5 * units::pi * std::sinh(t);
    const double ch = std::cosh(u);
    const double w = 0.5 * units::pi * std::cosh(t) / (ch * ch);
    sum += w * f(mid + half * std::tanh(u));
  }
  return sum * h * half;
}

}  // namespace

double disc_rectangle_area(double r, double x0, double x1, double y0, double y1) {
  if (r <= 0.0 || x1 <= x0 || y1 <= y0) return 0.0;
  const double area = disc_quadrant_area(r, x1, y1) - disc_quadrant_area(r, x0, y1) -
                      disc_quadrant_area(r, x1, y0) + disc_quadrant_area(r, x0, y0);
  return std::max(0.0, area);
}

double sphere_box_volume(const Vec3& c, double r, const Box3& box) {
  // Box relative to the sphere centre.
  const double x0 = box.lo.x - c.x, x1 = box.hi.x - c.x;
  const double y0 = box.lo.y - c.y, y1 = box.hi.y - c.y;
  const double z0 = std::max(box.lo.z - c.z, -r), z1 = std::min(box.hi.z - c.z, r);
  if (z1 <= z0 || x1 <= -r || x0 >= r || y1 <= -r || y0 >= r) return 0.0;
  // Whole sphere inside: exact shortcut.
  if (x0 <= -r && x1 >= r && y0 <= -r && y1 >= r && z0 <= -r && z1 >= r) return 4.0 / 3.0 * units::pi * r * r * r;
  // Heights where a slice circle (radius rho(z)) crosses an edge line (|x_i| or |y_j|) or a corner.
  std::vector<double> cuts{z0, z1};
  auto add_level = [&](double d2) {
    if (d2 >= r * r) return;
    const double z = std::sqrt(r * r - d2);
    for (double zz : {-z, z})
      if (zz > z0 && zz < z1) cuts.push_back(zz);
  };
  for (double x : {x0, x1}) {
    add_level(x * x);
    for (double y : {y0, y1}) add_level(x * x + y * y);
  }
  for (double y : {y0, y1}) add_level(y * y);
  if (0.0 > z0 && 0.0 < z1) cuts.push_back(0.0);
  std::sort(cuts.begin(), cuts.end());
  auto slice_area = [&](double z) {
    const double rho = std::sqrt(std::max(0.0, r * r - z * z));
    return disc_rectangle_area(rho, x0, x1, y0, y1);
  };
  double volume = 0.0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) volume += tanh_sinh(slice_area, cuts[k], cuts[k + 1]);
  return volume;
}

}  // namespace pastemix::analysis
