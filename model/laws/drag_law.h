// SPDX-License-Identifier: MIT
// What a drag law is, to the engine. A drag law (the force of a fluid at rest on a sphere moving at speed s)
// is one header in laws/ plus one entry in DragLaws (laws/registry.h). It provides:
//
//   name                 its scene name ([[fluid]] rheology = "...")
//   Params               the fluid's values (SI), with `using Law = ...`, `density` (kg/m3) and
//                        `yield_stress` (Pa, 0 for a fluid without one: buoyancy, the yield number Y, the
//                        collective rule and the yield_term switch read them)
//   from_params(fluid)   the only place its keys and their checks appear (the [[fluid]] table)
//   default_curve        the Cd(Re') curve when the scene names none ("" : the scene must name one)
//   from_store           (optional) Params from a lab store's tau_y, eta_B and density (rheology_from)
//   Sphere               what is constant for one sphere in this fluid (diameter, curve, Y, prefactors)
//   sphere(prm, curve, d, y)   its Sphere; d in m, y the yield number tau_y / (|g| d (rho_p - rho_f))
//   magnitude(sphere, s) the drag D(s) >= 0 in N at speed s >= 0, non-decreasing in s; D(0+) is the rest
//                        resistance the stable kick holds (fluid/drag_kick.h)
//   yield_term(sphere)   N, the (pi d / 2)^2 tau_y part of D (the scene's yield_term = false removes it)
//   affine_part(sphere)  (optional) AffinePart: the speeds below s_max where D is exactly D(0+) + k s (the
//                        stable kick then has a closed form: fluid/drag_kick.h affine_kick)
//
// The fluid pass (fluid/field.cpp) reaches a drag law only through this list, and the kick it runs is
// fluid/drag_kick.h's drag_kick_implicit over the law's magnitude.
#pragma once

#include <concepts>

#include "base/drag_curves.h"
#include "base/units.h"

namespace pastemix::model {

template <class L>
concept DragLaw = requires(const typename L::Params& p, const typename L::Sphere& s, const drag::DragCurve& c) {
  { L::name } -> std::convertible_to<const char*>;
  { L::default_curve } -> std::convertible_to<const char*>;
  { p.density } -> std::convertible_to<double>;
  { p.yield_stress } -> std::convertible_to<double>;
  { L::sphere(p, c, 1.0, 0.0) } -> std::same_as<typename L::Sphere>;
  { L::magnitude(s, 1.0) } -> std::convertible_to<double>;
  { L::yield_term(s) } -> std::convertible_to<double>;
};

// The Sphere of a law that keeps nothing more than its fluid, curve, diameter d (m) and yield number y.
template <class P>
struct DragSphere {
  P fluid;
  const drag::DragCurve* curve = nullptr;
  double d = 0.0, y = 0.0;  // m, -
};

// A law's optional affine branch (affine_part(sphere)): D(s) = D(0+) + k s for 0 <= s < s_max (k = 0: none).
struct AffinePart {
  double k = 0.0;      // N s/m
  double s_max = 0.0;  // m/s
};

// Projected area pi d^2 / 4 of a sphere of diameter d (m), m^2.
inline double projected_area(double d) { return 0.25 * units::pi * d * d; }
// Dedegil's yield term (pi d / 2)^2 tau_y (N) of a sphere of diameter d (m) in a fluid of yield stress tau_y (Pa).
inline double dedegil_yield_term(double d, double tau_y) { return 0.25 * units::pi * units::pi * d * d * tau_y; }

}  // namespace pastemix::model
