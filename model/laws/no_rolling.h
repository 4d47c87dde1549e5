// SPDX-License-Identifier: MIT
// No rolling resistance ([contact] rolling = "none", the default): spheres roll freely.
#pragma once

#include "base/params.h"
#include "model/material.h"

namespace pastemix::model {

struct NoRolling {
  static constexpr const char* name = "none";
  struct Params {
    using Law = NoRolling;
  };
  static constexpr int history_size = 0;
  static constexpr bool needs_rotation = false;
  static constexpr bool kick_friction = false;

  // A rolling coefficient without a law to give it a meaning is a scene mistake, not a silent zero.
  static Params from_params(const pastemix::Params& contact, const MaterialPair& pair) {
    if (pair.rolling_friction > 0.0)
      contact.fail("rolling", "an [[interaction]] sets rolling_friction but no rolling law is named here");
    return {};
  }
};

}  // namespace pastemix::model
