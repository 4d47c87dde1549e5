// SPDX-License-Identifier: MIT
// What a rolling-resistance law is, to the engine. A rolling law is one header in laws/ plus one entry in
// RollingLaws (laws/registry.h). It provides:
//
//   name                  its scene name ([contact] rolling = "...")
//   Params                per material pair (SI), with `using Law = ...`
//   from_params(contact, pair)   the only place its keys and defaults appear: [contact] holds the law's own
//                         options, the MaterialPair the [[interaction]]'s coefficients (rolling_friction)
//   history_size          doubles per contact it keeps (after the contact law's own slots)
//   needs_rotation        whether it needs angular arrays (a law that does nothing does not)
//   kick_friction         true: the law is a non-reversing friction on omega applied in the half kick (the
//                         engine sums capacity() per particle); false: it returns a contact moment
//   capacity(prm, F_n, arm, R*)        N.m, the particle's share of the friction (kick_friction laws); arm
//                                      = its centre-to-contact distance, R* the pair's equivalent radius
//   moment(prm, RollingInput, history) N.m, the moment on i, j gets the opposite (history_size > 0 laws)
#pragma once

#include <concepts>

#include "model/vec3.h"

namespace pastemix::model {

// What a moment law sees of a contact, seen from particle i (the contact law has just run).
struct RollingInput {
  Vec3 w_rel;               // rad/s, omega_i - omega_j (omega_i for a wall)
  double normal_stiffness;  // N/m, the contact law's normal stiffness k_n at this overlap
  double normal_force;      // N, F_n >= 0
  double R_star;            // m
  double m_star;            // kg
  double dt;                // s
};

template <class R>
concept RollingLaw = requires {
  typename R::Params;
  { R::name } -> std::convertible_to<const char*>;
  { R::history_size } -> std::convertible_to<int>;
  { R::needs_rotation } -> std::convertible_to<bool>;
  { R::kick_friction } -> std::convertible_to<bool>;
};

}  // namespace pastemix::model
