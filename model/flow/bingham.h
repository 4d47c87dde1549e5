// SPDX-License-Identifier: MIT
// The paste's yield-stress laws for the flow solver (issue 17, part 2), and what "at rest" means for them.
//
// Bingham, regularised after Papanastasiou (1987, J. Rheol. 31:385), as DESIGN.md section 6 states:
//   eta(gamma_dot) = eta_B + tau_y (1 - exp(-m gamma_dot)) / gamma_dot          (Pa s)
// m (s) is the regularisation: the exact Bingham law is the limit m -> infinity. At gamma_dot = 0 the
// viscosity is finite, eta_B + tau_y m (the plug's viscosity). A stress below tau_y does not stop the flow:
// it creeps at gamma_dot ~ -ln(1 - tau/tau_y) / m, so every creep speed halves when m doubles (tested).
// Herschel-Bulkley, regularised the same way:
//   eta(gamma_dot) = K max(gamma_dot, 1/m)^(n - 1) + tau_y (1 - exp(-m gamma_dot)) / gamma_dot
// (the power-law part is evaluated at no less than 1/m so that a shear-thinning n < 1 stays finite in the
// plug; above gamma_dot = 1/m it is the exact K gamma_dot^n). n = 1 with K = eta_B is the Bingham law.
//
// At rest: a regularised fluid never stops (Frigaard & Nouar 2005), so rest is a stated speed. The paste is
// at rest when its alpha-weighted RMS speed, sqrt(sum alpha |u|^2 / sum alpha) over the cells (cell-centre
// velocities), is below kRestSpeed. The paste's own motion, not the air's: the largest speed over cells with
// alpha >= 1/2 (paste_speed, kept for the cliff's movement bound) is set at the interface, where a cell's face
// means carry the air's motion (the 10 mm slump: air at 0.29 m/s at 4 s, the interface cells' max 1.3e-3 m/s
// and rising while the paste's RMS speed fell). 1e-3 m/s: a 5 mm cell in 5 s, far below the 0.01 m/s the pours'
// stop rule uses for rock in the paste (model/stop_rule.h paste_speed), and above the creep of a standing
// paste at m >= 1000 s (a body of size L creeps at ~L / m: 1e-4 m/s for 0.1 m at m = 1000 s; at m = 100 s it
// would reach 1e-3).
//
// The store: the same values the engine's scenes read (`rheology_from` + `solids_fraction`,
// model/fluid/fluid_scene.h): paste_rheology.cw_<...>.{yield_stress, plastic_viscosity, density} of the
// parameters.toml that `pastemix lab reduce` writes. (Read here with the same keys: the flow library links
// base only, not the engine.)
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "base/params.h"
#include "model/flow/rheology.h"

namespace pastemix::flow {

inline constexpr double kRestSpeed = 1e-3;  // m/s, see above

class Bingham final : public Rheology {
 public:
  // tau_y >= 0 (Pa), eta_B > 0 (Pa s), m > 0 (s); std::invalid_argument otherwise.
  Bingham(double tau_y, double eta_B, double m);
  double viscosity(double gamma_dot) const override;
  bool shear_dependent() const override { return true; }
  std::string describe() const override;
  double yield_stress() const { return tau_y_; }
  double plastic_viscosity() const { return eta_B_; }
  double regularisation() const { return m_; }

 private:
  double tau_y_, eta_B_, m_;
};

class HerschelBulkley final : public Rheology {
 public:
  // tau_y >= 0 (Pa), K > 0 (Pa s^n), n > 0 (-), m > 0 (s).
  HerschelBulkley(double tau_y, double K, double n, double m);
  double viscosity(double gamma_dot) const override;
  bool shear_dependent() const override { return true; }
  std::string describe() const override;

 private:
  double tau_y_, K_, n_, m_;
};

// tau_y (1 - exp(-m g)) / g, with its limit tau_y m at g -> 0 (series below m g = 1e-8, where the quotient
// loses its digits).
double papanastasiou_term(double tau_y, double m, double gamma_dot);

// The [flow.paste] table's law (keys documented in flow_config.h). `density` is set from the store when the
// table reads `rheology_from`, else from its `density` key. Errors name the file, line and key.
std::shared_ptr<const Rheology> read_paste_law(const Params& paste, double& density);

// The paste rheology of a store at one solids content (the engine's `rheology_from` keys).
struct StorePaste {
  std::string key;  // paste_rheology.cw_75
  double yield_stress = 0.0, plastic_viscosity = 0.0, density = 0.0;  // Pa, Pa s, kg/m3
};
// InputError naming the file and key when the store has no paste_rheology table or not that solids content.
StorePaste read_store_paste(const std::string& parameters_toml, double solids_fraction);

class FlowSolver;
// Max over cells with alpha >= 1/2 of the cell-centre speed (m/s): bounds how fast any paste moves.
double paste_speed(const FlowSolver& s);
// sqrt(sum alpha |u_c|^2 / sum alpha) over the cells (m/s): the speed "at rest" is judged by; 0 without paste.
double paste_rms_speed(const FlowSolver& s);
inline bool at_rest(const FlowSolver& s, double rest_speed = kRestSpeed) { return paste_rms_speed(s) < rest_speed; }

}  // namespace pastemix::flow
