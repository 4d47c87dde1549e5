// SPDX-License-Identifier: MIT
// Helpers for model tests: small scenes written as TOML text, parsed through the real scene loader.
#pragma once

#include <string>

#include "base/error.h"
#include "model/scene.h"

namespace pastemix::model::test {

inline Scene scene_from(const std::string& text, const std::string& name = "test.toml") {
  return parse_scene(text, name);
}

// A [[material]] block.
inline std::string material(const std::string& name, double density, double E, double nu) {
  return "[[material]]\nname = \"" + name + "\"\ndensity = " + std::to_string(density) +
         "\nyoungs_modulus = " + std::to_string(E) + "\npoisson_ratio = " + std::to_string(nu) + "\n";
}

inline std::string interaction(const std::string& pair, double e, double mu, double mu_r = 0.0) {
  return "[[interaction]]\nmaterials = \"" + pair + "\"\nrestitution = " + std::to_string(e) +
         "\nfriction = " + std::to_string(mu) + "\nrolling_friction = " + std::to_string(mu_r) + "\n";
}

// Runs `steps` (any callable) and returns the RuntimeFailure's message it stopped with ("" if none).
template <class Steps>
std::string failure_of(Steps&& steps) {
  try {
    steps();
  } catch (const RuntimeFailure& e) {
    return e.what();
  }
  return "";
}

}  // namespace pastemix::model::test
