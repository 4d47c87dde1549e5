// SPDX-License-Identifier: MIT
// The dataset manifest (DIR/manifest.toml): which file feeds which ingester, with the unit of each column.
//
// Read through base/params.h so that an unknown key (a typo, a misplaced option) is an error with its line.
// Each reduce step reads its own table ([slump], [block_cut], ...) through Manifest::input, which resolves
// the file relative to the dataset folder and checks every column's unit (base/units.h): a missing file,
// an unknown unit or a unit of the wrong dimension is an InputError naming manifest.toml:line.
//
//   [slump]
//   file = "slump_tests.csv"
//   [slump.units]
//   H_mm = "mm"
//   ...
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "base/csv.h"
#include "base/params.h"
#include "lab/ingest/ingest.h"

namespace pastemix::lab {

struct ManifestInput {
  std::filesystem::path path;  // as opened (dataset folder / file), used in error messages
  std::string relative;        // as written in the manifest, recorded as the source
  ColumnUnits units;
};

class Manifest {
 public:
  // Parses DIR/manifest.toml (the file must exist).
  static Manifest load(const std::filesystem::path& dir);

  const Params& root() const { return root_; }
  const std::filesystem::path& dir() const { return dir_; }
  const std::filesystem::path& path() const { return path_; }

  // Reads `file_key` (a file name relative to the dataset folder, which must exist) and the `units` sub-table
  // of `table` for the columns of `specs`.
  ManifestInput input(const Params& table, const std::vector<ColumnSpec>& specs,
                      std::string_view file_key = "file") const;
  // Reads the CSV of an input (strict: see base/csv.h).
  static CsvTable read(const ManifestInput& input);

 private:
  std::filesystem::path dir_, path_;
  Params root_ = Params::parse("", "");
};

}  // namespace pastemix::lab
