// SPDX-License-Identifier: MIT
// The flow solver's box grid: uniform cells over an axis-aligned box, a staggered (MAC) layout, and one
// boundary condition per face of the box.
//
// Cells are numbered i + n0 (j + n1 k) (x fastest), the row-major [k][j][i] order that XDMF reads. Velocity
// component c lives on the faces normal to axis c: face index I along c sits at x_c = origin_c + I h_c, between
// cells I-1 and I. Along a periodic axis there are n_c such faces (face n_c is face 0); along a bounded axis
// n_c + 1, the two end faces being the box's walls (or its open side). This module knows nothing of particles.
#pragma once

#include <array>
#include <string>

namespace pastemix::flow {

enum class BoundaryType {
  no_slip,    // wall: u = wall velocity (tangential), normal velocity 0
  free_slip,  // wall: normal velocity 0, no shear stress
  open,       // open side (e.g. the top): pressure 0, no stress, air (or paste) may cross it
  periodic,   // both faces of that axis; set on both or neither
};
const char* boundary_name(BoundaryType t);

struct Boundary {
  BoundaryType type = BoundaryType::no_slip;
  std::array<double, 3> wall_velocity{};  // m/s; only its tangential components are used (a moving lid)
};

struct Grid {
  std::array<int, 3> n{};           // cells per axis
  std::array<double, 3> h{};        // m, cell size per axis
  std::array<double, 3> origin{};   // m, the box's low corner
  std::array<Boundary, 6> bc{};     // x_lo, x_hi, y_lo, y_hi, z_lo, z_hi

  const Boundary& side(int d, int hi) const { return bc[2 * d + hi]; }
  bool periodic(int d) const { return bc[2 * d].type == BoundaryType::periodic; }
  long cell_count() const { return static_cast<long>(n[0]) * n[1] * n[2]; }
  double cell_volume() const { return h[0] * h[1] * h[2]; }
  long cell(int i, int j, int k) const { return i + static_cast<long>(n[0]) * (j + static_cast<long>(n[1]) * k); }
  long cell(const std::array<int, 3>& q) const { return cell(q[0], q[1], q[2]); }
  std::array<int, 3> cell_at(long c) const {  // the inverse of cell()
    return {static_cast<int>(c % n[0]), static_cast<int>((c / n[0]) % n[1]), static_cast<int>(c / (static_cast<long>(n[0]) * n[1]))};
  }

  // Faces of component c per axis.
  std::array<int, 3> face_dims(int c) const {
    std::array<int, 3> f = n;
    if (!periodic(c)) f[c] += 1;
    return f;
  }
  long face_count(int c) const {
    const auto f = face_dims(c);
    return static_cast<long>(f[0]) * f[1] * f[2];
  }
  long face(int c, const std::array<int, 3>& q) const {
    const auto f = face_dims(c);
    return q[0] + static_cast<long>(f[0]) * (q[1] + static_cast<long>(f[1]) * q[2]);
  }
  // A face of component c on the box boundary (a wall or the open side): its velocity is not advected.
  bool boundary_face(int c, int index_along_c) const {
    return !periodic(c) && (index_along_c == 0 || index_along_c == n[c]);
  }
  // Cell index along d, wrapped on a periodic axis; -1 outside a bounded one.
  int wrap_cell(int d, int i) const {
    if (i >= 0 && i < n[d]) return i;
    if (!periodic(d)) return -1;
    return ((i % n[d]) + n[d]) % n[d];
  }
  // Cell index along d, wrapped (periodic) or clamped to the box (a zero-gradient ghost).
  int clamp_cell(int d, int i) const {
    const int w = wrap_cell(d, i);
    return w >= 0 ? w : (i < 0 ? 0 : n[d] - 1);
  }
  // Index along d of a component-c face, wrapped (periodic) or clamped.
  int clamp_face(int c, int d, int i) const {
    if (c != d) return clamp_cell(d, i);
    if (periodic(d)) return ((i % n[d]) + n[d]) % n[d];
    return i < 0 ? 0 : (i > n[d] ? n[d] : i);
  }
  // Calls f(c, q) for every face q = (i, j, k) of each component c, c outermost, then in storage order (x fastest).
  template <class F>
  void for_each_face(F&& f) const {
    for (int c = 0; c < 3; ++c) {
      const auto fd = face_dims(c);
      for (int k = 0; k < fd[2]; ++k)
        for (int j = 0; j < fd[1]; ++j)
          for (int i = 0; i < fd[0]; ++i) f(c, std::array<int, 3>{i, j, k});
    }
  }
  // Throws std::invalid_argument if the grid is not usable (no cells, periodic on one side only, ...).
  void check() const;
  std::string describe() const;
};

}  // namespace pastemix::flow
