// SPDX-License-Identifier: MIT
#include "lab/ingest/ingest.h"

#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "base/error.h"
#include "base/stats.h"
#include "base/suggest.h"
#include "base/units.h"

namespace pastemix::lab {

ColumnUnits ColumnUnits::defaults(const std::vector<ColumnSpec>& specs) {
  ColumnUnits u;
  for (const auto& s : specs)
    if (!s.default_unit.empty()) u.entries_[s.name] = Entry{s.default_unit, si_factor(s.default_unit).value()};
  return u;
}

ColumnUnits ColumnUnits::from_manifest(const std::vector<ColumnSpec>& specs, const Params& units) {
  ColumnUnits u;
  for (const auto& s : specs) {
    if (s.default_unit.empty()) continue;  // ids and text carry no unit
    if (!units.has(s.name))
      units.fail(s.name, fmt::format("no unit given for column '{}' (expected a unit of {}, e.g. \"{}\")", s.name,
                                     si_unit(s.default_unit), s.default_unit));
    const std::string unit = units.string(s.name);
    auto factor = si_factor(unit);
    if (!factor)
      units.fail(s.name, fmt::format("unknown unit '{}' (expected a unit of {}, e.g. \"{}\")", unit,
                                     si_unit(s.default_unit), s.default_unit));
    if (si_unit(unit) != si_unit(s.default_unit))
      units.fail(s.name, fmt::format("unit '{}' converts to {}, but column '{}' needs a unit of {}", unit,
                                     si_unit(unit), s.name, si_unit(s.default_unit)));
    u.entries_[s.name] = Entry{unit, *factor};
  }
  return u;
}

double ColumnUnits::factor(std::string_view column) const {
  auto it = entries_.find(column);
  if (it == entries_.end()) throw std::logic_error(fmt::format("no unit registered for column '{}'", column));
  return it->second.factor;
}

const std::string& ColumnUnits::unit(std::string_view column) const {
  auto it = entries_.find(column);
  if (it == entries_.end()) throw std::logic_error(fmt::format("no unit registered for column '{}'", column));
  return it->second.unit;
}

void require_spec_columns(const CsvTable& table, const std::vector<ColumnSpec>& specs) {
  std::vector<std::string> required, known;
  for (const auto& s : specs) {
    known.push_back(s.name);
    if (s.required) required.push_back(s.name);
  }
  table.require_columns(required);
  table.require_only_columns(known);
}

void require_unique_ids(const CsvTable& table, std::string_view column) {
  std::map<long, int> first_line;
  for (const auto& row : table.rows()) {
    const long id = table.integer(row, column);
    auto [it, fresh] = first_line.emplace(id, row.line);
    if (!fresh)
      table.fail(row, column, fmt::format("{} {} is listed twice (first on line {}): each trial counts once", column,
                                          id, it->second));
  }
}

void check_plausible(const CsvTable& table, const CsvTable::Row& row, std::string_view column, double value_si,
                     const Plausible& bounds, const ColumnUnits& units) {
  if (!units.plausibility_checks() || (value_si >= bounds.lo && value_si <= bounds.hi)) return;
  table.fail(row, column,
             fmt::format("{} = {:g} is not plausible as {} (expected {:g} to {:g}); check the unit of the column "
                         "(the manifest's [.units]). If the value is right, set allow_implausible_values = true in "
                         "this input's manifest table",
                         shown(table.text(row, column)), value_si, bounds.what, bounds.lo, bounds.hi));
}

double rounding_tolerance(std::string_view cell) {
  // "1.08e-7": the last printed digit of the mantissa, scaled by the exponent.
  int exponent = 0;
  if (auto e = cell.find_first_of("eE"); e != std::string_view::npos) {
    exponent = std::atoi(std::string(cell.substr(e + 1)).c_str());
    cell = cell.substr(0, e);
  }
  const auto dot = cell.find('.');
  const int decimals = dot == std::string_view::npos ? 0 : static_cast<int>(cell.size() - dot - 1);
  // A hair above half a unit so that values that round either way at exactly .5 do not warn.
  return 0.5 * std::pow(10.0, static_cast<double>(exponent - decimals)) * (1.0 + 1e-6);
}

std::string where(const CsvTable& table, const CsvTable::Row& row) {
  return fmt::format("{}:{}", table.path(), row.line);
}

std::string format_value(double value) {
  if (!std::isfinite(value)) return "nan";
  if (value == 0.0) return "0";
  const int magnitude = static_cast<int>(std::floor(std::log10(std::abs(value))));
  const int decimals = std::max(0, 3 - magnitude);
  return fmt::format("{:.{}f}", value, decimals);
}

Parameter summary_parameter(const std::string& key, const std::vector<double>& values, const std::string& unit,
                            const std::string& method, const std::string& source) {
  const Summary s = summarize(values);
  Parameter p;
  p.key = key;
  p.value = s.mean;
  p.sd = s.sd;
  p.n = s.n;
  p.unit = unit;
  p.method = method;
  p.provenance = Provenance::measured;
  p.source = source;
  return p;
}

}  // namespace pastemix::lab
