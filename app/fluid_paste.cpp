// SPDX-License-Identifier: MIT
#include "app/fluid_paste.h"

#include <filesystem>

#include <fmt/format.h>

#include "base/error.h"
#include "model/fluid/fluid_scene.h"

namespace pastemix::app {

void add_flow_options(CLI::App* cmd, long& coupling_interval, double& regularisation) {
  cmd->add_option("--interval", coupling_interval, "with --flow: DEM steps per flow interval (default 50)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--regularisation", regularisation, "with --flow: Papanastasiou's m, s (default 1000)")
      ->check(CLI::PositiveNumber);
}

void add_paste_options(CLI::App* cmd, PasteOpts& o, bool with_eta) {
  cmd->add_option("--params", o.params,
                  fmt::format("lab parameter store (pastemix lab reduce), default {}", kDefaultParams));
  cmd->add_option("--tau-y,--tau", o.tau_y, "paste yield stress (Pa), overrides paste.yield_stress");
  cmd->add_option("--rho-paste", o.rho, "paste density (kg/m3), overrides paste.density");
  if (with_eta)
    cmd->add_option("--eta", o.eta,
                    fmt::format("plastic viscosity (Pa.s); default paste.plastic_viscosity of the store, else {} "
                                "(thesis calibration, Table 4.4)",
                                kThesisEtaB));
  cmd->add_option("--curve", o.curve, "drag curve name (default: the store's drag_curve.chosen)");
}

Paste resolve_paste(const PasteOpts& o, bool need_eta) {
  Paste p;
  const bool have_file = std::filesystem::exists(o.params);
  std::optional<drag::CurveId> fixed;
  if (!o.curve.empty()) {
    fixed = drag::find_curve(o.curve);
    if (!fixed) throw InputError("--curve", 0, "curve", fmt::format("unknown drag curve '{}'", o.curve));
  }
  const bool explicit_all = o.tau_y > 0 && o.rho > 0 && fixed && drag::curve_info(*fixed).n_coefficients == 0;
  if (!have_file && !explicit_all)
    throw InputError(o.params, 0, "--params",
                     "no such parameter file: run `pastemix lab reduce datasets/thesis --out out/lab` first, or pass "
                     "--params FILE, or give --tau-y, --rho-paste and --curve (published_4_19 or stokes) explicitly");
  model::fluid::LabPaste lab;
  if (have_file) lab = model::fluid::read_lab_paste(o.params, o.curve);
  auto pick = [&](double given, double stored, const char* key, std::string* from) {
    if (given > 0) {
      *from = "command line";
      return given;
    }
    *from = fmt::format("{} {}", o.params, key);
    return stored;
  };
  p.tau_y = pick(o.tau_y, lab.tau_y, "paste.yield_stress", &p.tau_from);
  p.rho = pick(o.rho, lab.density, "paste.density", &p.rho_from);
  if (have_file) {
    p.curve = lab.curve;
    p.curve_from = o.curve.empty()                 ? fmt::format("{} drag_curve.chosen", o.params)
                   : p.curve.coefficients.empty() ? std::string("--curve")
                                                  : fmt::format("--curve, coefficients from {}", o.params);
  } else {
    p.curve = {*fixed, {}};
    p.curve_from = "--curve";
  }
  if (o.eta > 0) {
    p.eta = o.eta, p.eta_from = "command line";
  } else if (lab.eta_B) {
    p.eta = *lab.eta_B, p.eta_from = fmt::format("{} paste.plastic_viscosity", o.params);
  } else {
    p.eta = kThesisEtaB;
    p.eta_from = have_file ? fmt::format("thesis calibration (Table 4.4): {} has no paste.plastic_viscosity", o.params)
                           : "thesis calibration (Table 4.4)";
  }
  if (!need_eta) p.eta_from.clear();
  if (lab.ball_restitution && lab.ball_friction) {
    p.ball_restitution = *lab.ball_restitution, p.ball_friction = *lab.ball_friction;
    p.ball_from = fmt::format("{} steel_ball.restitution / static_friction", o.params);
  }
  return p;
}

void print_paste(const Paste& p) {
  fmt::print("paste: tau_y {:.4g} Pa ({}), rho {:.6g} kg/m3 ({}), curve {} ({})", p.tau_y, p.tau_from, p.rho,
             p.rho_from, p.curve.info().name, p.curve_from);
  if (!p.eta_from.empty()) fmt::print(", eta_B {:.6g} Pa.s ({})", p.eta, p.eta_from);
  fmt::print("\n");
}

validation::SteelBallPaste steel_ball_paste(const Paste& p) {
  validation::SteelBallPaste s;
  s.tau_y = p.tau_y, s.rho_paste = p.rho, s.curve = p.curve;
  return s;
}

}  // namespace pastemix::app
