// SPDX-License-Identifier: MIT
#include "model/coupling/mobility.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "model/coupling/drag.h"

namespace pastemix::coupling {

LatticeStokes::LatticeStokes(int n, int reach, bool free_space) : reach_(reach) {
  if (n % 2 != 0 || reach < 0 || 2 * reach + 2 > n)
    throw std::invalid_argument(fmt::format("coupling: a lattice Green's function of reach {} on {}^3 cells (need an "
                                            "even n >= 2 reach + 2)", reach, n));
  // One octant of k (j = 0..n/2 per axis, counted twice where j and n - j differ): the summand is even in each k_d.
  const int half = n / 2, R1 = reach + 1;
  std::vector<double> s(half + 1), mult(half + 1), cs(static_cast<std::size_t>(half + 1) * R1);
  for (int j = 0; j <= half; ++j) {
    const double k = 2.0 * std::numbers::pi * j / n;
    s[j] = 2.0 - 2.0 * std::cos(k);
    mult[j] = (j == 0 || j == half) ? 1.0 : 2.0;
    for (int r = 0; r <= reach; ++r) cs[j * R1 + r] = std::cos(k * r);
  }
  table_.assign(static_cast<std::size_t>(R1) * R1 * R1, 0.0);
  std::vector<double> plane(static_cast<std::size_t>(R1) * R1);  // per k_x: the sum over k_y, k_z
  for (int jx = 0; jx <= half; ++jx) {
    std::fill(plane.begin(), plane.end(), 0.0);
    for (int jy = 0; jy <= half; ++jy)
      for (int jz = 0; jz <= half; ++jz) {
        if (jx == 0 && jy == 0 && jz == 0) continue;  // the mean: no velocity
        const double lambda = s[jx] + s[jy] + s[jz];
        const double f = mult[jy] * mult[jz] * (lambda - s[jx]) / (lambda * lambda);
        for (int ry = 0; ry <= reach; ++ry) {
          const double fy = f * cs[jy * R1 + ry];
          for (int rz = 0; rz <= reach; ++rz) plane[ry * R1 + rz] += fy * cs[jz * R1 + rz];
        }
      }
    for (int rx = 0; rx <= reach; ++rx) {
      const double fx = mult[jx] * cs[jx * R1 + rx];
      for (std::size_t i = 0; i < plane.size(); ++i) table_[rx * plane.size() + i] += fx * plane[i];
    }
  }
  const double image = free_space ? kHasimotoSelf / (6.0 * std::numbers::pi * n) : 0.0;
  for (double& v : table_) v = v / (static_cast<double>(n) * n * n) + image;
}

std::array<std::size_t, 3> LatticeStokes::strides(int c) const {
  const std::size_t r1 = reach_ + 1, r2 = r1 * r1;
  return c == 0 ? std::array<std::size_t, 3>{r2, r1, 1} : (c == 1 ? std::array<std::size_t, 3>{r1, r2, 1}
                                                                    : std::array<std::size_t, 3>{1, r1, r2});
}

double LatticeStokes::component(int c, const std::array<int, 3>& r) const {
  const int x = std::abs(r[0]), y = std::abs(r[1]), z = std::abs(r[2]);
  if (x > reach_ || y > reach_ || z > reach_)
    throw std::invalid_argument(
        fmt::format("coupling: lattice offset ({}, {}, {}) beyond the reach {}", r[0], r[1], r[2], reach_));
  // G_yy(x, y, z) = G_xx(y, x, z), G_zz(x, y, z) = G_xx(z, y, x).
  return c == 0 ? xx(x, y, z) : (c == 1 ? xx(y, x, z) : xx(z, y, x));
}

const LatticeStokes& lattice_stokes() {
  static const LatticeStokes table(128, 6);
  return table;
}

namespace {

// Per axis at most this many weights (the lattices' reach is below it); fixed buffers: no allocation per call.
constexpr std::size_t kMaxRun = 15;
struct Run {  // weights along one axis, in order
  std::array<double, kMaxRun + 1> v{};
  std::size_t size = 0;
};

// The axis's cell weights in order along it (index 0 the lowest cell), or size 0 where the free-space lattice
// does not apply: the kernel in a bounded axis's end cell (a wall), spanning more than half a periodic axis, or
// more than kMaxRun cells.
Run axis_run(const flow::Grid& g, int d, const std::vector<std::pair<int, double>>& w) {
  const int n = g.n[d];
  std::array<int, kMaxRun> at{};
  if (w.empty() || w.size() > kMaxRun) return {};
  int lo = 0, hi = 0;
  for (std::size_t e = 0; e < w.size(); ++e) {
    if (!g.periodic(d)) {
      if (w[e].first == 0 || w[e].first == n - 1) return {};
      at[e] = w[e].first - w.front().first;
    } else {
      const int o = ((w[e].first - w.front().first) % n + n) % n;  // the unwrapped offset from the first entry
      at[e] = o > n / 2 ? o - n : o;
    }
    lo = std::min(lo, at[e]), hi = std::max(hi, at[e]);
  }
  Run r;
  r.size = static_cast<std::size_t>(hi - lo + 1);
  if (r.size > kMaxRun || (g.periodic(d) && 2 * static_cast<int>(r.size) > n)) return {};
  for (std::size_t e = 0; e < w.size(); ++e) r.v[at[e] - lo] += w[e].second;
  return r;
}

// A(r) = sum_i v_i v_{i+r} for r >= 0, twice where r > 0 (the sum over +-r: G and A are even).
Run autocorrelation(const Run& v) {
  Run a;
  a.size = v.size;
  for (std::size_t r = 0; r < v.size; ++r) {
    for (std::size_t i = 0; i + r < v.size; ++i) a.v[r] += v.v[i] * v.v[i + r];
    if (r > 0) a.v[r] *= 2.0;
  }
  return a;
}

// The faces' weights along the axis of the component: half of each cell's weight to its two faces.
Run face_weights(const Run& cells) {
  Run f;
  f.size = cells.size + 1;
  for (std::size_t i = 0; i < cells.size; ++i) f.v[i] += 0.5 * cells.v[i], f.v[i + 1] += 0.5 * cells.v[i];
  return f;
}

}  // namespace

std::optional<std::array<double, 3>> place_mobility(const flow::Grid& g, const Stencil& s, double viscosity,
                                                    const LatticeStokes& table) {
  if (s.empty() || !(viscosity > 0.0)) return std::nullopt;
  const double h = g.h[0];
  if (std::abs(g.h[1] - h) > 1e-9 * h || std::abs(g.h[2] - h) > 1e-9 * h) return std::nullopt;
  std::array<Run, 3> cell_a, face_a;  // per axis, the autocorrelations
  for (int d = 0; d < 3; ++d) {
    const Run v = axis_run(g, d, s.axis[d]);
    if (v.size == 0 || static_cast<int>(v.size) > table.reach()) return std::nullopt;  // faces: one more offset
    cell_a[d] = autocorrelation(v);
    face_a[d] = autocorrelation(face_weights(v));
  }
  std::array<double, 3> m{};
  for (int c = 0; c < 3; ++c) {
    const Run& ax = c == 0 ? face_a[0] : cell_a[0];
    const Run& ay = c == 1 ? face_a[1] : cell_a[1];
    const Run& az = c == 2 ? face_a[2] : cell_a[2];
    const std::array<std::size_t, 3> stride = table.strides(c);
    double sum = 0.0;
    for (std::size_t x = 0; x < ax.size; ++x)
      for (std::size_t y = 0; y < ay.size; ++y) {
        const double wxy = ax.v[x] * ay.v[y];
        const double* row = table.data() + x * stride[0] + y * stride[1];
        for (std::size_t z = 0; z < az.size; ++z) sum += wxy * az.v[z] * row[z * stride[2]];
      }
    m[c] = sum / (viscosity * h);
  }
  return m;
}

double disturbance_mobility(const flow::Grid& g, const Stencil& s, double diameter, double width_factor,
                            double viscosity, const std::array<double, 3>& slip) {
  const double a = 0.5 * width_factor * diameter;  // m
  if (a <= kPlaceAwareHalfWidth * g.h[0]) {
    if (const auto m = place_mobility(g, s, viscosity)) {
      const double w2 = slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2];
      if (!(w2 > 0.0) || !std::isfinite(w2)) return ((*m)[0] + (*m)[1] + (*m)[2]) / 3.0;
      return (slip[0] * slip[0] * (*m)[0] + slip[1] * slip[1] * (*m)[1] + slip[2] * slip[2] * (*m)[2]) / w2;
    }
  }
  return self_mobility(diameter, width_factor, g.h, viscosity);
}

}  // namespace pastemix::coupling
