// SPDX-License-Identifier: MIT
// Ensemble statistics over seeded realizations of one scene: per block mean and sd of C, the S class most
// realizations agree on, and mean and sd of the mixed / unmixed / outside masses.
#pragma once

#include <vector>

#include "analysis/maps/mixing_map.h"
#include "base/stats.h"

namespace pastemix::analysis {

// The three S classes the scoring compares (lab::SFlag without the "K unknown" case).
enum class SClass : int { unknown = -1, no_rock = 0, partial = 1, capped = 2 };
SClass s_class(std::int32_t flag);  // from lab::SFlag
const char* to_string(SClass c);    // "no rock", "S < 100 %", "capped at 100 %", "unknown (no K)"

struct Ensemble {
  BlockLayout layout;
  int n = 0;                        // realizations
  std::vector<Summary> C;           // per block, fraction
  std::vector<Summary> rock_mass;   // per block, kg
  std::vector<SClass> s_class;      // per block: the majority class (ties: the lower class)
  double no_rock_below = 0.0;       // kg, see kLabMassResolution
  std::vector<double> s_class_share;  // per block: share of realizations in that class
  // Per block, S (capped, fraction) over the realizations where it is defined (rock of at least no_rock_below
  // and a known K); n = 0 and mean NaN where none is.
  std::vector<Summary> S;
  Summary poured, mixed, unmixed, outside_grid, escaped;  // kg (escaped: left the simulation's domain)
};

// The lab weighed block masses to 0.1 g (Table 3.2 prints kg to 4 decimals), so a block it reports without
// rock may hold up to 0.05 g. For the S class vote, a model block with less rock than `no_rock_below` (kg)
// counts as "no rock" like the lab's; C itself is never altered.
inline constexpr double kLabMassResolution = 0.5e-4;  // kg, half the last printed digit of Table 3.2

// All maps must share one layout (same block count); throws std::invalid_argument otherwise.
Ensemble ensemble(const std::vector<MixingMap>& maps, double no_rock_below = kLabMassResolution);

}  // namespace pastemix::analysis
