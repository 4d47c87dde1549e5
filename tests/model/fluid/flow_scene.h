// SPDX-License-Identifier: MIT
// Scene texts of the flow-pass tests (tests/model/fluid/flow_*_test.cpp): the 6 x 6 cm rock box with a
// dynamics = "flow" region of 1 cm cells up to 12 cm, parsed through the real scene loader.
#pragma once

#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "tests/model/scene_text.h"

namespace pastemix::model::test {

// The two arrays hold the same bits.
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// The box, its rock and a flow region with the paste's keys `paste` and the flow keys `flow` added; the
// surface at `surface` m. No particles: the caller appends them.
inline std::string flow_box(double dt, double surface, const std::string& paste, const std::string& flow,
                            double end_time = 0.3) {
  return fmt::format("seed = 11\ntime_step = {}\nend_time = {}\n[domain]\nmin = [-0.02, -0.02, -0.01]\n"
                     "max = [0.08, 0.08, 0.35]\non_exit = \"remove\"\n[neighbor]\nskin = 1.25e-3\n",
                     dt, end_time) +
         kRockRolling + box_wall("[0.0, 0.0, 0.0]", "[0.06, 0.06, 0.3]") +
         fmt::format("[[fluid]]\nname = \"paste\"\nx = [0.0, 0.06]\ny = [0.0, 0.06]\nbottom = 0.0\nsurface = {}\n",
                     surface) +
         paste + "dynamics = \"flow\"\ncell = 0.01\ntop = 0.12\n" + flow;
}

// 8 g of 5-6 mm rocks dropped from 12-24 cm into 6 cm of a Bingham paste (tau_y 46 Pa, eta_B 0.2 Pa s, m = 100 s),
// coupled every 50 steps of 2e-5 s: datasets/scenes/flow_drop.toml's set-up, run to `end_time`; the rocks fill
// z_lo to z_hi (m).
inline std::string flow_drop_scene(double end_time, long coupling_interval = 50, const std::string& z_lo = "0.12",
                                   const std::string& z_hi = "0.24") {
  return flow_box(2e-5, 0.06,
                  "density = 1789.4\nrheology = \"bingham\"\nyield_stress = 46.0\nplastic_viscosity = 0.2\n"
                  "curve = \"published_4_19\"\nregularisation = 100.0\n",
                  fmt::format("coupling_interval = {}\n", coupling_interval), end_time) +
         fmt::format("[[factory]]\nmaterial = \"rock\"\nmass = 0.008\nshape = \"box\"\nmin = [0.008, 0.008, {}]\n"
                     "max = [0.052, 0.052, {}]\n[[factory.psd]]\nd_min = 5e-3\nd_max = 6e-3\nfraction = 1.0\n",
                     z_lo, z_hi);
}

}  // namespace pastemix::model::test
