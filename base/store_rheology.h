// SPDX-License-Identifier: MIT
// Reading the paste rheology of a lab store (`pastemix lab reduce`, lab/rheology/paste_rheology.h) at one
// solids content: paste_rheology.cw_<...>.{yield_stress, plastic_viscosity, density}, matched by
// solids_fraction (1e-9). One reader for both users: the engine's fluid regions (model/fluid/fluid_scene.h,
// `rheology_from`) and the flow solver's paste (model/flow/bingham.h). It lives in base because the flow
// solver links base only.
#pragma once

#include <string>

namespace pastemix {

struct StoreRheology {
  std::string key;                 // paste_rheology.cw_72_5
  double yield_stress = 0.0;       // Pa
  double plastic_viscosity = 0.0;  // Pa.s
  double density = 0.0;            // kg/m3
  std::string curve;       // the drag curve eta_B belongs to (paste_rheology.model.curve); "" when not asked
  std::string provenance;  // yield_stress.method: "model exponential, shape parameter calibrated on case 2"
};

// What a caller needs besides the three values. The engine's drag needs the curve eta_B was fitted with and
// reports the provenance, so for it both keys are required; the flow solver uses the values only and reads
// stores (its tests' among them) that may lack them.
enum class StoreKeys { values, values_curve_provenance };

// `at`: "value", or "minus_sd" / "plus_sd" (tau_y and eta_B with the shape parameter at -1 / +1 sd: the band).
// InputError naming the file and key when the store has no paste_rheology table, not that solids content, or
// (StoreKeys::values_curve_provenance) no model.curve or yield_stress.method.
StoreRheology read_store_rheology(const std::string& parameters_toml, double solids_fraction,
                                  const std::string& at = "value",
                                  StoreKeys keys = StoreKeys::values_curve_provenance);

}  // namespace pastemix
