// SPDX-License-Identifier: MIT
// Drag-coefficient curves Cd(Re') for a sphere in a Bingham fluid, evaluated by name.
//
// The lab fits these curves to settling spheres (lab/drag/) and the engine's Bingham drag law evaluates the
// same expressions by the same name, so this header is formulas only: no I/O, no Ceres. Every formula is a
// template on the scalar so that ceres::Jet can flow through it (AutoDiff in the fit, implicit
// differentiation in the velocity fit).
//
// Physics (Dedegil 1987, as used by Zhang 2024, ch. 4):
//   Re' = rho_f v^2 / (tau_y + eta_B v / d)                                  (4.18)
//   F_d = (pi d / 2)^2 tau_y + 1/2 Cd(Re') rho_f v^2 (pi d^2 / 4)             (4.9)
// Writing rho_f v^2 = Re' (tau_y + eta_B v/d), the dynamic part is 1/2 h(Re') (tau_y + eta_B v/d) pi d^2/4
// with h = Cd Re'. Re' increases strictly with v, so the drag increases with v (and a settling sphere has a
// unique terminal velocity) whenever h(Re') is non-decreasing. A curve is therefore "well posed" here if
//   (1) Cd is continuous, (2) Cd decreases with Re', and (3) Cd Re' does not decrease with Re'.
// The published curve (4.19) violates (1): h jumps from 24 to 29.3 at Re' = 1 and from 58.4 to 60 at
// Re' = 150, and a sphere whose net weight falls inside a jump has no terminal velocity at all.
// The fitted families below satisfy (1)-(3) by construction for every admissible coefficient vector:
//   power_sum:   Cd = k/Re' + a Re'^-b + c                  h = k + a Re'^(1-b) + c Re'
//   power_blend: Cd = ((k/Re' + a Re'^-b)^n + c^n)^(1/n)     h = ((k + a Re'^(1-b))^n + (c Re')^n)^(1/n)
// with k, a >= 0 (k + a > 0), 0 < b < 1, c >= 0 (> 0 for the blend), n > 0: sums and power means of
// non-increasing positive terms are non-increasing, and of non-decreasing terms non-decreasing.
// power_blend is a smooth maximum (Churchill-Usagi) of a viscous-yield branch and Newton's constant Cd = c;
// n sets how sharply the two meet.
//
// yield_blend also depends on the sphere's yield number Y = tau_y / (g d (rho_p - rho_f)) (a constant for a
// given sphere in a given fluid; the yield term holds the sphere suspended for Y >= 2/(3 pi)):
//   yield_blend: Cd = ((k exp(-q Y)/Re' + a Re'^-b)^n + c^n)^(1/n)
// For fixed Y it is power_blend with k' = k exp(-q Y) > 0, so (1)-(3) hold for every Y and admissible
// coefficient vector. Why Y: near yield the force balance fixes Cd Re' ~ (4/3)(1 - 3 pi Y / 2)/Y while the
// measured Re' spans two decades (Table 4.3 rows 1, 2, 67 against 54, 56), which no curve of Re' alone can
// follow; Beris et al. (1985) likewise find the creeping drag in a Bingham fluid set by the yield
// (Bingham) number beyond Re'. Fitted for 0.0015 <= Y <= 0.045 and Re' >= 0.4: its Y -> 0, Re' << 1 limit
// is k/Re' (k ~ 110), not Stokes 24/Re'; no sphere in the data is Newtonian and creeping.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

#include "base/units.h"

