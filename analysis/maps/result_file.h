// SPDX-License-Identifier: MIT
// What the mixing maps need from a model result file (HDF5, schema in model/output.h), read through files only.
//
// Read from the file:
//   /snapshots/NNNNNN/{position (N x 3, m), radius (N, m), material (N)}   the chosen (default: last) snapshot
//                     velocity (N x 3, m/s) when present: whether the state is at rest (maps/motion.h)
//   /materials (M names), /material_density (M, kg/m3)                      rock density per material
//   root attributes seed, scene_hash; fluid_surface_z (m), fluid_density (kg/m3), fluid_solids_fraction (-)
//   /escaped/{time (s), mass (kg)}   particles removed at the domain boundary ([domain] on_exit = "remove"):
//                                    those removed up to the snapshot's time are part of the poured mass
//                                    (absent in older files and runs without outflow: no escapes)
//   /flow                            a `dynamics = "flow"` result's paste field (paste_field.h), optional; with it
//                                    fluid_surface_z may be absent (the maps take the field's surface)
// The last three describe the paste at the end of the run (the surface has risen by the volume of rock that
// entered it). A command-line override takes precedence over the file and is reported as the source; without
// either, reading fails with an InputError that names the file and the missing attribute and the option.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/maps/paste_field.h"
#include "base/vec3.h"

namespace pastemix {
class H5Reader;
}

namespace pastemix::analysis {

struct ResultOverrides {
  std::optional<double> surface_z;        // m
  std::optional<double> paste_density;    // kg/m3 (wet paste)
  std::optional<double> solids_fraction;  // - (mass of solids / mass of paste)
  std::optional<double> rock_density;     // kg/m3, for every material when /material_density is absent
  std::optional<int> snapshot;            // snapshot index; default the last one
};

// A value and where it came from ("file attribute 'fluid_surface_z'" or "command line --surface-z").
struct Sourced {
  double value = 0.0;
  std::string source;
};

struct ResultSnapshot {
  std::string path;                 // the result file
  std::int64_t seed = 0;            // -1 if the file has none
  std::string scene_hash;           // "" if the file has none
  // The scene without its top-level `seed` line (text_hash, hex; the scene_hash when the file has no scene_text):
  // seeded realizations of one scene (`--realizations`, `--set seed=S`) share it, other scenes do not.
  std::string ensemble_key;
  int snapshot = 0;                 // index of the snapshot read
  double time_s = 0.0;              // its time
  std::vector<Vec3> position;  // m
  std::vector<double> radius;                   // m
  std::vector<Vec3> velocity;  // m/s (empty when the snapshot has none: motion unknown)
  // m/s, the run's [stop] displacement measure (mean speed over its last check interval), when the snapshot has
  // it: the motion census then uses it instead of the velocities (model/stop_rule.h says why)
  std::vector<double> mean_speed;
  std::vector<double> density;                  // kg/m3 per particle (from its material)
  double escaped_mass = 0.0;                    // kg, removed at the domain boundary up to time_s
  std::size_t escaped_count = 0;
  Sourced surface_z, paste_density, solids_fraction;  // surface_z NaN: none in the file, the paste field has it
  std::optional<PasteField> paste_field;  // a `dynamics = "flow"` result's paste at time_s (/flow, paste_field.h)
  std::string density_source;
  std::vector<std::string> notes;  // what came from the command line instead of the file
};

// Reads and checks everything (finite positions, positive radii, densities and paste properties, solids in
// (0, 1], material indices in range). Any defect -> InputError naming the file and the dataset or attribute.
ResultSnapshot read_result(const std::filesystem::path& path, const ResultOverrides& overrides);

// The ensemble key of a scene text: base/hash.h text_hash of its lines without a top-level `seed = ...` line.
std::string seedless_scene_key(const std::string& text);

// Index of the snapshot to read: `chosen` if the file has it, else the last NNNNNN group under /snapshots.
// InputError (naming `file`) when /snapshots is missing or empty, or `chosen` is not in it.
int snapshot_index(const H5Reader& h5, const std::string& file, std::optional<int> chosen = std::nullopt);

}  // namespace pastemix::analysis
