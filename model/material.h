// SPDX-License-Identifier: MIT
// Materials and material-pair interaction coefficients, as read from a scene.
#pragma once

#include <string>

namespace pastemix::model {

struct Material {
  std::string name;
  double density = 0.0;          // kg/m3
  double youngs_modulus = 0.0;   // Pa
  double poisson_ratio = 0.0;    // -
  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }  // Pa
};

// What a scene's [[interaction]] gives for one pair of materials (walls are materials too).
struct MaterialPair {
  const Material* a = nullptr;
  const Material* b = nullptr;
  double restitution = 1.0;       // -, coefficient of restitution e in (0, 1]
  double friction = 0.0;          // -, static (Coulomb) friction mu_s
  double rolling_friction = 0.0;  // -, rolling coefficient mu_r (its meaning belongs to the rolling law)
};

}  // namespace pastemix::model
