// SPDX-License-Identifier: MIT
// maps.h5: one result's mixing map (written by `pastemix maps`, read by scripts/plot_mixing_maps.py).
//
// Layout (grids float64 [ni][nj][nk] row-major, index [i-1][j-1][k-1] as lab.h5: i along x, j along y,
// k = layer 1 (top) .. nk; C and S are fractions, NaN = undefined):
//   /      attrs software, command, created, result_file, seed, scene_hash, snapshot, snapshot_time_s,
//          surface_z_m (+ _source), paste_density_kg_m3 (+ _source), solids_fraction (+ _source),
//          rock_density_source, K_kg_m3 (NaN = unknown) + K_source, rho_s_kg_m3, e_f, unmixed_rule, notes,
//          state ("at rest" | "NOT AT REST (--allow-moving)"), at_rest (0/1), moving_mass_kg, in_flight_mass_kg,
//          max_speed_m_s, moving_speed_limit_m_s, moving_mass_limit_kg (maps/motion.h)
//   /grid  attrs origin_x_m, origin_y_m, count_i, count_j, layers, size_x_m, size_y_m, layer_thickness_m,
//          top_open (1: rock above the surface counts in layer 1)
//   /blocks/{C, S, S_raw, flag (int32, lab::SFlag), rock_mass_kg, rock_volume_m3, rock_volume_submerged_m3,
//            paste_volume_m3, paste_dried_mass_kg, block_volume_m3}, /blocks/block_id (strings, flattened)
//   /accounting attrs poured_kg, in_blocks_kg, below_grid_kg, beside_grid_kg, above_uncounted_kg (above the
//          surface and in no block), above_surface_kg (unmixed),
//          mixed_kg (submerged), escaped_kg (left the simulation's domain: outflow), conservation_relative_error,
//          overfull_blocks
#pragma once

#include <filesystem>
#include <string>

#include "analysis/maps/mixing_map.h"
#include "analysis/maps/motion.h"
#include "analysis/maps/result_file.h"

namespace pastemix::analysis {

struct MapsProvenance {
  std::string software, command, created;
  std::string K_source;  // "" if K is unknown
};

void write_maps_h5(const std::filesystem::path& path, const MixingMap& map, const MixingInputs& in,
                   const ResultSnapshot& result, const MapsProvenance& info, const StateMark& state = {});

// The printed summary of a map: accounting and C / S per layer (rows j = nj..1, columns i = 1..ni).
std::string maps_table(const MixingMap& map, const ResultSnapshot& result, const MixingInputs& in,
                       const std::string& K_source);

}  // namespace pastemix::analysis
