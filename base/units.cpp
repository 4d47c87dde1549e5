// SPDX-License-Identifier: MIT
#include "base/units.h"

#include <array>
#include <utility>

namespace pastemix {

namespace {
struct UnitRow {
  std::string_view name;
  double factor;
  std::string_view si;
};
constexpr std::array<UnitRow, 27> kUnits{{
    {"m", 1.0, "m"},         {"cm", 1e-2, "m"},        {"mm", 1e-3, "m"},          {"um", 1e-6, "m"},
    {"kg", 1.0, "kg"},       {"g", 1e-3, "kg"},        {"s", 1.0, "s"},            {"ms", 1e-3, "s"},
    {"Pa", 1.0, "Pa"},       {"kPa", 1e3, "Pa"},       {"MPa", 1e6, "Pa"},         {"GPa", 1e9, "Pa"},
    {"kg/m3", 1.0, "kg/m3"}, {"g/cm3", 1e3, "kg/m3"},  {"Pa.s", 1.0, "Pa.s"},      {"mPa.s", 1e-3, "Pa.s"},
    {"m/s", 1.0, "m/s"},     {"mm/s", 1e-3, "m/s"},    {"cm/s", 1e-2, "m/s"},      {"m/s2", 1.0, "m/s2"},
    {"deg", 1.0, "deg"},     {"%", 1e-2, "-"},         {"percent", 1e-2, "-"},     {"-", 1.0, "-"},
    {"1", 1.0, "-"},         {"N", 1.0, "N"},          {"J", 1.0, "J"},
}};
}  // namespace

std::optional<double> si_factor(std::string_view unit) {
  for (const auto& row : kUnits)
    if (row.name == unit) return row.factor;
  return std::nullopt;
}

std::string si_unit(std::string_view unit) {
  for (const auto& row : kUnits)
    if (row.name == unit) return std::string(row.si);
  return {};
}

}  // namespace pastemix
