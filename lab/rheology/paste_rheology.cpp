// SPDX-License-Identifier: MIT
#include "lab/rheology/paste_rheology.h"

#include <cmath>

#include <fmt/format.h>

#include "base/error.h"
#include "base/params.h"
#include "lab/ingest/ingest.h"

namespace pastemix::lab::rheology {

namespace {

// The tau_y ratio the priors are stated over: anchor and 2.5 points of solids below it (mass fraction).
constexpr double kStep = 0.025;

double kd_factor(double phi, double phi_m) { return std::pow(1.0 - phi / phi_m, -kIntrinsicViscosity * phi_m); }

double packing_g(double phi, double phi_m) { return phi * phi * phi / (phi_m - phi); }

double shape_derivative(const Model& m, double cw, double (*f)(const Model&, double)) {
  const Prior p = prior(m.family, m.anchor);
  const double h = 1e-6 * (p.hi - p.lo);
  Model lo = m, hi = m;
  lo.shape -= h, hi.shape += h;
  return (f(hi, cw) - f(lo, cw)) / (2.0 * h);
}

double combine(double a, double b) {  // sqrt(a^2 + b^2) with NaN meaning "not known" (dropped)
  const bool fa = std::isfinite(a), fb = std::isfinite(b);
  if (!fa && !fb) return kNaN;
  return std::hypot(fa ? a : 0.0, fb ? b : 0.0);
}

}  // namespace

const char* to_string(Family f) { return f == Family::exponential ? "exponential" : "packing"; }

std::optional<Family> find_family(std::string_view name) {
  if (name == "exponential") return Family::exponential;
  if (name == "packing") return Family::packing;
  return std::nullopt;
}

double Prior::sd() const { return (hi - lo) / std::sqrt(12.0); }

double solids_volume_fraction(const Anchor& a, double cw) {
  const double vs = cw / a.solids_density, vw = (1.0 - cw) / a.water_density;
  return vs / (vs + vw);
}

double mixture_density(const Anchor& a, double cw) {
  return 1.0 / (cw / a.solids_density + (1.0 - cw) / a.water_density);
}

double air_content(const Anchor& a) { return 1.0 - a.density / mixture_density(a, a.solids_fraction); }

double density(const Anchor& a, double cw) {
  // rho_75 x (a ratio that is exactly 1 at the anchor): the anchor's density comes back to the bit.
  return a.density * (mixture_density(a, cw) / mixture_density(a, a.solids_fraction));
}

double equivalent_packing_fraction(const Anchor& a, double factor) {
  const double hi = solids_volume_fraction(a, a.solids_fraction);
  const double lo = solids_volume_fraction(a, a.solids_fraction - kStep);
  // G(hi)/G(lo) = (hi/lo)^3 (phi_m - lo)/(phi_m - hi) = factor, solved for phi_m.
  const double q = factor / std::pow(hi / lo, 3.0);
  if (!(q > 1.0))
    throw InputError("", 0, "factor",
                     fmt::format("a tau_y factor of {:.4g} per 2.5 points is below what phi^3 alone gives ({:.4g}): "
                                 "no packing fraction matches it",
                                 factor, std::pow(hi / lo, 3.0)));
  return (q * hi - lo) / (q - 1.0);
}

Prior prior(Family f, const Anchor& a) {
  if (f == Family::exponential)
    return Prior{std::log(kFactorLow) / (100.0 * kStep), std::log(kFactorHigh) / (100.0 * kStep), std::string("b"),
                 std::string("1/wt%")};
  // The steepest rise (factor 4.5) has the packing fraction closest to the anchor's phi: the low end.
  return Prior{equivalent_packing_fraction(a, kFactorHigh), equivalent_packing_fraction(a, kFactorLow),
               std::string("phi_m"), std::string("-")};
}

void check_anchor(const Anchor& a, const std::string& where) {
  auto positive = [&](double v, const char* field) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError(where, 0, field, fmt::format("expected a positive finite value, got {}", v));
  };
  positive(a.yield_stress, "anchor yield_stress (Pa)");
  positive(a.plastic_viscosity, "anchor plastic_viscosity (Pa.s)");
  positive(a.density, "anchor density (kg/m3)");
  positive(a.solids_density, "solids_density (kg/m3)");
  positive(a.water_density, "water_density (kg/m3)");
  if (!(a.solids_fraction > kStep && a.solids_fraction < 1.0))
    throw InputError(where, 0, "anchor solids_fraction",
                     fmt::format("a mass fraction in ({}, 1) (e.g. 0.75), got {}", kStep, a.solids_fraction));
  if (a.curve.empty()) throw InputError(where, 0, "anchor curve", "the drag curve eta_B belongs to is not named");
}

