// SPDX-License-Identifier: MIT
// [[fluid]] tables of a scene -> FluidRegion (all values SI). Several regions are allowed; a particle belongs
// to the first region (in file order) that holds it.
//
//   [[fluid]]
//   name = "paste"                       # optional
//   x = [-0.1, 0.1]   y = [-0.0825, 0.0825]   # m, horizontal extent of the box
//   bottom = 0.0                         # m, bottom of the fluid
//   surface = 0.15                       # m, free surface without rock (it rises as rock enters)
//   density = 1843                       # kg/m3
//   rheology = "bingham"                 # the drag law, by name (laws/registry.h, DragLaws); its own keys
//   yield_stress = 138                   # follow (laws/<law>.h, from_params), e.g. for "bingham": Pa
//   plastic_viscosity = 0.7              # Pa.s ("newtonian": viscosity = 1e-3 Pa.s, curve default "stokes")
//   curve = "power_blend"  coefficients = [k, a, b, c, n]    # or curve = "published_4_19" / "stokes", or
//   curve_from = "parameters.toml"       # lab reduce output (relative to the scene file): drag_curve.chosen
//   solids_fraction = 0.75               # -, optional (0), recorded for the analysis maps
//   rheology_from = "../../out/lab/parameters.toml"   # instead of density, yield_stress, plastic_viscosity:
//                                        # the store's paste_rheology.cw_<C_w> values for this solids_fraction
//                                        # (required then), written by `pastemix lab reduce`; `curve` must be
//                                        # the store's paste_rheology.model.curve (the curve eta_B belongs to)
//   rheology_at = "value"                # or "minus_sd" / "plus_sd": the store's band (shape parameter -/+ 1 sd)
//   buoyancy = true  yield_term = true  partial_submergence = true  surface_rise = true   # switches
//   collective = "bearing_capacity"      # or "none" (default): touching spheres share the paste's bearing
//                                        # capacity (collective.h); needs yield_stress > 0
//   collective_interval = 5e-4           # s, optional: simulated time between two cluster updates
//   dynamics = "at_rest"                 # default: the paste at rest (this file's model); or "flow": the
//                                        # region's paste solved by the flow solver, coupled both ways (issue
//                                        # 18), with its keys:
//   cell = 0.005                         #   m, the flow grid's cubic cells, tiling the region; or
//   cells = [20, 16, 15]                 #   the cells along x, y, z from the bottom to `top` (one of the two
//                                        #   required), sides within 1.2 of each other (a 16.5 cm side in ~1 cm)
//   top = 0.2                            #   m, top of the flow box (air above the surface), default the domain's
//   kernel_width = 2.0                   #   c of the particles' kernels (model/coupling/kernel.h), >= 1.2091
//   coupling_interval = 1                #   DEM steps per coupling cycle (fluid/flow_coupling.h), >= 1
//   regularisation = 1000.0              #   s, Papanastasiou's m (model/flow/bingham.h), required with a
//                                        #   yield stress (its effect is part of every result)
//   flow_time_step = 1e-3                #   s, optional: the flow's largest sub-step inside a coupling cycle
//                                        #   (default the solver's 1e-2 s; the CFL bound applies as well)
//   implicit_stick = false               #   optional: a yield-held particle moves with the paste during the
//                                        #   flow interval (model/coupling/coupled_flow.h)
//                                        # A flow region is the scene's only [[fluid]] region, without the
//                                        # collective rule (the paste's own stress carries a pile).
//   [fluid.flow]                         # or: the flow keys above in this sub-table of the region (not both).
//                                        # A region at rest may carry it: the frozen numerics of its flow
//                                        # variant, checked as for "flow" but unused until
//                                        # --set fluid.N.dynamics=flow (the shipped mixing
//                                        # scenes use datasets/scenes/mixing_flow.overrides.toml)
//
// Checks: positive density and viscosities, non-negative yield stress, extents min < max, surface above the
// bottom, a known curve with admissible coefficients (exactly one of curve / curve_from); with dynamics =
// "flow": a grid (cell or cells), a top inside the domain and above the surface, cells that tile the region, a kernel
// width at or above its minimum, coupling_interval >= 1, regularisation with (only with) a yield stress, no
// collective rule, no second region.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/params.h"
#include "base/store_rheology.h"
#include "model/fluid/field.h"

namespace pastemix::model::fluid {

// Every region must lie inside the domain box [domain_min, domain_max] (m): InputError at its key otherwise.
std::vector<FluidRegion> read_fluid_regions(const Params& root, const std::string& scene_path, const Vec3& domain_min,
                                            const Vec3& domain_max);

// The drag curve chosen by `lab reduce` in a parameters.toml: [drag_curve.chosen] text = NAME and
// [drag_curve.NAME.<coefficient>] value = ... (InputError naming the file on anything missing).
// With `name` given, that curve's coefficients instead of the chosen one (a fixed curve needs none).
drag::DragCurve read_chosen_curve(const std::string& parameters_toml, const std::string& name = "");

// The paste (and steel-ball) values of a lab parameters.toml (`pastemix lab reduce`), for the steel-ball
// validations and the viscosity calibration. Required: paste.yield_stress, paste.density and the chosen drag
// curve (or `curve_name`'s coefficients); optional (absent -> nullopt): paste.plastic_viscosity (the lab
// reduction does not produce it: it is the calibrated quantity), steel_ball.restitution,
// steel_ball.static_friction, steel_ball.density. InputError naming the file and key on anything malformed.
struct LabPaste {
  double tau_y = 0.0;        // Pa
  double density = 0.0;      // kg/m3
  drag::DragCurve curve;
  std::optional<double> eta_B, ball_restitution, ball_friction, ball_density;
};
LabPaste read_lab_paste(const std::string& parameters_toml, const std::string& curve_name = "");

// The paste rheology of a lab store at one solids content, with the drag curve eta_B belongs to and its
// provenance (base/store_rheology.h: the one reader, shared with the flow solver).
using pastemix::read_store_rheology;
using pastemix::StoreRheology;

}  // namespace pastemix::model::fluid
