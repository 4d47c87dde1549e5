// SPDX-License-Identifier: MIT
// The rheology of the pastes nobody measured (70 and 72.5 % solids by mass): a one-parameter model anchored
// at the measured 75 % paste (issue 15; ../shared/DESIGN.md sections 4 and 6; docs/rheology_protocol.md).
//
// Only the 75 % paste was measured: tau_y by slump (paste.yield_stress), the density with the slump tests
// (paste.density, 1843 kg/m3), and eta_B by the thesis's steel-ball calibration (0.7 Pa.s, Table 4.4), which
// belongs to the drag curve it was calibrated with (published_4_19, validation/fluid/VALIDATION.md section 4).
// Every family below returns exactly those values at the anchor and has ONE free shape parameter.
//
// Solids volume fraction (of the solids + water, air excluded), from the solids content by mass C_w:
//   phi(C_w) = (C_w / rho_s) / (C_w / rho_s + (1 - C_w) / rho_w),  rho_s = 2710 kg/m3 (tailings, Table 3.2's
//   rho_s), rho_w = 1000 kg/m3.  75 % -> 0.5254, 72.5 % -> 0.4931, 70 % -> 0.4627.
// Density: the mixture rule rho_mix = 1 / (C_w / rho_s + (1 - C_w) / rho_w) gives 1898.4 kg/m3 at 75 %, the
//   slump file says 1843: a gap of 2.9 %, read as entrained air (a = 1 - 1843/1898.4 = 2.92 %) held constant:
//   rho(C_w) = rho_75 rho_mix(C_w) / rho_mix(0.75). The gap is reported (air_content, mixture_density_at_anchor).
// Yield stress, family "exponential": tau_y = tau_75 exp(b (C_w - 75)), C_w in wt %, b per wt %.
// Yield stress, family "packing" (YODEL, Flatt & Bowen 2006, J. Am. Ceram. Soc. 89:1244:
//   tau_y ~ phi (phi - phi_0)^2 / (phi_m (phi_m - phi))), with the percolation threshold phi_0 taken as 0 so
//   that the maximum packing fraction phi_m is the one shape parameter: tau_y = tau_75 G(phi) / G(phi_75),
//   G = phi^3 / (phi_m - phi). (phi_0 of flocculated fines lies well below 0.46; its effect on the 70-75 %
//   ratio is absorbed by phi_m.)
// Plastic viscosity, both families: Krieger & Dougherty (1959, Trans. Soc. Rheol. 3:137),
//   eta_B = eta_75 [(1 - phi/phi_m) / (1 - phi_75/phi_m)]^(-[eta] phi_m), [eta] = 2.5 (Einstein's value for
//   spheres), tied to the same phi. The packing family uses its own phi_m; the exponential family has none,
//   so it uses its packing equivalent: the phi_m whose packing-family tau_y ratio between 72.5 and 75 % equals
//   exp(2.5 b) (closed form, equivalent_packing_fraction()).
// Priors: published fits for tailings pastes near 65-78 % solids give tau_y rising by a factor of 2-4.5 per
//   2.5 points of solids (../shared/DESIGN.md section 6, issue 15): b in [ln 2, ln 4.5] / 2.5 = [0.277, 0.602] per wt %,
//   and for the packing family the phi_m range that gives the same factors between 72.5 and 75 %
//   ([0.537, 0.575] with the anchor above). The prior value is the middle of the range, its sd the range /
//   sqrt(12) (uniform).
// What a calibrated value means: calibrated on a mixing case with the paste at rest (../shared/DESIGN.md section 6),
//   the rheology is "at-rest effective": it also absorbs the drag curve's behaviour at Re' 10-20 and the
//   missing paste flow. The store and the docs keep that label (kAtRestLabel).
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lab/parameter.h"