void check_shape(Family f, const Anchor& a, double shape, const std::string& where) {
  const Prior p = prior(f, a);
  const std::string field = fmt::format("{}.{}", to_string(f), p.name);
  if (!std::isfinite(shape)) throw InputError(where, 0, field, fmt::format("not a finite number ({})", shape));
  if (shape < p.lo || shape > p.hi)
    throw InputError(where, 0, field,
                     fmt::format("{} = {:.6g} {} is outside its prior range [{:.6g}, {:.6g}] ({})", field, shape,
                                 p.unit, p.lo, p.hi, kPriorSource));
}

double packing_fraction(const Model& m) {
  if (m.family == Family::packing) return m.shape;
  return equivalent_packing_fraction(m.anchor, std::exp(m.shape * 100.0 * kStep));
}

double yield_stress(const Model& m, double cw) {
  const Anchor& a = m.anchor;
  if (m.family == Family::exponential) return a.yield_stress * std::exp(m.shape * 100.0 * (cw - a.solids_fraction));
  const double phi = solids_volume_fraction(a, cw), phi_a = solids_volume_fraction(a, a.solids_fraction);
  if (!(phi < m.shape))
    throw InputError("", 0, "solids_fraction",
                     fmt::format("C_w = {:.4g} gives phi = {:.4g}, at or above the packing fraction {:.4g}: no yield "
                                 "stress (the paste is jammed)",
                                 cw, phi, m.shape));
  return a.yield_stress * (packing_g(phi, m.shape) / packing_g(phi_a, m.shape));
}

double plastic_viscosity(const Model& m, double cw) {
  const Anchor& a = m.anchor;
  const double phi_m = packing_fraction(m);
  const double phi = solids_volume_fraction(a, cw), phi_a = solids_volume_fraction(a, a.solids_fraction);
  if (!(phi < phi_m))
    throw InputError("", 0, "solids_fraction",
                     fmt::format("C_w = {:.4g} gives phi = {:.4g}, at or above the packing fraction {:.4g}", cw, phi,
                                 phi_m));
  return a.plastic_viscosity * (kd_factor(phi, phi_m) / kd_factor(phi_a, phi_m));
}

Point evaluate(const Model& m, double cw) {
  Point p;
  p.solids_fraction = cw;
  p.phi = solids_volume_fraction(m.anchor, cw);
  p.yield_stress = yield_stress(m, cw);
  p.plastic_viscosity = plastic_viscosity(m, cw);
  p.density = density(m.anchor, cw);
  if (cw == m.anchor.solids_fraction) {  // the measured paste: its own uncertainties, nothing from the shape
    p.yield_stress_sd = m.anchor.yield_stress_sd;
    p.plastic_viscosity_sd = m.anchor.plastic_viscosity_sd;
    return p;
  }
  const bool shape_known = std::isfinite(m.shape_sd);
  const double dtau = shape_known ? shape_derivative(m, cw, yield_stress) * m.shape_sd : kNaN;
  const double deta = shape_known ? shape_derivative(m, cw, plastic_viscosity) * m.shape_sd : kNaN;
  p.yield_stress_sd = combine(p.yield_stress / m.anchor.yield_stress * m.anchor.yield_stress_sd, dtau);
  p.plastic_viscosity_sd =
      combine(p.plastic_viscosity / m.anchor.plastic_viscosity * m.anchor.plastic_viscosity_sd, deta);
  return p;
}

std::string solids_key(double cw) {
  std::string s = fmt::format("cw_{:g}", std::round(cw * 1e4) / 1e2);  // 0.725 -> "cw_72.5"
  for (char& c : s)
    if (c == '.') c = '_';
  return s;
}

}  // namespace pastemix::lab::rheology