namespace pastemix::drag {

inline constexpr int kMaxCoefficients = 6;

enum class CurveId { stokes, published_4_19, power_sum, power_blend, yield_blend };

struct CurveInfo {
  CurveId id;
  std::string_view name;
  std::string_view formula;
  int n_coefficients;  // 0 for the fixed curves
  std::array<std::string_view, kMaxCoefficients> coefficient_names;
  // Admissible box (monotonicity holds inside it) and the fit's starting point.
  std::array<double, kMaxCoefficients> lower, upper, start;
  bool continuous;  // false only for the published piecewise curve
  bool uses_yield_number = false;  // Cd depends on Y = tau_y / (g d (rho_p - rho_f)) as well as Re'
};

inline constexpr std::array<CurveInfo, 5> kCurves{{
    {CurveId::stokes, "stokes", "Cd = 24/Re'", 0, {}, {}, {}, {}, true, false},
    {CurveId::published_4_19, "published_4_19",
     "Cd = 24/Re' (Re' < 1); 29.12/Re' + 0.195 (1 <= Re' <= 150); 0.4 (Re' > 150)", 0, {}, {}, {}, {},
     false, false},
    {CurveId::power_sum, "power_sum", "Cd = k/Re' + a Re'^-b + c", 4,
     {"k", "a", "b", "c", ""},
     {0.0, 0.0, 0.01, 0.0, 0.0},
     {1000.0, 1000.0, 0.99, 10.0, 0.0},
     {24.0, 3.0, 0.5, 0.3, 0.0},
     true, false},
    {CurveId::power_blend, "power_blend", "Cd = ((k/Re' + a Re'^-b)^n + c^n)^(1/n)", 5,
     {"k", "a", "b", "c", "n"},
     {0.0, 0.0, 0.01, 0.01, 0.3},
     {1000.0, 1000.0, 0.99, 10.0, 10.0},
     {24.0, 1.0, 0.5, 0.4, 1.5},
     true, false},
    {CurveId::yield_blend, "yield_blend", "Cd = ((k exp(-q Y)/Re' + a Re'^-b)^n + c^n)^(1/n), Y = tau_y/(g d (rho_p - rho_f))",
     6,
     {"k", "a", "b", "c", "n", "q"},
     {0.0, 0.0, 0.01, 0.01, 0.3, -100.0},
     {1000.0, 1000.0, 0.99, 10.0, 10.0, 200.0},
     {24.0, 1.0, 0.5, 0.4, 1.5, 0.0},
     true, true},
}};

inline const CurveInfo& curve_info(CurveId id) { return kCurves[static_cast<std::size_t>(id)]; }

inline std::optional<CurveId> find_curve(std::string_view name) {
  for (const auto& c : kCurves)
    if (c.name == name) return c.id;
  return std::nullopt;
}

// Coefficients inside the admissible box (and k + a > 0, so Cd is strictly decreasing). Returns an empty
// view on success, else a static description of what is wrong.
inline std::string_view check_coefficients(CurveId id, const std::vector<double>& c) {
  const auto& info = curve_info(id);
  if (static_cast<int>(c.size()) != info.n_coefficients) return "wrong number of coefficients";
  for (int i = 0; i < info.n_coefficients; ++i)
    if (!(c[i] >= info.lower[i] && c[i] <= info.upper[i])) return "coefficient outside its admissible range";
  if (info.n_coefficients > 0 && !(c[0] + c[1] > 0.0)) return "k + a must be positive";
  return {};
}

// Smooth maximum of the viscous-yield branch x and Newton's constant cn with exponent n (Churchill-Usagi),
// written around the larger term so x^n cannot overflow at tiny Re'.
template <typename T>
T power_mean_max(const T& x, const T& cn, const T& n) {
  using std::pow;
  const T m = x > cn ? x : cn;
  return m * pow(pow(x / m, n) + pow(cn / m, n), T(1.0) / n);
}

// Cd(Re', Y) for curve `id` with coefficients `c` (ignored by the fixed curves). Re' > 0; y is the sphere's
// yield number Y = tau_y / (g d (rho_p - rho_f)) (see yield_number), used only by families with
// uses_yield_number.
template <typename T>
T drag_coefficient(CurveId id, const T* c, const T& re, double y) {
  using std::exp;
  using std::pow;  // ceres::pow for Jets is found by argument-dependent lookup
  switch (id) {
    case CurveId::stokes:
      return T(24.0) / re;
    case CurveId::published_4_19:
      if (re < T(1.0)) return T(24.0) / re;
      if (re <= T(150.0)) return T(29.12) / re + T(0.195);
      return T(0.4) + T(0.0) * re;  // keep the derivative slot of a Jet defined
    case CurveId::power_sum:
      return c[0] / re + c[1] * pow(re, -c[2]) + c[3];
    case CurveId::power_blend:
      return power_mean_max(c[0] / re + c[1] * pow(re, -c[2]), c[3], c[4]);
    case CurveId::yield_blend:
      return power_mean_max(c[0] * exp(-c[5] * y) / re + c[1] * pow(re, -c[2]), c[3], c[4]);
  }
  return T(0.0);
}

// The curve's viscous branch: Cd = c / Re' for Re' < re_max (c = 0: the curve has none). There Dedegil's
// drag (4.9) is affine in the speed, D = (pi d / 2)^2 tau_y + (c/2) (tau_y + eta_B v / d) pi d^2 / 4, which
// the engine's kick integrates in closed form (model/laws/bingham_dedegil.h affine_part).
struct ViscousBranch {
  double c = 0.0;       // -, Cd Re' on the branch
  double re_max = 0.0;  // -, the branch holds for Re' < re_max (inf: for every Re')
};
inline ViscousBranch viscous_branch(CurveId id) {
  switch (id) {
    case CurveId::stokes:
      return {24.0, INFINITY};
    case CurveId::published_4_19:
      return {24.0, 1.0};  // drag_coefficient: re < 1
    default:
      return {};  // the fitted families: k/Re' plus a Re'^-b term (and c): taken as not affine
  }
}

// Modified particle Reynolds number (4.18); SI units, eta_B > 0.
template <typename T>
T bingham_reynolds(double rho_f, const T& v, double tau_y, double eta_B, double d) {
  return rho_f * v * v / (tau_y + eta_B * v / d);
}

// A sphere settling in a Bingham fluid at rest (SI units).
struct BinghamSphere {
  double d = 0.0;      // m
  double rho_p = 0.0;  // kg/m3
  double rho_f = 0.0;  // kg/m3
  double tau_y = 0.0;  // Pa
  double eta_B = 0.0;  // Pa.s
};


// Yield number Y = tau_y / (g d (rho_p - rho_f)) (dimensionless; g in m/s2). The yield term of (4.9) is
// 3 pi Y / 2 times the net weight, so a sphere with Y >= 2/(3 pi) ~ 0.212 stays suspended.
inline double yield_number(const BinghamSphere& s, double g) { return s.tau_y / (g * s.d * (s.rho_p - s.rho_f)); }

// Net weight (weight minus buoyancy), N.
inline double net_weight(const BinghamSphere& s, double g) {
  return (s.rho_p - s.rho_f) * g * units::pi * s.d * s.d * s.d / 6.0;
}

// Dedegil's drag (4.9) at speed v > 0, N; y = yield_number(s, g).
template <typename T>
T dedegil_drag(CurveId id, const T* c, const BinghamSphere& s, const T& v, double y) {
  const T re = bingham_reynolds(s.rho_f, v, s.tau_y, s.eta_B, s.d);
  const double area = units::pi * s.d * s.d / 4.0;
  const double yield = (units::pi * s.d / 2.0) * (units::pi * s.d / 2.0) * s.tau_y;
  return yield + 0.5 * drag_coefficient(id, c, re, y) * s.rho_f * v * v * area;
}

// Settling drag coefficient (4.17) from a measured terminal velocity: the Cd that balances net weight.
inline double settling_drag_coefficient(const BinghamSphere& s, double v, double g) {
  return 2.0 / (v * v * s.rho_f) * (2.0 / 3.0 * (s.rho_p - s.rho_f) * s.d * g - units::pi * s.tau_y);
}

// A curve with its coefficients, for callers that work in doubles.
struct DragCurve {
  CurveId id = CurveId::stokes;
  std::vector<double> coefficients;

  const CurveInfo& info() const { return curve_info(id); }
  double cd(double re, double y) const { return drag_coefficient<double>(id, coefficients.data(), re, y); }
  double drag(const BinghamSphere& s, double v, double y) const {
    return dedegil_drag<double>(id, coefficients.data(), s, v, y);
  }
};

}  // namespace pastemix::drag
