// SPDX-License-Identifier: MIT
// The paste of the steel-ball commands (`validate steel-balls`, `validate ball-pour`, `calibrate viscosity`):
// read from the lab parameter store (`--params`, default out/lab/parameters.toml, written by `pastemix lab
// reduce`), each value overridable on the command line. Every value carries where it came from, printed in
// the command's header.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "base/drag_curves.h"
#include "validation/fluid/validations.h"

namespace pastemix::app {

inline constexpr const char* kDefaultParams = "out/lab/parameters.toml";
// eta_B when neither --eta nor paste.plastic_viscosity in the store gives it: the thesis's steel-ball
// calibration (Table 4.4, 12.6 mm ball at 255 mm). `lab reduce` does not produce it: it is calibrated.
inline constexpr double kThesisEtaB = 0.7;

struct PasteOpts {
  std::string params = kDefaultParams;
  std::string curve;                 // empty: the store's drag_curve.chosen
  double tau_y = -1, rho = -1, eta = -1;  // < 0: not given
};

struct Paste {
  double tau_y = 0, rho = 0, eta = 0;
  drag::DragCurve curve;
  std::string tau_from, rho_from, eta_from, curve_from;
  double ball_restitution = 0.612, ball_friction = 0.341;  // steel-steel, Tables 4.6, 4.7 (thesis means)
  std::string ball_from = "thesis Tables 4.6/4.7 means";
};

void add_paste_options(CLI::App* cmd, PasteOpts& o, bool with_eta = true);
// The moving paste's options of a validation (--interval, --regularisation: dynamics = "flow"'s coupling interval
// in DEM steps and Papanastasiou's m in s), both positive.
void add_flow_options(CLI::App* cmd, long& coupling_interval, double& regularisation);
// Throws InputError (exit 2) naming the path when the store is missing and a value is not given explicitly.
Paste resolve_paste(const PasteOpts& o, bool need_eta = true);
void print_paste(const Paste& p);
validation::SteelBallPaste steel_ball_paste(const Paste& p);

// `pastemix validate ball-pour` (app/cmd_fluid_pour.cpp), registered on `validate`.
void register_pour(CLI::App* validate);

}  // namespace pastemix::app
