// SPDX-License-Identifier: MIT
#include "model/flow/obstacle.h"

#include <algorithm>

namespace pastemix::flow {

bool any_blocked(const FaceMask& m) { return blocked_count(m) > 0; }

long blocked_count(const FaceMask& m) {
  long n = 0;
  for (const auto& v : m) n += std::count(v.begin(), v.end(), static_cast<unsigned char>(1));
  return n;
}

double LiftedMould::lower_edge(double t) const {
  if (instant()) return std::numeric_limits<double>::infinity();
  return speed * std::max(0.0, t);
}

double LiftedMould::opening_time(const Grid& g, int k) const {
  if (instant()) return 0.0;
  return (k + 0.5) * g.h[2] / speed;  // the plate is the box's floor
}

int LiftedMould::open_layers(const Grid& g, double t) const {
  int k = 0;
  while (k < g.n[2] && t + 1e-12 >= opening_time(g, k)) ++k;
  return k;
}

bool LiftedMould::inside(const Grid& g, int i, int j) const {
  const double x = g.origin[0] + (i + 0.5) * g.h[0] - axis_x, y = g.origin[1] + (j + 0.5) * g.h[1] - axis_y;
  return x * x + y * y < radius * radius;
}

FaceMask LiftedMould::faces(const Grid& g, double t) const {
  FaceMask m;
  const int open = open_layers(g, t);
  if (open == g.n[2]) return m;  // gone (or never there): no wall
  // The shell is vertical: it blocks x- and y-faces only, those between an inside and an outside cell.
  for (int c = 0; c < 2; ++c) {
    m[c].assign(g.face_count(c), 0);
    const auto fd = g.face_dims(c);
    for (int k = 0; k < fd[2]; ++k) {
      if (k < open) continue;
      for (int j = 0; j < fd[1]; ++j)
        for (int i = 0; i < fd[0]; ++i) {
          std::array<int, 3> a{i, j, k}, b{i, j, k};
          a[c] = g.wrap_cell(c, a[c] - 1);
          b[c] = g.wrap_cell(c, b[c]);
          if (a[c] < 0 || b[c] < 0) continue;  // a box side: a wall already
          if (inside(g, a[0], a[1]) != inside(g, b[0], b[1])) m[c][g.face(c, {i, j, k})] = 1;
        }
    }
  }
  m[2].assign(g.face_count(2), 0);
  return m;
}

}  // namespace pastemix::flow
