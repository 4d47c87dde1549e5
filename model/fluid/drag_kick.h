// SPDX-License-Identifier: MIT
// The stable implicit drag kick: the velocity update of a sphere under a drag law D(s) (laws/drag_law.h) and
// other forces, stable for any dt. The one kernel FluidField::kick runs and the tests test.
//
// Why a special update. Two properties of this force break an explicit DEM step:
//  * Stiffness: a 0.1 mm grain in water relaxes in 1.5 ms, far below the contact time step of the rock;
//    an explicit kick is unstable above twice that.
//  * The yield part is a constant force against the motion, like Coulomb friction: applied explicitly it
//    reverses the velocity and the particle chatters around v = 0 instead of stopping.
// So we write D(s) = D0 + k(s) s, where D0 = D(0+) is the part that does not vanish as s -> 0 (the yield
// term, plus the yield part hidden in Cd's 24/Re' branch) and k(s) s the rest, and advance
//   m dv/dt = F - D0 v_hat - k v
// over a kick of length h with k frozen (evaluated at the mean speed of the kick, iterated): the linear part
// is integrated exactly (exponential), and D0 removes at most the speed it can remove in that time,
// D0 (1 - exp(-k h / m)) / k, never reversing the velocity. Consequences, each tested:
//  * exact for Stokes drag with constant F (the water settling test is exact at any dt);
//  * a particle at rest whose other forces are below D0 stays exactly at rest (no creep, no chatter),
//    and restarts as soon as they exceed it;
//  * the terminal state satisfies D(s) = |F| exactly, so terminal velocities match the force balance;
//  * it never overshoots equilibrium, whatever h: the time step is set by the contacts, not the drag.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace pastemix::model::fluid {

// Linearisation of the drag for the update: D(s) = d0 + k s.
struct DragSplit {
  double d0 = 0.0;  // N, drag as s -> 0+
  double k = 0.0;   // N s/m, (D(s) - d0) / s at the evaluation speed
};

// The speed at which the limit D(0+) is evaluated. Re' there is ~1e-12 or less, deep in any curve's
// 24/Re'-like branch, where D(s) - D(0+) = O(s): the error is below 1e-9 of the force.
inline constexpr double kRestSpeed = 1e-12;  // m/s

using Vec = std::array<double, 3>;

// One kick of length h (s): v (m/s) under non-drag force F (N) on mass m (kg) plus drag with the given split.
// The kick's last part: out = v decay + F gain (the linear part, integrated exactly), then the rest drag d0
// removes at most d0 gain of speed, along the motion, never reversing it. `speed2` is |v decay + F gain|^2.
inline Vec remove_rest(Vec out, double speed2, double d0, double gain) {
  const double speed = std::sqrt(speed2);
  const double removable = d0 * gain;
  if (speed <= removable) return Vec{0.0, 0.0, 0.0};
  const double scale = (speed - removable) / speed;
  for (double& c : out) c *= scale;
  return out;
}

inline Vec drag_kick(const Vec& v, const Vec& F, double m, double h, const DragSplit& split) {
  Vec out{};
  const double a = split.k * h / m;  // dimensionless damping of the kick
  // phi = (1 - exp(-a)) / k written so it stays accurate as k -> 0 (then phi -> h / m).
  const double one_minus = -std::expm1(-a);
  const double phi = a > 1e-12 ? one_minus / split.k : h / m;
  const double decay = std::exp(-a);
  for (int c = 0; c < 3; ++c) out[c] = v[c] * decay + F[c] * phi;
  return remove_rest(out, out[0] * out[0] + out[1] * out[1] + out[2] * out[2], split.d0, phi);
}

