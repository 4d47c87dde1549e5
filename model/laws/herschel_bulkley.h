// SPDX-License-Identifier: MIT
// Drag on a sphere in a Herschel-Bulkley fluid at rest, tau = tau_y + K gamma_dot^n: Dedegil's form (thesis
// eq. 4.9) with the fluid's stress at the sphere's shear rate s/d in place of the Bingham stress,
//   D(s) = (pi d / 2)^2 tau_y + 1/2 Cd(Re_HB) rho_f s^2 (pi d^2 / 4),   Re_HB = rho_f s^2 / (tau_y + K (s/d)^n)
// (Re_HB as Kelessidis & Mpandelis 2004 define it for Herschel-Bulkley liquids). n = 1 is the Bingham law
// with eta_B = K (laws/bingham_dedegil.h), to round-off; tau_y = 0 a power-law fluid.
// Keys of its [[fluid]] table: density (kg/m3), yield_stress (Pa, >= 0), consistency K (Pa.s^n, > 0),
// flow_index n (0.1-2) and a named curve.
#pragma once

#include <cmath>

#include "base/drag_curves.h"
#include "base/params.h"
#include "model/laws/drag_law.h"

namespace pastemix::model {

struct HerschelBulkley {
  static constexpr const char* name = "herschel_bulkley";
  static constexpr const char* default_curve = "";  // the scene names the curve
  struct Params {
    using Law = HerschelBulkley;
    double density = 0.0;       // kg/m3
    double yield_stress = 0.0;  // Pa
    double consistency = 0.0;   // Pa.s^n, K
    double flow_index = 1.0;    // -, n
  };
  static Params from_params(const pastemix::Params& f) {
    Params p{f.number("density", Range::positive), f.number("yield_stress", Range::non_negative),
             f.number("consistency", Range::positive), f.number("flow_index", Range::positive)};
    if (p.flow_index < 0.1 || p.flow_index > 2.0)
      f.fail("flow_index", "the flow index n of a Herschel-Bulkley fluid must lie in [0.1, 2]");
    return p;
  }

  using Sphere = DragSphere<Params>;
  static Sphere sphere(const Params& p, const drag::DragCurve& c, double d, double y) { return {p, &c, d, y}; }

  static double yield_term(const Sphere& s) { return dedegil_yield_term(s.d, s.fluid.yield_stress); }
  // Re_HB at speed s (m/s).
  static double reynolds(const Sphere& s, double speed) {
    const Params& f = s.fluid;
    return f.density * speed * speed / (f.yield_stress + f.consistency * std::pow(speed / s.d, f.flow_index));
  }
  // N; s in m/s.
  static double magnitude(const Sphere& s, double speed) {
    const double area = projected_area(s.d);  // m^2
    const double yield = yield_term(s);
    if (speed <= 0.0) return yield;
    return yield + 0.5 * s.curve->cd(reynolds(s, speed), s.y) * s.fluid.density * speed * speed * area;
  }
};

}  // namespace pastemix::model