namespace pastemix::lab::rheology {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kIntrinsicViscosity = 2.5;  // [eta] of Krieger-Dougherty, spheres (Einstein)
inline constexpr double kFactorLow = 2.0, kFactorHigh = 4.5;  // tau_y(75)/tau_y(72.5), published range
inline constexpr const char* kPriorSource =
    "published fits for tailings pastes near 65-78 % solids: tau_y rises by a factor of 2-4.5 per 2.5 points "
    "of solids (DESIGN.md section 6, issue 15)";
inline constexpr const char* kAtRestLabel =
    "at-rest effective: calibrated with the paste at rest, it also absorbs the drag curve's behaviour at "
    "Re' 10-20 and the missing paste flow; recalibrate when the moving paste is on";

enum class Family { exponential, packing };
const char* to_string(Family f);
// nullopt when unknown.
std::optional<Family> find_family(std::string_view name);
inline const std::vector<std::string>& family_names() {
  static const std::vector<std::string> names{"exponential", "packing"};
  return names;
}

// The measured 75 % paste (all SI; solids contents as mass fractions 0..1).
struct Anchor {
  double solids_fraction = 0.75;       // C_w of the measured paste, -
  double yield_stress = kNaN;          // Pa (slump)
  double yield_stress_sd = kNaN;       // Pa, over the slump trials
  double plastic_viscosity = kNaN;     // Pa.s (steel-ball calibration)
  double plastic_viscosity_sd = kNaN;  // Pa.s; NaN: not known (the thesis gives none)
  std::string curve;                   // the drag curve eta_B was calibrated with
  double density = kNaN;               // kg/m3, measured
  double solids_density = 2710.0;      // kg/m3, tailings particles
  double water_density = 1000.0;       // kg/m3
};

struct Prior {
  double lo = 0.0, hi = 0.0;
  std::string name, unit;  // "b", "1/wt%" or "phi_m", "-"
  double mid() const { return 0.5 * (lo + hi); }
  double sd() const;        // (hi - lo) / sqrt(12)
};

struct Model {
  Family family = Family::exponential;
  Anchor anchor;
  double shape = kNaN;     // b (1/wt%) or phi_m (-)
  double shape_sd = kNaN;  // its standard deviation
};

// Physics of the mixture (anchor gives the densities).
double solids_volume_fraction(const Anchor& a, double solids_fraction);
double mixture_density(const Anchor& a, double solids_fraction);  // kg/m3, no air
double air_content(const Anchor& a);                               // 1 - rho_75 / rho_mix(0.75)
double density(const Anchor& a, double solids_fraction);           // kg/m3, with the anchor's air content

// The prior range of a family's shape parameter (the packing range depends on the anchor's densities).
Prior prior(Family f, const Anchor& a);
// Throws InputError(where, 0, "<family>.<name>", ...) when the shape is not finite or outside the prior,
// naming the parameter, its value and the range.
void check_shape(Family f, const Anchor& a, double shape, const std::string& where);
// Throws InputError naming the field when the anchor is incomplete or unphysical.
void check_anchor(const Anchor& a, const std::string& where);

// The Krieger-Dougherty maximum packing fraction a model's eta_B uses.
double packing_fraction(const Model& m);
// The packing-family phi_m whose tau_y ratio between 72.5 and 75 % is `factor` (> the phi^3 ratio alone).
double equivalent_packing_fraction(const Anchor& a, double factor);

double yield_stress(const Model& m, double solids_fraction);       // Pa
double plastic_viscosity(const Model& m, double solids_fraction);  // Pa.s

// One solids content: values with standard deviations (the anchor's and the shape parameter's, combined).
struct Point {
  double solids_fraction = 0.0, phi = 0.0;
  double yield_stress = 0.0, yield_stress_sd = kNaN;            // Pa
  double plastic_viscosity = 0.0, plastic_viscosity_sd = kNaN;  // Pa.s
  double density = 0.0;                                         // kg/m3
};
Point evaluate(const Model& m, double solids_fraction);

// What the store records about where the shape parameter came from.
struct ShapeSource {
  bool calibrated = false;  // false: the prior
  int case_id = 0;          // calibrated on this mixing case
  std::string record;       // the calibration record (file) or "" for the prior
  std::string detail;       // one line: how (objective, seeds, command)
};

// The store's parameters for the model (keys paste_rheology.model.*) and for each solids content in
// `solids_fractions` (keys paste_rheology.cw_<percent with '_' for '.'>.*, e.g. cw_72_5), with the cases
// using each one (`cases[k]` for solids_fractions[k], as text "2, 4, 5"). Values at the anchor's solids
// content are the anchor's own (measured / calibrated with the steel balls).
std::vector<Parameter> store_parameters(const Model& m, const ShapeSource& source,
                                        const std::vector<double>& solids_fractions,
                                        const std::vector<std::string>& cases, const std::string& anchor_source);
// "cw_72_5" for 0.725 (the key of a solids content in the store).
std::string solids_key(double solids_fraction);

// Reads the model back from a parameters.toml written by `lab reduce` (paste_rheology.model.*). InputError
// naming the file and key when missing (run `pastemix lab reduce`) or malformed.
Model read_model(const std::string& parameters_toml);

// A calibration record (written by `pastemix calibrate rheology`, read by `lab reduce --rheology-calibration`).
struct Calibration {
  Family family = Family::exponential;
  double shape = kNaN, sd = kNaN;
  int case_id = 0;
  std::string detail;
};
Calibration read_calibration(const std::string& path);
std::string calibration_toml(const Calibration& c, const std::string& command, const std::string& created);

}  // namespace pastemix::lab::rheology
