// SPDX-License-Identifier: MIT
// Terminal velocity of a sphere in a Bingham fluid under any drag curve (Dedegil's force balance, 4.9).
//
// Residual G(v) = net weight - F_d(v), v > 0. Three outcomes:
//  * suspended: G(0+) <= 0, the yield term (plus the curve's v -> 0 limit) holds the sphere;
//  * settling: exactly one sign change of G, and G is continuous there (|G| -> 0 on both sides);
//  * no consistent solution: G changes sign only across a jump of the curve (the Re' = 1 trap of 4.19): no
//    speed balances the forces, and an explicit DEM would chatter inside the bracket; or several roots.
// The full solve scans G on a log grid from 1e-9 m/s up to where the drag exceeds the weight, bisects each
// sign change to 1e-13 relative width, and classifies it by the residual left on either side. A fast path
// (bracket + bisection, no scan) is for curves known to be well posed (fitted families inside their box),
// used inside the velocity fit where it runs thousands of times.
#pragma once

#include <string>

#include "base/drag_curves.h"

namespace pastemix::lab::drag {

using pastemix::drag::BinghamSphere;
using pastemix::drag::DragCurve;

enum class SettlingOutcome { settling, suspended, no_consistent_solution, multiple_solutions };
const char* to_string(SettlingOutcome o);

struct TerminalVelocity {
  SettlingOutcome outcome = SettlingOutcome::settling;
  double v = 0.0;  // m/s: the root (settling), 0 (suspended), the bracket's midpoint (no consistent solution)
  double bracket_lo = 0.0, bracket_hi = 0.0;  // m/s: where G changes sign (jump or root)
  double residual_lo = 0.0, residual_hi = 0.0;  // G at the bracket ends, N
  int sign_changes = 0;
};

// Full, robust solve (scan for every sign change). g in m/s2.
TerminalVelocity solve_terminal_velocity(const DragCurve& curve, const BinghamSphere& s, double g);
// Fast solve for a curve with non-decreasing Cd Re' (unique root or suspended); no uniqueness scan.
TerminalVelocity solve_terminal_velocity_monotone(const DragCurve& curve, const BinghamSphere& s, double g);

// Analytic Stokes terminal velocity for a Newtonian fluid (tau_y = 0): (rho_p - rho_f) g d^2 / (18 eta).
double stokes_terminal_velocity(const BinghamSphere& s, double g);

}  // namespace pastemix::lab::drag
