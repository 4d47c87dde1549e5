// SPDX-License-Identifier: MIT
#include "analysis/maps/maps_h5.h"

#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "base/h5.h"
#include "lab/ingest/block_cut.h"

namespace pastemix::analysis {

namespace {
constexpr const char* kRuleOpen =
    "rock above the final free surface is unmixed and counts in the layer-1 block under it (the lab cut the "
    "unmixed cone with layer 1); rock below it is mixed (in a block, below the grid or beside it); layer 1 is "
    "the top layer, depth measured from the final free surface; paste only below the surface";
constexpr const char* kRuleClosed =
    "rock above the final free surface is unmixed and in no block; rock below it is mixed (in a block, below "
    "the grid or beside it); layer 1 is the top layer, depth measured from the final free surface";
}

void write_maps_h5(const std::filesystem::path& path, const MixingMap& m, const MixingInputs& in,
                   const ResultSnapshot& r, const MapsProvenance& info, const StateMark& st) {
  H5Writer h5(path);
  h5.attribute("/", "state", st.at_rest ? "at rest" : "NOT AT REST (--allow-moving)");
  h5.attribute("/", "at_rest", static_cast<std::int64_t>(st.at_rest));
  h5.attribute("/", "moving_mass_kg", st.moving_mass);
  h5.attribute("/", "in_flight_mass_kg", st.in_flight_mass);
  h5.attribute("/", "max_speed_m_s", st.max_speed);
  h5.attribute("/", "moving_speed_limit_m_s", st.speed_limit);
  h5.attribute("/", "moving_mass_limit_kg", st.mass_limit);
  h5.attribute("/", "software", info.software);
  h5.attribute("/", "command", info.command);
  h5.attribute("/", "created", info.created);
  h5.attribute("/", "result_file", r.path);
  h5.attribute("/", "seed", r.seed);
  h5.attribute("/", "scene_hash", r.scene_hash);
  h5.attribute("/", "snapshot", static_cast<std::int64_t>(r.snapshot));
  h5.attribute("/", "snapshot_time_s", r.time_s);
  h5.attribute("/", "surface_z_m", in.surface_z);
  h5.attribute("/", "surface_z_source", in.surface_source.empty() ? r.surface_z.source : in.surface_source);
  h5.attribute("/", "paste_rule", m.from_paste_field ? std::string("paste field (flow result): paste and mixed rock from its paste fraction")
                                                     : std::string("flat surface: all fluid below the surface is paste"));
  h5.attribute("/", "paste_density_kg_m3", in.paste_density);
  h5.attribute("/", "paste_density_source", r.paste_density.source);
  h5.attribute("/", "solids_fraction", in.solids_fraction);
  h5.attribute("/", "solids_fraction_source", r.solids_fraction.source);
  h5.attribute("/", "rock_density_source", r.density_source);
  h5.attribute("/", "K_kg_m3", in.K);
  h5.attribute("/", "K_source", info.K_source.empty() ? std::string("unknown: S not computed") : info.K_source);
  h5.attribute("/", "rho_s_kg_m3", in.rho_s);
  h5.attribute("/", "e_f", in.e_f);
  h5.attribute("/", "unmixed_rule", m.layout.top_open ? kRuleOpen : kRuleClosed);
  h5.attribute("/", "notes", r.notes.empty() ? std::string("(none)") : fmt::format("{}", fmt::join(r.notes, "; ")));
  const BlockLayout& L = m.layout;
  h5.create_group("/grid");
  h5.attribute("/grid", "origin_x_m", L.origin[0]);
  h5.attribute("/grid", "origin_y_m", L.origin[1]);
  h5.attribute("/grid", "count_i", static_cast<std::int64_t>(L.count[0]));
  h5.attribute("/grid", "count_j", static_cast<std::int64_t>(L.count[1]));
  h5.attribute("/grid", "layers", static_cast<std::int64_t>(L.layers));
  h5.attribute("/grid", "size_x_m", L.size[0]);
  h5.attribute("/grid", "size_y_m", L.size[1]);
  h5.attribute("/grid", "layer_thickness_m", L.layer_thickness);
  h5.attribute("/grid", "top_open", static_cast<std::int64_t>(L.top_open ? 1 : 0));
  const std::vector<std::uint64_t> dims{static_cast<std::uint64_t>(L.count[0]), static_cast<std::uint64_t>(L.count[1]),
                                        static_cast<std::uint64_t>(L.layers)};
  h5.write("/blocks/C", m.C, dims);
  h5.write("/blocks/S", m.S, dims);
  h5.write("/blocks/S_raw", m.S_raw, dims);
  h5.write("/blocks/flag", m.flag, dims);
  h5.write("/blocks/rock_mass_kg", m.rock_mass, dims);
  h5.write("/blocks/rock_volume_m3", m.rock_volume, dims);
  h5.write("/blocks/rock_volume_submerged_m3", m.rock_volume_submerged, dims);
  h5.write("/blocks/paste_volume_m3", m.paste_volume, dims);
  h5.write("/blocks/paste_dried_mass_kg", m.paste_dried_mass, dims);
  h5.write("/blocks/block_volume_m3", m.block_volume, dims);
  std::vector<std::string> ids;
  for (int i = 1; i <= L.count[0]; ++i)
    for (int j = 1; j <= L.count[1]; ++j)
      for (int k = 1; k <= L.layers; ++k) ids.push_back(block_name(i, j, k));
  h5.write_strings("/blocks/block_id", ids);
  h5.create_group("/accounting");
  h5.attribute("/accounting", "poured_kg", m.poured);
  h5.attribute("/accounting", "in_blocks_kg", m.in_blocks);
  h5.attribute("/accounting", "below_grid_kg", m.below_grid);
  h5.attribute("/accounting", "beside_grid_kg", m.beside_grid);
  h5.attribute("/accounting", "above_uncounted_kg", m.above_uncounted);
  h5.attribute("/accounting", "above_surface_kg", m.above_surface);
  h5.attribute("/accounting", "mixed_kg", m.mixed());
  h5.attribute("/accounting", "escaped_kg", m.escaped);
  h5.attribute("/accounting", "escaped_count", static_cast<std::int64_t>(r.escaped_count));
  h5.attribute("/accounting", "conservation_relative_error", m.conservation_error());
  h5.attribute("/accounting", "overfull_blocks", static_cast<std::int64_t>(m.overfull_blocks));
  h5.close();
}

std::string maps_table(const MixingMap& m, const ResultSnapshot& r, const MixingInputs& in, const std::string& K_source) {
  const BlockLayout& L = m.layout;
  std::string o = fmt::format("maps: {} (seed {}, scene {}), snapshot {} at t = {:g} s, {} particles\n", r.path,
                              r.seed, r.scene_hash.empty() ? "?" : r.scene_hash, r.snapshot, r.time_s,
                              r.radius.size());
  o += fmt::format("surface z = {:.5g} m ({}); paste {:g} kg/m3 ({}), solids {:g} ({}); rock density: {}\n",
                   in.surface_z, in.surface_source.empty() ? r.surface_z.source : in.surface_source, in.paste_density, r.paste_density.source, in.solids_fraction,
                   r.solids_fraction.source, r.density_source);
  o += fmt::format("K = {}\n", std::isfinite(in.K) ? fmt::format("{:g} kg/m3 ({})", in.K, K_source)
                                                    : std::string("unknown: S not computed (give --K or --lab CASE)"));
  for (const auto& n : r.notes) o += "note: " + n + "\n";
  o += fmt::format("rock: poured {:.6f} kg = in blocks {:.6f} + below the grid {:.6f} + beside it {:.6f} + above "
                   "the surface in no block {:.6f} + escaped {:.6f}; relative error {:.1e}\n",
                   m.poured, m.in_blocks, m.below_grid, m.beside_grid, m.above_uncounted, m.escaped,
                   m.conservation_error());
  o += fmt::format("escaped (left the simulation's domain, removed: outflow) {:.6f} kg = {:.3g} % of the poured mass, "
                   "{} particle(s)\n",
                   m.escaped, m.poured > 0 ? 100.0 * m.escaped / m.poured : 0.0, r.escaped_count);
  o += fmt::format("mixed ({}) {:.6f} kg, unmixed {:.6f} kg; rock above the surface {}\n",
                   m.from_paste_field ? "weighted by the paste fraction around each rock" : "submerged", m.mixed(), m.unmixed(),
                   L.top_open ? "counts in the layer-1 block under it (as the lab cut it)" : "is in no block");
  if (m.conservation_error() > 1e-9)
    o += fmt::format("warning: the accounting misses {:.1e} of the poured mass (more than 1e-9)\n", m.conservation_error());
  if (m.overfull_blocks)
    o += fmt::format("warning: {} block(s) hold more rock volume than their own volume (particle overlaps); their "
                     "paste volume is set to 0\n",
                     m.overfull_blocks);
  o += "C and S in % per layer, seen from above: columns i = 1.., rows j = n..1; 100* = capped, rock0 = no rock, "
       "- = K unknown\n";
  for (int k = 1; k <= L.layers; ++k) {
    o += fmt::format("layer {}{}\n", k, k == 1 ? " (top)" : "");
    for (int j = L.count[1]; j >= 1; --j) {
      o += fmt::format("  j={:<2} C", j);
      for (int i = 1; i <= L.count[0]; ++i) o += fmt::format("{:>7.1f}", 100 * m.C[L.index(i, j, k)]);
      o += "   S";
      for (int i = 1; i <= L.count[0]; ++i) {
        const std::size_t b = L.index(i, j, k);
        std::string cell;
        switch (static_cast<lab::SFlag>(m.flag[b])) {
          case lab::SFlag::capped: cell = "100*"; break;
          case lab::SFlag::no_rock: cell = "rock0"; break;
          case lab::SFlag::no_K: cell = "-"; break;
          case lab::SFlag::value: cell = fmt::format("{:.1f}", 100 * m.S[b]); break;
        }
        o += fmt::format("{:>7}", cell);
      }
      o += "\n";
    }
  }
  return o;
}

}  // namespace pastemix::analysis