// The kick of a linear drag D(s) = k s without a rest part (a Newtonian fluid with the Stokes curve,
// laws/newtonian_stokes.h): m dv/dt = F - k v has the exact solution v e^-a + F (1 - e^-a) / k over a kick of
// length h, a = k h / m: drag_kick with the slope k, to which drag_kick_implicit's iterations converge (there
// the slope is measured from D(1e-12 m/s) and differs from k by ~1e-12 / s relative: a rounding-level
// difference, tested in tests/model/fluid/drag_kick_test.cpp). Both factors depend only on the sphere and h,
// so FluidField computes them once per sphere: a kick is then three multiply-adds per component.
struct LinearKick {
  double decay = 1.0;  // -, e^-a
  double gain = 0.0;   // s/kg, (1 - e^-a) / k
};
inline LinearKick linear_kick(double k, double m, double h) {
  const double a = k * h / m;
  return {std::exp(-a), a > 1e-12 ? -std::expm1(-a) / k : h / m};  // the small-a form as drag_kick's
}
inline Vec apply(const LinearKick& c, const Vec& v, const Vec& F) {
  return {v[0] * c.decay + F[0] * c.gain, v[1] * c.decay + F[1] * c.gain, v[2] * c.decay + F[2] * c.gain};
}

// The kick of an affine drag D(s) = d0 + k s (laws' affine_part: a Bingham sphere on its curve's viscous
// branch, speeds below s_max): with k constant, drag_kick with the split {held, k} is what
// drag_kick_implicit's iterations converge to, and its factors depend only on the sphere and h, so
// FluidField keeps them per sphere (c = linear_kick(k, m, h); f_gain = c.gain / phi folds the scaled force
// F / phi in). No transcendental function and no evaluation of D per kick. Valid while the speed stays
// below s_max over the kick: the caller checks |v| and |v decay + F f_gain| against it (`limit2`, m2/s2)
// and takes drag_kick_implicit otherwise (returns false then). Tested against drag_kick_implicit in
// tests/model/fluid/drag_kick_test.cpp (the slope there is a difference quotient: ~1e-12 relative apart).
inline bool affine_kick(const LinearKick& c, double f_gain, double held, double limit2, const Vec& v, const Vec& F,
                        Vec& out) {
  if (!(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] < limit2)) return false;
  for (int k = 0; k < 3; ++k) out[k] = v[k] * c.decay + F[k] * f_gain;
  const double speed2 = out[0] * out[0] + out[1] * out[1] + out[2] * out[2];
  if (!(speed2 < limit2)) return false;
  out = remove_rest(out, speed2, held, c.gain);
  return true;
}

// The implicit kick: the one FluidField::kick runs and the tests test. `magnitude` is the drag D(s) (N) of
// any drag law (laws/drag_law.h), d0 = D(0+) the part the slope k(s) = (D(s) - d0) / s is measured from,
// and `held` (N) the rest resistance the kick applies (d0 for a lone sphere; d0 times its cluster factor
// under the collective rule, collective.h). k is evaluated at the mean speed of the kick (fixed-point
// iterations), which makes the update second-order accurate in the variation of k over the kick and exact at
// equilibrium; near rest the slope is a one-sided difference at 1e-9 m/s, well above kRestSpeed.
//
// At rest under forces the rest resistance holds (v = 0, |F| < held): every iteration's kick ends at
// |F| phi <= held phi, i.e. at v = 0, so the result is returned without evaluating the drag. The margin
// 1e-12 on |F| is far above the rounding of |F| phi and held phi (~1e-15), so this is the iterations' result
// to the bit, and a settled bed in a paste costs a comparison per particle and kick.
template <class D>
Vec drag_kick_implicit(const D& magnitude, double d0, double held, const Vec& v, const Vec& F, double m, double h,
                       int iterations = 3) {
  if (v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0) {
    const double hold = held * (1.0 - 1e-12);
    if (F[0] * F[0] + F[1] * F[1] + F[2] * F[2] < hold * hold) return Vec{0.0, 0.0, 0.0};
  }
  const double s0 = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  double s_eval = s0;
  Vec out = v;
  for (int it = 0; it < iterations; ++it) {
    const double s = s_eval > 1e3 * kRestSpeed ? s_eval : 1e-9;
    out = drag_kick(v, F, m, h, DragSplit{held, std::max(0.0, (magnitude(s) - d0) / s)});
    const double s1 = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
    s_eval = 0.5 * (s0 + s1);
  }
  return out;
}

}  // namespace pastemix::model::fluid
