// SPDX-License-Identifier: MIT
// Dedegil's drag on a sphere in a Bingham fluid at rest (Dedegil 1987; thesis eq. 4.9), opposing the motion:
//   D(s) = (pi d / 2)^2 tau_y + 1/2 Cd(Re') rho_f s^2 (pi d^2 / 4),   Re' = rho_f s^2 / (tau_y + eta_B s / d)
// with s the particle speed and Cd(Re') the region's curve (base/drag_curves.h; the lab fits it).
// Keys of its [[fluid]] table: density (kg/m3), yield_stress (Pa, >= 0), plastic_viscosity (Pa.s, > 0) and a
// named curve; or rheology_from = a lab store (its paste rheology is this law's tau_y and eta_B).
#pragma once

#include <cmath>

#include "base/drag_curves.h"
#include "base/params.h"
#include "model/laws/drag_law.h"

namespace pastemix::model {

struct BinghamDedegil {
  static constexpr const char* name = "bingham";
  static constexpr const char* default_curve = "";  // the curve belongs to the paste: the scene names it
  struct Params {
    using Law = BinghamDedegil;
    double density = 0.0;            // kg/m3
    double yield_stress = 0.0;       // Pa
    double plastic_viscosity = 0.0;  // Pa.s
  };
  static Params from_params(const pastemix::Params& f) {
    return {f.number("density", Range::positive), f.number("yield_stress", Range::non_negative),
            f.number("plastic_viscosity", Range::positive)};
  }
  static Params from_store(double density, double yield_stress, double plastic_viscosity) {
    return {density, yield_stress, plastic_viscosity};
  }

  using Sphere = DragSphere<Params>;
  static Sphere sphere(const Params& p, const drag::DragCurve& c, double d, double y) { return {p, &c, d, y}; }

  static double yield_term(const Sphere& s) { return dedegil_yield_term(s.d, s.fluid.yield_stress); }
  // Where the curve has its viscous branch Cd = c / Re' (drag_curves.h viscous_branch: the Stokes and the
  // published curve), D(s) = D(0+) + k s exactly for speeds below s_max (Re' < re_max there):
  //   k = (c/2) eta_B (pi d^2 / 4) / d   (N s/m; 3 pi eta_B d for c = 24)
  //   s_max: rho_f s^2 = re_max (tau_y + eta_B s / d), the positive root (inf for re_max = inf)
  // The stable kick (fluid/drag_kick.h affine_kick) then needs no evaluation of D and no iteration.
  // k = 0: no such branch (the kick iterates on magnitude()).
  static AffinePart affine_part(const Sphere& s) {
    const drag::ViscousBranch b = drag::viscous_branch(s.curve->id);
    if (!(b.c > 0.0)) return {};
    const double d = s.d, rho = s.fluid.density, tau = s.fluid.yield_stress, eta = s.fluid.plastic_viscosity;
    const double k = 0.5 * b.c * eta * projected_area(d) / d;
    if (b.re_max == INFINITY) return {k, INFINITY};
    const double lin = b.re_max * eta / d;  // Pa s/m: rho_f s^2 - lin s - re_max tau_y = 0
    return {k, (lin + std::sqrt(lin * lin + 4.0 * rho * b.re_max * tau)) / (2.0 * rho)};
  }
  // N; s in m/s.
  static double magnitude(const Sphere& s, double speed) {
    const double d = s.d;
    const double area = projected_area(d);  // m^2
    const double yield = yield_term(s);
    if (speed <= 0.0) return yield;
    const double re = drag::bingham_reynolds(s.fluid.density, speed, s.fluid.yield_stress, s.fluid.plastic_viscosity, d);
    return yield + 0.5 * s.curve->cd(re, s.y) * s.fluid.density * speed * speed * area;
  }
};

}  // namespace pastemix::model
