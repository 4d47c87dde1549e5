// SPDX-License-Identifier: MIT
// Constant directional rolling torque, EDEM "standard" (= LIGGGHTS rolling_friction cdt):
//   tau_i = -mu_r F_n R_i omega_i / |omega_i|,  R_i the centre-to-contact distance.
// Not added to the torque: the engine sums the magnitudes M = sum mu_r F_n R_i per particle (capacity())
// and applies them in each half kick as a friction on omega that can stop the spin but never reverse it
// (world.cpp): the explicit law whenever the spin survives the step, without its chatter at omega -> 0.
#pragma once

#include "base/params.h"
#include "model/material.h"

namespace pastemix::model {

struct ConstantTorque {
  static constexpr const char* name = "constant_torque";
  struct Params {
    using Law = ConstantTorque;
    double rolling_friction = 0.0;  // -, mu_r
  };
  static constexpr int history_size = 0;
  static constexpr bool needs_rotation = true;
  static constexpr bool kick_friction = true;

  static Params from_params(const pastemix::Params&, const MaterialPair& pair) { return {pair.rolling_friction}; }

  // N.m: this contact's share mu_r F_n R_i of the particle's rolling friction (arm = R_i; R* unused).
  static double capacity(const Params& p, double normal_force, double arm, double /*R_star*/) {
    return p.rolling_friction * normal_force * arm;
  }
};

}  // namespace pastemix::model
