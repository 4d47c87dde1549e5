// SPDX-License-Identifier: MIT
// Internal solid faces: thin walls inside the box (the slump test's mould), as a mask over the MAC faces.
//
// A blocked face is a piece of a wall with zero normal velocity. The solver honours it in every stage
// (solver.h): the advection has no flux through it and leaves its velocity at 0, gravity and the pressure
// gradient do not act on it, the projection drops it from the pressure Laplacian (a Neumann wall: the
// pressure may jump across it), and the viscous step holds it at 0 and carries no shear on the edges around
// it (free slip on both sides of the wall; the box's own free-slip sides are the same rule). An empty mask is
// no wall at all, and every stage then does exactly what it did without one (bit for bit).
//
// A wall that is not aligned with the grid is a staircase of cell faces: the cylindrical mould blocks the
// horizontal faces between a cell whose centre is inside its radius and one whose centre is outside.
#pragma once

#include <array>
#include <limits>
#include <vector>

#include "model/flow/grid.h"

namespace pastemix::flow {

// One flag per face of each component (Grid::face indexing); 1 = blocked. Empty vectors: no wall.
using FaceMask = std::array<std::vector<unsigned char>, 3>;

inline bool blocked(const FaceMask& m, int c, long face) { return !m[c].empty() && m[c][face] != 0; }
bool any_blocked(const FaceMask& m);
long blocked_count(const FaceMask& m);

// A thin cylindrical shell with a vertical axis through (axis_x, axis_y), radius `radius` (m), its lower edge at
// z = speed t from the plate (z = origin): the slump test's mould, lifted at a constant speed from t = 0 (m/s;
// infinity: gone at t = 0, the instantaneous release), `height` the level it is filled to. A face of the
// staircase is blocked while its centre is above the lower edge: it opens when the edge passes its centre (a
// layer of faces at a time, every h_z / speed), at opening_time(k) exactly, so that a run can land its steps on
// those times. The shell reaches the box's top: faces only ever open. (Blocking a face with flow through it, as
// the rim of a 152 mm mould rising into a 160 mm box would, leaves the velocity with a divergence that the
// next advection turns into lost or created paste: 5e-8 of the volume on the 5 mm slump.)
struct LiftedMould {
  double axis_x = 0.0, axis_y = 0.0;  // m
  double radius = 0.076;              // m
  double height = 0.152;              // m: the paste's level in it (the lab mould's height)
  double speed = std::numeric_limits<double>::infinity();  // m/s

  bool instant() const { return !(speed < std::numeric_limits<double>::infinity()); }
  double lower_edge(double t) const;  // m above the plate; infinity for the instantaneous release (t >= 0)
  // When the lower edge passes the centre of layer k's faces (s; 0 for the instantaneous release).
  double opening_time(const Grid& g, int k) const;
  // The layers open at t: those whose opening time is at most t + 1e-12 s (a step that lands on an opening time
  // may end an ulp short of it).
  int open_layers(const Grid& g, double t) const;
  // Whether cell (i, j)'s centre is inside the shell's radius.
  bool inside(const Grid& g, int i, int j) const;
  // The faces the shell blocks at time t (empty once its lower edge has left the box).
  FaceMask faces(const Grid& g, double t) const;
};

}  // namespace pastemix::flow
