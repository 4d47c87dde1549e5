// SPDX-License-Identifier: MIT
// Drag on a sphere in a Newtonian fluid at rest: D(s) = 1/2 Cd(Re) rho_f s^2 (pi d^2 / 4), Re = rho_f s d / eta
// (Re' of thesis eq. 4.14 with tau_y = 0). With the default curve Cd = 24/Re this is Stokes's law,
// D = 3 pi eta d s, linear in s (the settling-in-water validation is exact at any time step).
// Keys of its [[fluid]] table: density (kg/m3), viscosity (Pa.s, > 0); curve optional (default stokes).
#pragma once

#include "base/drag_curves.h"
#include "base/params.h"
#include "base/units.h"
#include "model/laws/drag_law.h"

namespace pastemix::model {

struct NewtonianStokes {
  static constexpr const char* name = "newtonian";
  static constexpr const char* default_curve = "stokes";
  struct Params {
    using Law = NewtonianStokes;
    double density = 0.0;    // kg/m3
    double viscosity = 0.0;  // Pa.s
    static constexpr double yield_stress = 0.0;  // Pa: none
  };
  static Params from_params(const pastemix::Params& f) {
    return {f.number("density", Range::positive), f.number("viscosity", Range::positive)};
  }

  using Sphere = DragSphere<Params>;  // y unused: no yield stress
  static Sphere sphere(const Params& p, const drag::DragCurve& c, double d, double /*y*/) { return {p, &c, d, 0.0}; }

  static double yield_term(const Sphere&) { return 0.0; }
  // N s/m: with the Stokes curve D(s) = 3 pi eta d s exactly (24/Re times 1/2 rho s^2 pi d^2/4), so D(0+) = 0 and
  // the stable kick (fluid/drag_kick.h) has the closed form of a linear drag; 0 with any other curve (then D is
  // not linear in s and the kick iterates on magnitude()).
  static double linear_slope(const Sphere& s) {
    return s.curve->id == drag::CurveId::stokes ? 3.0 * units::pi * s.fluid.viscosity * s.d : 0.0;
  }
  // N; s in m/s. Re as the Bingham form with tau_y = 0 (0 + x is exact: the same bits as that form).
  static double magnitude(const Sphere& s, double speed) {
    if (speed <= 0.0) return 0.0;
    const double d = s.d;
    const double area = projected_area(d);  // m^2
    const double re = drag::bingham_reynolds(s.fluid.density, speed, 0.0, s.fluid.viscosity, d);
    return 0.5 * s.curve->cd(re, 0.0) * s.fluid.density * speed * speed * area;
  }
};

}  // namespace pastemix::model
