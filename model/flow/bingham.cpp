// SPDX-License-Identifier: MIT
#include "model/flow/bingham.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "base/error.h"
#include "base/store_rheology.h"
#include "model/flow/solver.h"

namespace pastemix::flow {

double papanastasiou_term(double tau_y, double m, double g) {
  const double x = m * g;
  if (x < 1e-8) return tau_y * m * (1.0 - 0.5 * x);  // (1 - e^-x)/x = 1 - x/2 + O(x^2)
  return tau_y * (-std::expm1(-x)) / g;
}

Bingham::Bingham(double tau_y, double eta_B, double m) : tau_y_(tau_y), eta_B_(eta_B), m_(m) {
  if (!(tau_y >= 0.0 && std::isfinite(tau_y))) throw std::invalid_argument("Bingham: yield stress must be >= 0 Pa");
  if (!(eta_B > 0.0 && std::isfinite(eta_B))) throw std::invalid_argument("Bingham: plastic viscosity must be > 0 Pa s");
  if (!(m > 0.0 && std::isfinite(m))) throw std::invalid_argument("Bingham: regularisation m must be > 0 s");
}

double Bingham::viscosity(double g) const { return eta_B_ + papanastasiou_term(tau_y_, m_, g); }

std::string Bingham::describe() const {
  return fmt::format("Bingham (Papanastasiou), tau_y = {:.6g} Pa, eta_B = {:.6g} Pa s, m = {:.6g} s", tau_y_, eta_B_, m_);
}

HerschelBulkley::HerschelBulkley(double tau_y, double K, double n, double m) : tau_y_(tau_y), K_(K), n_(n), m_(m) {
  if (!(tau_y >= 0.0 && std::isfinite(tau_y))) throw std::invalid_argument("Herschel-Bulkley: yield stress must be >= 0 Pa");
  if (!(K > 0.0 && std::isfinite(K))) throw std::invalid_argument("Herschel-Bulkley: consistency K must be > 0 Pa s^n");
  if (!(n > 0.0 && std::isfinite(n))) throw std::invalid_argument("Herschel-Bulkley: flow index n must be > 0");
  if (!(m > 0.0 && std::isfinite(m))) throw std::invalid_argument("Herschel-Bulkley: regularisation m must be > 0 s");
}

double HerschelBulkley::viscosity(double g) const {
  return K_ * std::pow(std::max(g, 1.0 / m_), n_ - 1.0) + papanastasiou_term(tau_y_, m_, g);
}

std::string HerschelBulkley::describe() const {
  return fmt::format("Herschel-Bulkley (Papanastasiou), tau_y = {:.6g} Pa, K = {:.6g} Pa s^n, n = {:.6g}, m = {:.6g} s",
                     tau_y_, K_, n_, m_);
}

StorePaste read_store_paste(const std::string& file, double solids_fraction) {
  // The engine's reader (base/store_rheology.h), without the drag curve and provenance the flow does not use.
  const StoreRheology r = read_store_rheology(file, solids_fraction, "value", StoreKeys::values);
  return {r.key, r.yield_stress, r.plastic_viscosity, r.density};
}

namespace {

// law = "bingham" with rheology_from: tau_y, eta_B and the density come from the store, never the scene.
std::shared_ptr<const Rheology> bingham_from_store(const Params& paste, double m, double& density) {
  for (const char* key : {"yield_stress", "plastic_viscosity", "density"})
    if (paste.has(key)) paste.fail(key, fmt::format("give either rheology_from or {}, not both", key));
  if (!paste.has("solids_fraction")) paste.fail("rheology_from", "needs solids_fraction (which of the store's pastes)");
  const double cw = paste.number("solids_fraction", Range::fraction);
  std::filesystem::path file = paste.string("rheology_from");
  if (file.is_relative()) file = std::filesystem::path(paste.path()).parent_path() / file;
  if (!std::filesystem::exists(file))
    paste.fail("rheology_from", fmt::format("no such parameter store: {} (run `pastemix lab reduce datasets/thesis "
                                            "--out out/lab` first)",
                                            file.string()));
  StorePaste s;
  try {
    s = read_store_paste(file.string(), cw);
  } catch (const InputError& e) {  // name the scene's key too: the fix may be in either file
    paste.fail("rheology_from", e.what());
  }
  density = s.density;
  return std::make_shared<Bingham>(s.yield_stress, s.plastic_viscosity, m);
}

}  // namespace

std::shared_ptr<const Rheology> read_paste_law(const Params& paste, double& density) {
  const std::string law = paste.choice_or("law", {"newtonian", "bingham", "herschel_bulkley"}, "newtonian");
  if (law == "newtonian") {
    density = paste.number("density", Range::positive);
    return std::make_shared<Newtonian>(paste.number("viscosity", Range::positive));
  }
  if (paste.has("viscosity"))
    paste.fail("viscosity", fmt::format("law '{}' has no 'viscosity' (Bingham: plastic_viscosity; Herschel-Bulkley: "
                                        "consistency and flow_index)",
                                        law));
  if (!paste.has("regularisation"))
    paste.fail("law", fmt::format("law '{}' needs regularisation = m (s, Papanastasiou's parameter)", law));
  const double m = paste.number("regularisation", Range::positive);
  if (law == "bingham") {
    if (paste.has("rheology_from")) return bingham_from_store(paste, m, density);
    density = paste.number("density", Range::positive);
    const double tau_y = paste.number("yield_stress", Range::non_negative);
    return std::make_shared<Bingham>(tau_y, paste.number("plastic_viscosity", Range::positive), m);
  }
  if (paste.has("rheology_from"))
    paste.fail("rheology_from", "the store's paste rheology is Bingham: set law = \"bingham\"");
  density = paste.number("density", Range::positive);
  const double tau_y = paste.number("yield_stress", Range::non_negative);
  const double K = paste.number("consistency", Range::positive);
  return std::make_shared<HerschelBulkley>(tau_y, K, paste.number("flow_index", Range::positive), m);
}

double paste_speed(const FlowSolver& s) {
  const std::vector<double> uc = s.cell_velocity();
  double v = 0.0;
  for (long c = 0; c < s.grid().cell_count(); ++c) {
    if (s.alpha()[c] < 0.5) continue;
    v = std::max(v, std::hypot(uc[3 * c], uc[3 * c + 1], uc[3 * c + 2]));
  }
  return v;
}

double paste_rms_speed(const FlowSolver& s) {
  const std::vector<double> uc = s.cell_velocity();
  double num = 0.0, den = 0.0;
  for (long c = 0; c < s.grid().cell_count(); ++c) {
    const double a = std::clamp(s.alpha()[c], 0.0, 1.0);
    num += a * (uc[3 * c] * uc[3 * c] + uc[3 * c + 1] * uc[3 * c + 1] + uc[3 * c + 2] * uc[3 * c + 2]);
    den += a;
  }
  return den > 0.0 ? std::sqrt(num / den) : 0.0;
}

}  // namespace pastemix::flow
