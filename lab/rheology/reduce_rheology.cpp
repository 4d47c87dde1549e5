// SPDX-License-Identifier: MIT
#include "lab/rheology/reduce_rheology.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "base/error.h"
#include "lab/rheology/paste_rheology.h"

namespace pastemix::lab::rheology {

namespace {

const Parameter& find_parameter(const Params& table, const ReduceResult& r, const std::string& key) {
  for (const auto& p : r.parameters)
    if (p.key == key) return p;
  table.fail("anchor_solids_fraction",
             fmt::format("needs {} from the [slump] step, which the manifest does not name", key));
}

}  // namespace

void run_paste_rheology(const Params& t, const Manifest& m, ReduceResult& r) {
  Model model;
  const auto fam = find_family(t.choice("family", family_names()));
  model.family = *fam;
  Anchor& a = model.anchor;
  a.solids_fraction = t.number("anchor_solids_fraction", Range::fraction);
  a.plastic_viscosity = t.number("anchor_plastic_viscosity", Range::positive);
  const std::string eta_source = t.string("anchor_plastic_viscosity_source");
  a.curve = t.string("anchor_curve");
  a.solids_density = t.number("solids_density", Range::positive);
  a.water_density = t.number("water_density", Range::positive);
  const Parameter& tau = find_parameter(t, r, "paste.yield_stress");
  const Parameter& rho = find_parameter(t, r, "paste.density");
  a.yield_stress = tau.value;
  a.yield_stress_sd = tau.sd;
  a.density = rho.value;
  check_anchor(a, m.path().string());
  if (r.mixing_cases.empty())
    t.fail("family", "needs the solids contents of the [mixing_program] step, which the manifest does not name");
  // Every solids content a case uses, with its cases ("2, 4, 5, 6, 7").
  std::vector<double> cws;
  for (const auto& c : r.mixing_cases)
    if (std::find(cws.begin(), cws.end(), c.solids_fraction) == cws.end()) cws.push_back(c.solids_fraction);
  std::sort(cws.begin(), cws.end());
  std::vector<std::string> cases;
  for (double cw : cws) {
    std::vector<std::string> ids;
    for (const auto& c : r.mixing_cases)
      if (c.solids_fraction == cw) ids.push_back(std::to_string(c.case_id));
    cases.push_back(fmt::format("{}", fmt::join(ids, ", ")));
  }
  ShapeSource src;
  const Prior prior_range = prior(model.family, a);
  if (r.options.rheology_calibration.empty()) {
    model.shape = prior_range.mid();
    model.shape_sd = prior_range.sd();
    src.detail = fmt::format("middle of the prior [{:.6g}, {:.6g}], sd = range/sqrt(12)", prior_range.lo, prior_range.hi);
  } else {
    const Calibration c = read_calibration(r.options.rheology_calibration);
    model.family = c.family;
    model.shape = c.shape;
    model.shape_sd = c.sd;
    check_shape(c.family, a, c.shape, r.options.rheology_calibration);
    src.calibrated = true;
    src.case_id = c.case_id;
    src.record = r.options.rheology_calibration;
    src.detail = c.detail;
    r.inputs.push_back(r.options.rheology_calibration);
  }
  const std::string anchor_source = fmt::format("{} (tau_y, density); eta_B: {}", tau.source, eta_source);
  for (auto& p : store_parameters(model, src, cws, cases, anchor_source)) r.parameters.push_back(std::move(p));
  const double mix = mixture_density(a, a.solids_fraction);
  r.warnings.push_back({m.path().string(),
                        fmt::format("paste density: the mixture rule with rho_s = {:g} kg/m3 gives {:.1f} kg/m3 at "
                                    "C_w = {:g}, the slump file {:.1f}: gap {:.1f} kg/m3, taken as {:.2f} % air at "
                                    "every solids content",
                                    a.solids_density, mix, a.solids_fraction, a.density, mix - a.density,
                                    100.0 * air_content(a))});
}

}  // namespace pastemix::lab::rheology
