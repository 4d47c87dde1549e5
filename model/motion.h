// SPDX-License-Identifier: MIT
// Motion: how far the particles have moved since the Verlet lists were built, reduced to the few numbers the
// rebuild test needs (World::rebuild_due).
//
// The pair list holds every pair closer than r_i + r_j + skin at its build, so it stays valid while no
// pair's gap has closed by the skin: |dx_i - dx_j| < skin for every pair, dx the displacement since the
// build. The usual test (LIGGGHTS, LAMMPS: "rebuild when a particle moved skin/2") bounds that by 2 max|dx|.
// A pour defeats it: a stream of rock falls at one speed, so every falling sphere has nearly the largest
// displacement and the lists are rebuilt every few steps, although two falling spheres hardly move relative
// to each other, and a falling sphere and a resting one close their gap at the stream's speed, not twice it.
//
// So each particle is measured twice, against no motion (a = |dx|) and against a common displacement u
// (b = |dx - u|; World: u = V t, V the mean velocity of the fast spheres at the build), and counted as
// "still" (a <= b) or "moving" (b < a). For a pair, |dx_i - dx_j| <= a_i + a_j and <= b_i + b_j (the
// triangle inequality through 0 or through u), so
//   two still particles:   <= the two largest a of the still ones;
//   two moving particles:  <= the two largest b of the moving ones;
//   a still and a moving:  <= min(largest still a + largest moving a, largest still b + largest moving b).
// The largest of the three bounds every pair: exact for any u (a poor u only makes it the usual test's
// 2 max|dx| or less, never more), with no per-pair work. The same rounding as any test on |dx|: the bound is
// compared with the skin with no margin, as the usual test compares 2 max|dx| (issue 19).
#pragma once

#include <algorithm>
#include <cmath>

#include "model/vec3.h"

namespace pastemix::model {

// Keeps the two largest values seen in (first, second), first >= second (Motion and each lane of MotionLanes).
inline void keep_top_two(double& first, double& second, double v) {
  second = std::max(second, std::min(first, v));
  first = std::max(first, v);
}

struct Motion {
  // Squared displacements (m^2) since the build: the two largest a^2 of the still particles, the two largest
  // b^2 of the moving ones, the largest a^2 of the moving ones and the largest b^2 of the still ones. All
  // zero: no particle yet (a zero is below every value, so it never displaces one from a top two).
  double still1 = 0.0, still2 = 0.0;
  double moving1 = 0.0, moving2 = 0.0;
  double moving_a = 0.0;
  double still_b = 0.0;

  // Particles none of which moved more than sqrt(a2max) (m), measured against no motion only: the usual
  // test's bound, 2 sqrt(a2max).
  static Motion within(double a2max) { return {a2max, a2max, 0.0, 0.0, 0.0, a2max}; }
  // A particle with squared displacements a2 = |dx|^2 and b2 = |dx - u|^2 (m^2). Branch-free: which class a
  // sphere falls in is unpredictable where a stream meets a pile.
  void add(double a2, double b2) {
    const bool still = a2 <= b2;
    keep_top_two(still1, still2, still ? a2 : 0.0);
    keep_top_two(moving1, moving2, still ? 0.0 : b2);
    moving_a = std::max(moving_a, still ? 0.0 : a2);
    still_b = std::max(still_b, still ? b2 : 0.0);
  }
  // Another set of particles (a thread's): max and top-two merges are exact in any order.
  void merge(const Motion& o) {
    keep_top_two(still1, still2, o.still1);
    keep_top_two(still1, still2, o.still2);
    keep_top_two(moving1, moving2, o.moving1);
    keep_top_two(moving1, moving2, o.moving2);
    moving_a = std::max(moving_a, o.moving_a);
    still_b = std::max(still_b, o.still_b);
  }
  // The largest squared displacement |dx|^2 (m^2) of any particle.
  double max2() const { return std::max(still1, moving_a); }
  // An upper bound of |dx_i - dx_j| over every pair i != j (m); at most 2 sqrt(max2()).
  double pair_bound() const {
    const double s1 = std::sqrt(still1), s2 = std::sqrt(still2);
    const double m1 = std::sqrt(moving1), m2 = std::sqrt(moving2);
    const double across = std::min(s1 + std::sqrt(moving_a), std::sqrt(still_b) + m1);
    return std::max({s1 + s2, m1 + m2, across});
  }
};

// Motion::add over many particles, kLanes at a time, each lane a Motion of its own (one vector instruction
// per operation; the scalar add's chains of max per particle cost a pour's block kick ~4 ns per sphere);
// total() merges the lanes.
struct MotionLanes {
  static constexpr int kLanes = 8;
  double still1[kLanes] = {}, still2[kLanes] = {}, moving1[kLanes] = {}, moving2[kLanes] = {};
  double moving_a[kLanes] = {}, still_b[kLanes] = {};
  // Particles e = 0 .. n-1 with squared displacements a2[e], b2[e] (m^2); n a multiple of kLanes (pad with
  // zeros: a zero changes nothing).
  void add(const double* a2, const double* b2, int n) {
    for (int c = 0; c < n; c += kLanes) {
#pragma omp simd
      for (int l = 0; l < kLanes; ++l) {
        const double a = a2[c + l], b = b2[c + l];
        const bool still = a <= b;
        const double s = still ? a : 0.0, m = still ? 0.0 : b;
        keep_top_two(still1[l], still2[l], s);
        keep_top_two(moving1[l], moving2[l], m);
        moving_a[l] = std::max(moving_a[l], still ? 0.0 : a);
        still_b[l] = std::max(still_b[l], still ? b : 0.0);
      }
    }
  }
  Motion total() const {
    Motion all;
    for (int l = 0; l < kLanes; ++l) all.merge({still1[l], still2[l], moving1[l], moving2[l], moving_a[l], still_b[l]});
    return all;
  }
};

}  // namespace pastemix::model
