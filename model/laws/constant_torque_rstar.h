// SPDX-License-Identifier: MIT
// Directional constant rolling torque with the rolling radius R* (Ai et al. 2011, "type A"):
//   tau_i = -mu_r F_n R* omega_i / |omega_i|,  R* = R_i R_j / (R_i + R_j) (a wall: R* = R_i).
// The EDEM "standard" law (constant_torque.h) uses the centre-to-contact distance R_i instead; for two equal
// spheres R* = R/2, so the same mu_r resists rolling half as much, and a repose calibration finds another
// coefficient. Applied as the standard law is: the engine sums mu_r F_n R* per particle and applies it in
// each half kick as a friction on omega that can stop the spin but never reverse it (world.cpp).
#pragma once

#include "base/params.h"
#include "model/material.h"

namespace pastemix::model {

struct ConstantTorqueRstar {
  static constexpr const char* name = "constant_torque_rstar";
  struct Params {
    using Law = ConstantTorqueRstar;
    double rolling_friction = 0.0;  // -, mu_r
  };
  static constexpr int history_size = 0;
  static constexpr bool needs_rotation = true;
  static constexpr bool kick_friction = true;

  static Params from_params(const pastemix::Params&, const MaterialPair& pair) { return {pair.rolling_friction}; }

  // N.m: this contact's share mu_r F_n R* of the particle's rolling friction (the arm R_i is not used).
  static double capacity(const Params& p, double normal_force, double /*arm*/, double R_star) {
    return p.rolling_friction * normal_force * R_star;
  }
};

}  // namespace pastemix::model
