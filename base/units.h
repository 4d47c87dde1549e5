// SPDX-License-Identifier: MIT
// Unit conversion to SI for the units the lab files and manifests use.
//
// The datasets keep the printed units (mm, cm, g, GPa, %); everything inside pastemix is SI (m, kg, s, Pa).
// A unit string we do not know is an error, never a silent factor of 1.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace pastemix {

// Factor to multiply a value in `unit` by to get SI; nullopt if the unit is unknown.
// Known: m, cm, mm, um; kg, g; s, ms; Pa, kPa, MPa, GPa; kg/m3, g/cm3; Pa.s, mPa.s; m/s, mm/s, cm/s;
// m/s2; deg (kept in degrees: factor 1); %, percent (-> fraction 0.01); -, 1 (dimensionless).
std::optional<double> si_factor(std::string_view unit);
// The SI unit a known unit converts to ("mm" -> "m"); empty if unknown.
std::string si_unit(std::string_view unit);

namespace units {
inline constexpr double g = 9.81;  // m/s2: the value the thesis uses in (4.17), Table 4.3 and Pashias-Boger
inline constexpr double pi = 3.14159265358979323846;
}  // namespace units

}  // namespace pastemix
