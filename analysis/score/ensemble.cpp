// SPDX-License-Identifier: MIT
#include "analysis/score/ensemble.h"

#include <array>
#include <cmath>
#include <stdexcept>

#include "lab/ingest/block_cut.h"

namespace pastemix::analysis {

SClass s_class(std::int32_t flag) {
  switch (static_cast<lab::SFlag>(flag)) {
    case lab::SFlag::no_rock: return SClass::no_rock;
    case lab::SFlag::value: return SClass::partial;
    case lab::SFlag::capped: return SClass::capped;
    case lab::SFlag::no_K: return SClass::unknown;
  }
  return SClass::unknown;
}

const char* to_string(SClass c) {
  switch (c) {
    case SClass::no_rock: return "no rock";
    case SClass::partial: return "S < 100 %";
    case SClass::capped: return "capped at 100 %";
    case SClass::unknown: return "unknown (no K)";
  }
  return "?";
}

Ensemble ensemble(const std::vector<MixingMap>& maps, double no_rock_below) {
  if (maps.empty()) throw std::invalid_argument("ensemble of no maps");
  Ensemble e;
  e.layout = maps.front().layout;
  e.n = static_cast<int>(maps.size());
  e.no_rock_below = no_rock_below;
  const std::size_t nb = e.layout.block_count();
  for (const auto& m : maps)
    if (m.C.size() != nb) throw std::invalid_argument("ensemble: maps on different grids");
  std::vector<double> v(maps.size());
  auto over = [&](auto get) {
    for (std::size_t r = 0; r < maps.size(); ++r) v[r] = get(maps[r]);
    return summarize(v);
  };
  for (std::size_t b = 0; b < nb; ++b) {
    e.C.push_back(over([b](const MixingMap& m) { return m.C[b]; }));
    e.rock_mass.push_back(over([b](const MixingMap& m) { return m.rock_mass[b]; }));
    std::array<int, 4> votes{};  // unknown, no_rock, partial, capped
    for (const auto& m : maps) {
      const SClass c = m.rock_mass[b] < no_rock_below ? SClass::no_rock : s_class(m.flag[b]);
      ++votes[static_cast<std::size_t>(static_cast<int>(c) + 1)];
    }
    int best = 0;
    for (int c = 1; c < 4; ++c)
      if (votes[static_cast<std::size_t>(c)] > votes[static_cast<std::size_t>(best)]) best = c;
    e.s_class.push_back(static_cast<SClass>(best - 1));
    e.s_class_share.push_back(static_cast<double>(votes[static_cast<std::size_t>(best)]) / e.n);
    std::vector<double> s_defined;
    for (const auto& m : maps)
      if (m.rock_mass[b] >= no_rock_below && std::isfinite(m.S[b])) s_defined.push_back(m.S[b]);
    Summary s = summarize(s_defined);
    if (s_defined.empty()) s.mean = std::nan("");
    e.S.push_back(s);
  }
  e.poured = over([](const MixingMap& m) { return m.poured; });
  e.mixed = over([](const MixingMap& m) { return m.mixed(); });
  e.unmixed = over([](const MixingMap& m) { return m.unmixed(); });
  e.outside_grid = over([](const MixingMap& m) { return m.outside_grid(); });
  e.escaped = over([](const MixingMap& m) { return m.escaped; });
  return e;
}

}  // namespace pastemix::analysis
