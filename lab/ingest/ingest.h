// SPDX-License-Identifier: MIT
// What every ingester shares: its result type, the units of its columns, and the check of printed values.
//
// An ingester reads one CSV whose columns keep the units printed in the source (mm, cm, g, %). The SI factor
// of each column comes from the manifest ([<step>.units], checked through base/units.h) or, for a single-file
// CLI call, from the ingester's own defaults (the units in the column names). Either way a unit of the wrong
// dimension (kg for a length) is an error, never a silent factor.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "base/csv.h"
#include "base/params.h"
#include "lab/parameter.h"

namespace pastemix::lab {

struct IngestResult {
  std::vector<Parameter> parameters;
  std::vector<Warning> warnings;
};

struct ColumnSpec {
  std::string name;          // CSV column
  std::string default_unit;  // unit the column name states ("mm" for slump_mm); "" for ids and text
  bool required = true;      // optional columns hold printed values we only compare with
};

class ColumnUnits {
 public:
  // The defaults of `specs` (single-file CLI use).
  static ColumnUnits defaults(const std::vector<ColumnSpec>& specs);
  // A manifest [x.units] table: every column of `specs` must have a known unit of the same SI dimension as
  // its default; a column not in `specs` is an unknown key (Params::finish reports it with its line).
  static ColumnUnits from_manifest(const std::vector<ColumnSpec>& specs, const Params& units);

  double factor(std::string_view column) const;       // multiply a cell by this to get SI
  const std::string& unit(std::string_view column) const;  // the unit as written

 private:
  struct Entry {
    std::string unit;
    double factor = 1.0;
  };
  std::map<std::string, Entry, std::less<>> entries_;
};

// Checks that every required column is present and no unknown column is; line 1 errors name the column.
void require_spec_columns(const CsvTable& table, const std::vector<ColumnSpec>& specs);

// Half a unit of the last printed digit of `cell` ("0.612" -> 0.0005, "136" -> 0.5): how far a printed value
// may lie from the exact one through rounding alone.
double rounding_tolerance(std::string_view cell);

// "file:line" for warnings.
std::string where(const CsvTable& table, const CsvTable::Row& row);

// Fixed-point text with four significant digits ("138.0", "0.6120", "1843").
std::string format_value(double value);

}  // namespace pastemix::lab
