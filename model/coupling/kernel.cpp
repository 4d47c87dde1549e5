// SPDX-License-Identifier: MIT
#include "model/coupling/kernel.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace pastemix::coupling {

namespace {

// Cumulative of the unit Epanechnikov kernel k(u) = 3/4 (1 - u^2) on [-1, 1].
double cumulative(double u) {
  if (u <= -1.0) return 0.0;
  if (u >= 1.0) return 1.0;
  return 0.5 + 0.75 * u - 0.25 * u * u * u;
}

// Integral over [x0, x1] of the kernel of half-width a centred at x (m).
double piece(double x0, double x1, double x, double a) { return cumulative((x1 - x) / a) - cumulative((x0 - x) / a); }

// The weights along axis d of a kernel centred at x with half-width a.
std::vector<std::pair<int, double>> axis_weights(const flow::Grid& g, int d, double x, double a) {
  const double lo = g.origin[d], h = g.h[d], length = g.n[d] * h;
  std::vector<std::pair<int, double>> out;
  if (g.periodic(d)) {
    // Unwrapped cells covering [x - a, x + a], each folded onto its periodic image; the sum telescopes to 1.
    const int first = static_cast<int>(std::floor((x - a - lo) / h)), last = static_cast<int>(std::floor((x + a - lo) / h));
    std::vector<double> w(g.n[d], 0.0);
    for (int i = first; i <= last; ++i) w[g.wrap_cell(d, i)] += piece(lo + i * h, lo + (i + 1) * h, x, a);
    for (int i = 0; i < g.n[d]; ++i)
      if (w[i] != 0.0) out.emplace_back(i, w[i]);
    return out;
  }
  const double hi = lo + length;
  if (x < lo || x > hi) return out;
  if (a > length)
    throw std::invalid_argument(fmt::format("coupling: a kernel of half-width {:.4g} m is longer than the box along "
                                            "axis {} ({:.4g} m): one reflection per wall would not be exact",
                                            a, d, length));
  // The direct part and its two mirror images (at lo and at hi); the images land inside [x - a, x + a].
  const int first = std::max(0, static_cast<int>(std::floor((std::max(lo, x - a) - lo) / h)));
  const int last = std::min(g.n[d] - 1, static_cast<int>(std::floor((std::min(hi, x + a) - lo) / h)));
  for (int i = first; i <= last; ++i) {
    const double x0 = lo + i * h, x1 = lo + (i + 1) * h;
    const double w = piece(x0, x1, x, a) + piece(x0, x1, 2.0 * lo - x, a) + piece(x0, x1, 2.0 * hi - x, a);
    if (w != 0.0) out.emplace_back(i, w);
  }
  return out;
}

}  // namespace

Stencil stencil(const flow::Grid& g, const std::array<double, 3>& centre, double diameter, double width_factor) {
  if (!(width_factor >= kMinWidthFactor) || !std::isfinite(width_factor))
    throw std::invalid_argument(fmt::format("coupling: kernel width factor c = {} is below its minimum {} (a single "
                                            "sphere's smoothed solid fraction would exceed 1)",
                                            width_factor, kMinWidthFactor));
  if (!(diameter > 0.0) || !std::isfinite(diameter))
    throw std::invalid_argument(fmt::format("coupling: particle diameter {} m is not positive and finite", diameter));
  for (double x : centre)
    if (!std::isfinite(x)) throw std::invalid_argument("coupling: a particle centre is not finite");
  const double a = 0.5 * width_factor * diameter;
  Stencil s;
  for (int d = 0; d < 3; ++d) {
    s.axis[d] = axis_weights(g, d, centre[d], a);
    if (s.axis[d].empty()) return Stencil{};  // outside the box: no part in the flow
  }
  return s;
}

void deposit(const flow::Grid& g, const Stencil& s, double amount, std::vector<double>& cells) {
  for (const auto& [k, wk] : s.axis[2])
    for (const auto& [j, wj] : s.axis[1]) {
      const double wjk = wj * wk * amount;
      for (const auto& [i, wi] : s.axis[0]) cells[g.cell(i, j, k)] += wi * wjk;
    }
}

double interpolate(const flow::Grid& g, const Stencil& s, const std::vector<double>& cell_values) {
  double sum = 0.0;
  for (const auto& [k, wk] : s.axis[2])
    for (const auto& [j, wj] : s.axis[1]) {
      const double wjk = wj * wk;
      for (const auto& [i, wi] : s.axis[0]) sum += wi * wjk * cell_values[g.cell(i, j, k)];
    }
  return sum;
}

namespace {
// Calls f(c, low face, high face, w) for every cell of the stencil and every component c.
template <class F>
void each_face_pair(const flow::Grid& g, const Stencil& s, F&& f) {
  for (const auto& [k, wk] : s.axis[2])
    for (const auto& [j, wj] : s.axis[1])
      for (const auto& [i, wi] : s.axis[0]) {
        const std::array<int, 3> q{i, j, k};
        const double w = wi * wj * wk;
        for (int c = 0; c < 3; ++c) {
          std::array<int, 3> hi = q;
          hi[c] = g.periodic(c) ? (q[c] + 1) % g.n[c] : q[c] + 1;
          f(c, g.face(c, q), g.face(c, hi), w);
        }
      }
}
}  // namespace

std::array<double, 3> interpolate_velocity(const flow::Grid& g, const Stencil& s, const flow::Faces& u) {
  std::array<double, 3> v{};
  each_face_pair(g, s, [&](int c, long lo, long hi, double w) { v[c] += w * 0.5 * (u[c][lo] + u[c][hi]); });
  return v;
}

void deposit_faces(const flow::Grid& g, const Stencil& s, const std::array<double, 3>& amount, flow::Faces& faces) {
  each_face_pair(g, s, [&](int c, long lo, long hi, double w) {
    const double half = 0.5 * w * amount[c];
    faces[c][lo] += half;
    faces[c][hi] += half;
  });
}

double weight_sum(const Stencil& s) {
  double total = 1.0;
  for (const auto& axis : s.axis) {
    double t = 0.0;
    for (const auto& e : axis) t += e.second;
    total *= t;
  }
  return s.empty() ? 0.0 : total;
}

namespace {
// A sphere's volume over the cell's (inv_cell = 1 / V_cell), the solid fraction it deposits in all.
double solid_amount(double d, double inv_cell) { return std::numbers::pi / 6.0 * d * d * d * inv_cell; }
}  // namespace

std::vector<double> solid_fraction(const flow::Grid& g, std::span<const std::array<double, 3>> centres,
                                   std::span<const double> diameters, double width_factor) {
  if (centres.size() != diameters.size()) throw std::invalid_argument("coupling: centres and diameters differ in count");
  std::vector<double> eps(g.cell_count(), 0.0);
  const double inv_cell = 1.0 / g.cell_volume();
  for (std::size_t p = 0; p < centres.size(); ++p)  // one stencil at a time: nothing kept
    deposit(g, stencil(g, centres[p], diameters[p], width_factor), solid_amount(diameters[p], inv_cell), eps);
  return eps;
}

std::vector<double> solid_fraction(const flow::Grid& g, std::span<const Stencil> stencils, std::span<const double> diameters) {
  if (stencils.size() != diameters.size()) throw std::invalid_argument("coupling: stencils and diameters differ in count");
  std::vector<double> eps(g.cell_count(), 0.0);
  const double inv_cell = 1.0 / g.cell_volume();
  for (std::size_t p = 0; p < stencils.size(); ++p) deposit(g, stencils[p], solid_amount(diameters[p], inv_cell), eps);
  return eps;
}

}  // namespace pastemix::coupling
