// SPDX-License-Identifier: MIT
#include "lab/manifest.h"

#include <fmt/format.h>

#include "base/error.h"

namespace pastemix::lab {

Manifest Manifest::load(const std::filesystem::path& dir) {
  Manifest m;
  m.dir_ = dir;
  m.path_ = dir / "manifest.toml";
  if (!std::filesystem::is_regular_file(m.path_))
    throw InputError(m.path_.string(), 0, "", "no manifest: a dataset folder needs a manifest.toml saying which "
                                             "file feeds which ingester");
  m.root_ = Params::parse_file(m.path_);
  return m;
}

ManifestInput Manifest::input(const Params& table, const std::vector<ColumnSpec>& specs,
                              std::string_view file_key) const {
  ManifestInput in;
  in.relative = table.string(file_key);
  if (in.relative.empty() || std::filesystem::path(in.relative).is_absolute())
    table.fail(file_key, "expected a file name relative to the dataset folder");
  in.path = dir_ / in.relative;
  if (!std::filesystem::is_regular_file(in.path))
    table.fail(file_key, fmt::format("file '{}' not found in the dataset folder {}", in.relative, dir_.string()));
  in.units = ColumnUnits::from_manifest(specs, table.table("units"));
  // Values a lab cannot have measured are errors (a density in g/cm3 under "kg/m3"); a dataset that really
  // holds them says so here, for this input only.
  in.units.set_plausibility_checks(!table.boolean_or("allow_implausible_values", false));
  return in;
}

CsvTable Manifest::read(const ManifestInput& input) { return CsvTable::read(input.path); }

}  // namespace pastemix::lab
