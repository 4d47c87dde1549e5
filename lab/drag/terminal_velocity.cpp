// SPDX-License-Identifier: MIT
#include "lab/drag/terminal_velocity.h"

#include <cmath>
#include <vector>

#include "base/error.h"

namespace pastemix::lab::drag {

namespace {

constexpr double kVMin = 1e-9;   // m/s: "v -> 0+" (far below any settling speed worth reporting)
constexpr double kVMax = 1e4;    // m/s: no sphere in a fluid gets near this; reaching it means no drag
constexpr int kScanPoints = 4000;  // log grid over [kVMin, v_top]: about 250 points per decade

struct Residual {
  const DragCurve& curve;
  const BinghamSphere& s;
  double weight;
  double operator()(double v) const { return weight - curve.drag(s, v); }
};

// Bisects a sign change of G inside [a, b] down to a relative width of 1e-13.
TerminalVelocity bisect(const Residual& G, double a, double b) {
  double ga = G(a), gb = G(b);
  for (int it = 0; it < 300 && (b - a) > 1e-13 * b; ++it) {
    const double m = 0.5 * (a + b);
    const double gm = G(m);
    if (gm == 0.0) {
      a = b = m;
      ga = gb = 0.0;
      break;
    }
    if ((gm > 0.0) == (ga > 0.0)) a = m, ga = gm;
    else b = m, gb = gm;
  }
  TerminalVelocity r;
  r.bracket_lo = a;
  r.bracket_hi = b;
  r.residual_lo = ga;
  r.residual_hi = gb;
  // A root of a continuous G leaves |G| ~ G' * width ~ weight * 1e-13 on both sides; a jump leaves the jump.
  const double tol = 1e-7 * G.weight;
  const bool continuous = std::abs(ga) <= tol && std::abs(gb) <= tol;
  r.outcome = continuous ? SettlingOutcome::settling : SettlingOutcome::no_consistent_solution;
  // Interpolate inside the final bracket (exact for a linear G; the bracket is 1e-13 wide anyway).
  r.v = continuous && ga != gb ? a + (b - a) * ga / (ga - gb) : 0.5 * (a + b);
  return r;
}

void check_sphere(const BinghamSphere& s) {
  if (!(s.d > 0.0 && s.rho_p > 0.0 && s.rho_f > 0.0 && s.tau_y >= 0.0 && s.eta_B > 0.0))
    throw RuntimeFailure("terminal velocity: sphere or fluid properties are not positive (d, densities, eta_B)");
}

// Upper end where the drag exceeds the weight; 0 if none below kVMax.
double upper_bracket(const Residual& G) {
  double hi = 1.0;
  while (G(hi) > 0.0) {
    hi *= 2.0;
    if (hi > kVMax) return 0.0;
  }
  return hi;
}

TerminalVelocity suspended(double g0) {
  TerminalVelocity r;
  r.outcome = SettlingOutcome::suspended;
  r.residual_lo = r.residual_hi = g0;
  return r;
}

}  // namespace

const char* to_string(SettlingOutcome o) {
  switch (o) {
    case SettlingOutcome::settling: return "settling";
    case SettlingOutcome::suspended: return "suspended";
    case SettlingOutcome::no_consistent_solution: return "no_consistent_solution";
    case SettlingOutcome::multiple_solutions: return "multiple_solutions";
  }
  return "?";
}

double stokes_terminal_velocity(const BinghamSphere& s, double g) {
  return (s.rho_p - s.rho_f) * g * s.d * s.d / (18.0 * s.eta_B);
}

TerminalVelocity solve_terminal_velocity(const DragCurve& curve, const BinghamSphere& s, double g) {
  check_sphere(s);
  const Residual G{curve, s, pastemix::drag::net_weight(s, g)};
  if (G.weight <= 0.0) return suspended(G.weight);  // not heavier than the fluid: it does not sink
  const double g0 = G(kVMin);
  if (g0 <= 0.0) return suspended(g0);
  const double top = upper_bracket(G);
  if (top == 0.0) throw RuntimeFailure("terminal velocity: the drag never balances the weight below 1e4 m/s");

  std::vector<TerminalVelocity> changes;
  const double step = std::log(top / kVMin) / kScanPoints;
  double a = kVMin, ga = g0;
  for (int i = 1; i <= kScanPoints; ++i) {
    const double b = i == kScanPoints ? top : kVMin * std::exp(step * i);
    const double gb = G(b);
    if ((gb > 0.0) != (ga > 0.0)) changes.push_back(bisect(G, a, b));
    a = b, ga = gb;
  }
  if (changes.empty()) throw RuntimeFailure("terminal velocity: scan found no sign change although G(0+) > 0 > G(top)");
  TerminalVelocity r = changes.front();
  r.sign_changes = static_cast<int>(changes.size());
  if (changes.size() > 1) {
    // An odd number of sign changes: several equilibria (or roots next to jumps). Report the first bracket.
    r.outcome = SettlingOutcome::multiple_solutions;
  }
  return r;
}

TerminalVelocity solve_terminal_velocity_monotone(const DragCurve& curve, const BinghamSphere& s, double g) {
  check_sphere(s);
  const Residual G{curve, s, pastemix::drag::net_weight(s, g)};
  if (G.weight <= 0.0) return suspended(G.weight);
  const double g0 = G(kVMin);
  if (g0 <= 0.0) return suspended(g0);
  const double top = upper_bracket(G);
  if (top == 0.0) throw RuntimeFailure("terminal velocity: the drag never balances the weight below 1e4 m/s");
  double lo = top;  // shrink the bracket geometrically before bisecting (fewer steps than from 1e-9)
  while (lo > kVMin && G(lo) <= 0.0) lo *= 0.5;
  auto r = bisect(G, std::max(lo, kVMin), std::min(2.0 * lo, top));
  r.sign_changes = 1;
  return r;
}

}  // namespace pastemix::lab::drag
