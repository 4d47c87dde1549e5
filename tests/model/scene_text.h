// SPDX-License-Identifier: MIT
// Helpers for model tests: small scenes written as TOML text, parsed through the real scene loader.
#pragma once

#include <string>
#include <utility>

#include "base/error.h"
#include "model/scene.h"
#include "tests/input_error.h"

namespace pastemix::model::test {

inline Scene scene_from(const std::string& text, const std::string& name = "test.toml") {
  return parse_scene(text, name);
}

// One rock sphere in a 2 m box: the base of the scene-error tests. Line numbers in their checks count from
// this text (scene_test.cpp, scene_checks_test.cpp): keep it in sync with them.
inline const std::string kBase =
    "time_step = 1e-6\n"           // 1
    "end_time = 0.01\n"            // 2
    "[domain]\n"                   // 3
    "min = [-1, -1, -1]\n"         // 4
    "max = [1, 1, 1]\n"            // 5
    "[contact]\n"                  // 6
    "law = \"hertz_mindlin\"\n"    // 7
    "[[material]]\n"               // 8
    "name = \"rock\"\n"            // 9
    "density = 2760\n"             // 10
    "youngs_modulus = 4.68e7\n"    // 11
    "poisson_ratio = 0.19\n"       // 12
    "[[interaction]]\n"            // 13
    "materials = \"rock/rock\"\n"  // 14
    "restitution = 0.79\n"         // 15
    "friction = 0.466\n";          // 16
// ~700 spheres of 4-6 mm (0.12 kg of "rock") thrown down at 1.5 m/s into a 3 cm cylinder on a floor: impacts,
// lasting contacts, a resting heap under a falling cloud (world_sort_test.cpp, motion_test.cpp).
inline const std::string kThrownHeap =
    "[[wall]]\nname = \"floor\"\ntype = \"plane\"\nmaterial = \"rock\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n"
    "[[wall]]\nname = \"tube\"\ntype = \"cylinder\"\nmaterial = \"rock\"\ncenter = [0, 0]\nradius = 0.03\n"
    "z_min = 0\nz_max = 0.2\n"
    "[[factory]]\nmaterial = \"rock\"\nmass = 0.12\nshape = \"cylinder\"\ncenter = [0, 0]\nradius = 0.028\n"
    "z_min = 0.003\nz_max = 0.12\nvelocity = [0, 0, -1.5]\n[[factory.psd]]\nd_min = 4e-3\nd_max = 6e-3\n"
    "fraction = 1.0\n";
inline const std::string kSphere = "[[particle]]\nmaterial = \"rock\"\nradius = 0.01\nposition = [0, 0, 0]\n";

// The InputError message of loading `text` as the scene file `path` ("" if it loads).
inline std::string error_of(const std::string& text, const std::string& path = "bad.toml") {
  return pastemix::test::input_error_of([&] { parse_scene(text, path); });
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

// The ch. 5-7 rock (E reduced to 4.68e7 Pa) against itself with constant-torque rolling (mu_r = 0.15): the
// [contact], [[material]] and [[interaction]] tables of the small engine scenes.
inline const std::string kRockRolling = R"([contact]
law = "hertz_mindlin"
rolling = "constant_torque"
[[material]]
name = "rock"
density = 2760
youngs_modulus = 4.68e7
poisson_ratio = 0.19
[[interaction]]
materials = "rock/rock"
restitution = 0.79
friction = 0.466
rolling_friction = 0.15
)";

// A rock box wall named "box" from `min` to `max` (TOML arrays, m).
inline std::string box_wall(const std::string& min, const std::string& max) {
  return "[[wall]]\nname = \"box\"\ntype = \"box\"\nmaterial = \"rock\"\nmin = " + min + "\nmax = " + max + "\n";
}

// A [[factory]] of `mass` kg of rock, 2.5-5 mm spheres, filled into the box from `min` to `max` (TOML arrays, m).
inline std::string rock_factory(const std::string& mass, const std::string& min, const std::string& max) {
  return "[[factory]]\nmaterial = \"rock\"\nmass = " + mass + "\nshape = \"box\"\nmin = " + min + "\nmax = " + max +
         "\n[[factory.psd]]\nd_min = 2.5e-3\nd_max = 5.0e-3\nfraction = 1.0\n";
}

// Runs `steps` (any callable) and returns the RuntimeFailure's message it stopped with ("" if none).
template <class Steps>
std::string failure_of(Steps&& steps) {
  return pastemix::test::runtime_failure_of(std::forward<Steps>(steps));
}

}  // namespace pastemix::model::test
