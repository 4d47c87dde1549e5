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
  // On by default; a manifest turns it off for one input with `allow_implausible_values = true`.
  bool plausibility_checks() const { return plausibility_checks_; }
  void set_plausibility_checks(bool on) { plausibility_checks_ = on; }

 private:
  bool plausibility_checks_ = true;
  struct Entry {
    std::string unit;
    double factor = 1.0;
  };
  std::map<std::string, Entry, std::less<>> entries_;
};

// Checks that every required column is present and no unknown column is; line 1 errors name the column.
void require_spec_columns(const CsvTable& table, const std::vector<ColumnSpec>& specs);

// Every value of an id column (a trial or test number) must be unique: a duplicated row would count one
// trial twice. The error names both lines.
void require_unique_ids(const CsvTable& table, std::string_view column);

// Bounds of what a lab measures, in SI. Outside them the value is almost surely a unit mistake (a density
// in g/cm3 read as kg/m3 gives 1.8 kg/m3; in kg/m3 read as g/cm3, 1.8e6).
struct Plausible {
  double lo, hi;
  const char* what;  // "density", with the unit, for the message
};
inline constexpr Plausible plausible_density{100.0, 20000.0, "a density (kg/m3)"};
inline constexpr Plausible plausible_paste_yield_stress{0.0, 10000.0, "a paste's yield stress (Pa)"};
// InputError at the row (naming the value, the bounds and the manifest switch) if `value_si` is outside.
// (Not `si_value`: <signal.h> defines that name as a macro.)
void check_plausible(const CsvTable& table, const CsvTable::Row& row, std::string_view column, double value_si,
                     const Plausible& bounds, const ColumnUnits& units);

// Half a unit of the last printed digit of `cell` ("0.612" -> 0.0005, "136" -> 0.5): how far a printed value
// may lie from the exact one through rounding alone.
double rounding_tolerance(std::string_view cell);

// A measured parameter that summarises repeated values (base/stats.h summarize: mean, sample sd, count),
// with its SI unit, how it was obtained and the input file; the caller adds the trials where it keeps them.
Parameter summary_parameter(const std::string& key, const std::vector<double>& values, const std::string& unit,
                            const std::string& method, const std::string& source);

// "file:line" for warnings.
std::string where(const CsvTable& table, const CsvTable::Row& row);

// Fixed-point text with four significant digits ("138.0", "0.6120", "1843").
std::string format_value(double value);

}  // namespace pastemix::lab
