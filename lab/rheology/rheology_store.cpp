// SPDX-License-Identifier: MIT
// The paste-rheology model in the parameter store (parameters.toml / lab.h5) and the calibration record.
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "base/error.h"
#include "base/params.h"
#include "lab/rheology/paste_rheology.h"

namespace pastemix::lab::rheology {

namespace {

constexpr const char* kModelKey = "paste_rheology.model";

Parameter make(std::string key, double value, std::string unit, Provenance prov, std::string method,
               std::string source, std::string note = {}, double sd = kNaN) {
  Parameter p;
  p.key = std::move(key);
  p.value = value;
  p.sd = sd;
  p.unit = std::move(unit);
  p.provenance = prov;
  p.method = std::move(method);
  p.source = std::move(source);
  p.note = std::move(note);
  return p;
}

Parameter text(std::string key, std::string value, std::string method, std::string source, std::string note = {}) {
  Parameter p = make(std::move(key), kNaN, "-", Provenance::assumed, std::move(method), std::move(source),
                     std::move(note));
  p.text = std::move(value);
  return p;
}

std::string model_words(const Model& m, const ShapeSource& s) {
  return s.calibrated ? fmt::format("model {}, shape parameter calibrated on case {}", to_string(m.family), s.case_id)
                      : fmt::format("model {}, shape parameter at its prior (prior)", to_string(m.family));
}

void model_parameters(std::vector<Parameter>& out, const Model& m, const ShapeSource& s,
                      const std::string& anchor_source) {
  const Anchor& a = m.anchor;
  const Prior p = prior(m.family, a);
  const std::string k = kModelKey, src = s.calibrated ? s.record : std::string("lab/rheology/paste_rheology.h");
  out.push_back(text(k + ".family", to_string(m.family), "lab/rheology/paste_rheology.h", "manifest [paste_rheology]"));
  Parameter shape = make(k + ".shape", m.shape, p.unit, s.calibrated ? Provenance::calibrated : Provenance::assumed,
                         model_words(m, s) + (s.detail.empty() ? "" : "; " + s.detail), src,
                         fmt::format("{} = the family's one shape parameter; prior [{:.6g}, {:.6g}] from {}; {}", p.name,
                                     p.lo, p.hi, kPriorSource, kAtRestLabel),
                         m.shape_sd);
  out.push_back(shape);
  out.push_back(make(k + ".shape_prior_low", p.lo, p.unit, Provenance::literature, "prior range, low end", kPriorSource));
  out.push_back(make(k + ".shape_prior_high", p.hi, p.unit, Provenance::literature, "prior range, high end", kPriorSource));
  out.push_back(text(k + ".calibration", s.calibrated ? fmt::format("calibrated on case {}", s.case_id) : "prior",
                     model_words(m, s), src));
  out.push_back(make(k + ".anchor_solids_fraction", a.solids_fraction, "-", Provenance::measured,
                     "solids content by mass of the measured paste", anchor_source));
  out.push_back(make(k + ".anchor_yield_stress", a.yield_stress, "Pa", Provenance::measured, "paste.yield_stress (slump)",
                     anchor_source, "", a.yield_stress_sd));
  out.push_back(make(k + ".anchor_plastic_viscosity", a.plastic_viscosity, "Pa.s", Provenance::calibrated,
                     fmt::format("steel-ball calibration with drag curve {}", a.curve), anchor_source, "",
                     a.plastic_viscosity_sd));
  out.push_back(make(k + ".anchor_density", a.density, "kg/m3", Provenance::measured, "paste.density (slump file)",
                     anchor_source));
  out.push_back(text(k + ".curve", a.curve, "the drag curve the anchor's eta_B belongs to: a scene reading this "
                                            "rheology must use it", anchor_source));
  out.push_back(make(k + ".solids_density", a.solids_density, "kg/m3", Provenance::literature,
                     "tailings particle density (Table 3.2's rho_s)", "manifest [paste_rheology]"));
  out.push_back(make(k + ".water_density", a.water_density, "kg/m3", Provenance::literature, "water",
                     "manifest [paste_rheology]"));
  const double mix = mixture_density(a, a.solids_fraction);
  out.push_back(make(k + ".mixture_density_at_anchor", mix, "kg/m3", Provenance::assumed,
                     "mixture rule 1/rho = C_w/rho_s + (1 - C_w)/rho_w at the anchor", "lab/rheology/paste_rheology.h",
                     fmt::format("measured {:.1f} kg/m3: gap {:.1f} kg/m3 ({:.2f} %), read as entrained air", a.density,
                                 mix - a.density, 100.0 * (mix - a.density) / mix)));
  out.push_back(make(k + ".air_content", air_content(a), "-", Provenance::assumed,
                     "1 - rho_measured / rho_mix at the anchor, held constant at every solids content",
                     "lab/rheology/paste_rheology.h"));
  out.push_back(make(k + ".packing_fraction", packing_fraction(m), "-", Provenance::assumed,
                     m.family == Family::packing ? "phi_m = the shape parameter"
                                                 : "packing equivalent of b (same tau_y ratio 72.5/75 %)",
                     "Krieger & Dougherty (1959), [eta] = 2.5"));
}

// The band of the protocol: tau_y and eta_B with the shape parameter at -1 sd and +1 sd (k.minus_sd.*,
// k.plus_sd.*), read by a scene's `rheology_at = "minus_sd" | "plus_sd"`. Both move together: one parameter.
void band_parameters(std::vector<Parameter>& out, const Model& m, double cw, const std::string& k, const std::string& src) {
  const double sd = std::isfinite(m.shape_sd) ? m.shape_sd : 0.0;
  for (const auto& [name, sign] : {std::pair{"minus_sd", -1.0}, std::pair{"plus_sd", 1.0}}) {
    Model b = m;
    b.shape = m.shape + sign * sd;
    const std::string how = fmt::format("{} = {:.6g} (the shape parameter {} 1 sd)", prior(m.family, m.anchor).name,
                                        b.shape, sign < 0 ? "-" : "+");
    out.push_back(make(fmt::format("{}.{}.yield_stress", k, name), yield_stress(b, cw), "Pa", Provenance::assumed, how, src));
    out.push_back(make(fmt::format("{}.{}.plastic_viscosity", k, name), plastic_viscosity(b, cw), "Pa.s",
                       Provenance::assumed, how, src));
  }
}

}  // namespace

std::vector<Parameter> store_parameters(const Model& m, const ShapeSource& s, const std::vector<double>& cws,
                                        const std::vector<std::string>& cases, const std::string& anchor_source) {
  check_anchor(m.anchor, anchor_source);
  check_shape(m.family, m.anchor, m.shape, s.calibrated ? s.record : "paste_rheology prior");
  std::vector<Parameter> out;
  model_parameters(out, m, s, anchor_source);
  for (std::size_t i = 0; i < cws.size(); ++i) {
    const double cw = cws[i];
    const Point pt = evaluate(m, cw);
    const std::string k = "paste_rheology." + solids_key(cw);
    const bool anchor = cw == m.anchor.solids_fraction;
    const Provenance prov = anchor ? Provenance::measured : s.calibrated ? Provenance::calibrated : Provenance::assumed;
    const std::string how = anchor ? "the anchor (measured paste)" : model_words(m, s);
    const std::string used = fmt::format("used by case(s) {}", i < cases.size() ? cases[i] : "?");
    const std::string note = anchor ? used : fmt::format("{}; {}", kAtRestLabel, used);
    const std::string src = s.calibrated && !anchor ? s.record : anchor_source;
    out.push_back(make(k + ".solids_fraction", cw, "-", Provenance::measured, "solids content by mass (Table 3.1)",
                       "mixing programme", used));
    out.push_back(make(k + ".solids_volume_fraction", pt.phi, "-", Provenance::assumed,
                       "phi = (C_w/rho_s) / (C_w/rho_s + (1 - C_w)/rho_w)", "lab/rheology/paste_rheology.h"));
    out.push_back(make(k + ".yield_stress", pt.yield_stress, "Pa", prov, how, src, note, pt.yield_stress_sd));
    Parameter eta = make(k + ".plastic_viscosity", pt.plastic_viscosity, "Pa.s", anchor ? Provenance::calibrated : prov,
                         anchor ? "the anchor (steel-ball calibration)" : how + "; Krieger-Dougherty on phi", src,
                         note + fmt::format("; belongs to drag curve {}", m.anchor.curve), pt.plastic_viscosity_sd);
    out.push_back(eta);
    out.push_back(make(k + ".density", pt.density, "kg/m3", anchor ? Provenance::measured : Provenance::assumed,
                       anchor ? "the anchor (slump file)" : "mixture rule with the anchor's air content", anchor_source));
    band_parameters(out, m, cw, k, src);
  }
  return out;
}

Model read_model(const std::string& file) {
  if (!std::filesystem::exists(file))
    throw InputError(file, 0, kModelKey,
                     "no such parameter store: run `pastemix lab reduce datasets/thesis --out out/lab` first");
  const Params root = Params::parse_file(file);
  const auto pr = root.optional_table("paste_rheology");
  const auto mt = pr ? pr->optional_table("model") : std::nullopt;
  if (!mt)
    throw InputError(file, 0, kModelKey,
                     "missing: this store predates the paste-rheology model; rerun `pastemix lab reduce`");
  auto value = [&](const char* key) { return mt->table(key).number("value"); };
  auto sd = [&](const char* key) { return mt->table(key).optional_number("sd").value_or(kNaN); };
  Model m;
  const std::string fam = mt->table("family").string("text");
  const auto f = find_family(fam);
  if (!f) mt->table("family").fail("text", fmt::format("unknown family '{}' (exponential, packing)", fam));
  m.family = *f;
  m.shape = value("shape");
  m.shape_sd = sd("shape");
  Anchor& a = m.anchor;
  a.solids_fraction = value("anchor_solids_fraction");
  a.yield_stress = value("anchor_yield_stress");
  a.yield_stress_sd = sd("anchor_yield_stress");
  a.plastic_viscosity = value("anchor_plastic_viscosity");
  a.plastic_viscosity_sd = sd("anchor_plastic_viscosity");
  a.density = value("anchor_density");
  a.curve = mt->table("curve").string("text");
  a.solids_density = value("solids_density");
  a.water_density = value("water_density");
  // Not finish()ed: the store holds every lab parameter; only the model is read here.
  check_anchor(a, file);
  check_shape(m.family, a, m.shape, file);
  return m;
}

Calibration read_calibration(const std::string& path) {
  if (!std::filesystem::exists(path))
    throw InputError(path, 0, "", "no such calibration record (written by `pastemix calibrate rheology`)");
  const Params root = Params::parse_file(path);
  const Params t = root.table("rheology_calibration");
  Calibration c;
  const std::string fam = t.choice("family", family_names());
  c.family = *find_family(fam);
  c.shape = t.number("shape");
  c.sd = t.number("sd", Range::non_negative);
  c.case_id = static_cast<int>(t.integer("case"));
  if (c.case_id < 1) t.fail("case", "expected a mixing case number >= 1");
  c.detail = t.string_or("detail", "");
  t.ignore("command");
  t.ignore("created");
  root.finish();
  return c;
}

std::string calibration_toml(const Calibration& c, const std::string& command, const std::string& created) {
  auto q = [](const std::string& s) {
    std::string o = "\"";
    for (char ch : s) {
      if (ch == '"' || ch == '\\') o += '\\';
      if (ch == '\n') {
        o += "\\n";
        continue;
      }
      o += ch;
    }
    return o + "\"";
  };
  return fmt::format(
      "# Paste-rheology calibration record (`pastemix calibrate rheology`). `pastemix lab reduce DIR --out OUT\n"
      "# --rheology-calibration THIS_FILE` writes it into the parameter store.\n"
      "[rheology_calibration]\nfamily = {}\nshape = {}\nsd = {}\ncase = {}\ndetail = {}\ncommand = {}\ncreated = {}\n",
      q(to_string(c.family)), c.shape, c.sd, c.case_id, q(c.detail), q(command), q(created));
}

}  // namespace pastemix::lab::rheology
