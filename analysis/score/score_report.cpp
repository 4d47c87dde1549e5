// SPDX-License-Identifier: MIT
// The three text forms of a Score: the printed table, score.csv (per block) and score.toml (summary).
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "analysis/score/score.h"

namespace pastemix::analysis {

namespace {

std::string pct(double f) { return std::isfinite(f) ? fmt::format("{:.1f}", 100.0 * f) : "nan"; }

std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) out += fmt::format("\\u{:04x}", static_cast<int>(c));
        else out += c;
    }
  }
  return out + "\"";
}

std::string toml_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::string s = fmt::format("{:.6g}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string seeds_of(const Score& s) {
  std::vector<std::string> v;
  for (const auto& r : s.realizations) v.push_back(r.seed >= 0 ? fmt::format("{}", r.seed) : "?");
  return fmt::format("{}", fmt::join(v, ", "));
}

std::string kg(const Summary& m, int n) {
  return n > 1 ? fmt::format("{:.4f} +- {:.4f} kg", m.mean, m.sd) : fmt::format("{:.4f} kg", m.mean);
}

}  // namespace

std::string headline_table(const Score& s) {
  const int n = static_cast<int>(s.realizations.size());
  std::string o = fmt::format("HEADLINE: mixing case {}, {} realization{} (seed{} {}), {}\n", s.case_id, n,
                              n == 1 ? "" : "s", n == 1 ? "" : "s", seeds_of(s),
                              s.all_at_rest() ? "scored at rest"
                                              : "NOT AT REST (--allow-moving): an unfinished state, not a result");
  o += "rock per layer (kg, sum of the layer's 12 blocks): lab, model, relative error, tolerance, matched\n";
  for (const auto& h : s.headline)
    o += fmt::format("  layer {}: lab {:.4f}  model {}  {:>7}  +-{:.4f}  {}\n", h.k, h.lab,
                     n > 1 ? fmt::format("{:.4f} +- {:.4f}", h.model.mean, h.model.sd) : fmt::format("{:.4f}", h.model.mean),
                     std::isfinite(h.rel_error) ? fmt::format("{:+.1f} %", 100 * h.rel_error) : std::string("n/a"),
                     h.tolerance, h.matched ? "yes" : "NO");
  o += fmt::format("  {} of {} layers matched (tolerance: max(15 % of the lab's layer mass, 2 model sd, 10 g); the lab's "
                   "noise floor: one specimen per case, its 36 blocks recovered 0.85-1.02 kg of the 1 kg poured; this "
                   "case {:.3f} kg)\n",
                   s.layers_matched, s.headline.size(), s.lab_recovered_rock);
  o += fmt::format("deep share (rock in layers 2-3 / rock in all blocks): lab {} %, model {} %{}\n",
                   pct(s.lab_deep_share), pct(s.model_deep_share.mean),
                   n > 1 ? fmt::format(" +- {}", pct(s.model_deep_share.sd)) : std::string());
  o += "centre column C % (mean of M_22k and M_32k), layers 1 / 2 / 3:";
  std::vector<std::string> lab, model;
  for (const auto& c : s.centre) {
    lab.push_back(pct(c.lab_C));
    model.push_back(pct(c.model_C));
  }
  o += fmt::format(" lab {}, model {} (centre-column MAE {:.2f} pp)\n", fmt::join(lab, " / "), fmt::join(model, " / "),
                   s.centre_mae_pp);
  const char* verdict = s.model_cone == s.lab_cone ? (s.lab_cone ? "reproduced" : "agrees (no cone in either)")
                        : (s.lab_cone ? "NOT reproduced" : "the model has a cone the lab does not");
  o += fmt::format("unmixed cone (C >= 90 % in M_221 and M_321): model {} ({} %, {} %), lab {} ({} %, {} %): {}\n",
                   s.model_cone ? "yes" : "no", pct(s.cone_221), pct(s.cone_321), s.lab_cone ? "yes" : "no",
                   pct(s.lab_cone_221), pct(s.lab_cone_321), verdict);
  o += fmt::format("mean absolute C error: {:.2f} pp over {} blocks (details below)\n\n", s.mae_pp, s.blocks_compared);
  return o;
}

std::string score_table(const Score& s) {
  const int n = static_cast<int>(s.realizations.size());
  std::string o = headline_table(s);
  o += fmt::format("score: mixing case {} vs {} realization{} (seed{} {})\n", s.case_id, n,
                   n == 1 ? "" : "s", n == 1 ? "" : "s", seeds_of(s));
  o += s.top_open ? "rock above the final surface counts in the layer-1 block under it (the lab cut the unmixed cone "
                    "with layer 1: its blocks recovered 0.85-1.02 kg of the 1 kg poured)\n"
                  : "rock above the final surface is in no block (--above-surface none)\n";
  o += std::isfinite(s.K) ? fmt::format("K = {:g} kg/m3 ({})\n", s.K, s.K_source)
                          : std::string("K unknown for this case: S not computed, S classes of rock blocks not compared\n");
  o += fmt::format("{:<7} {:>7} {:>8} {:>6} {:>8}   {:<16} {:<16}\n", "block", "lab C%", "model C%",
                   n > 1 ? "sd" : "", "err pp", "S class lab", "S class model");
  for (const auto& b : s.blocks) {
    std::string model_cls = to_string(b.model_class);
    if (n > 1) model_cls += fmt::format(" ({:.0f} %)", 100 * b.model_class_share);
    o += fmt::format("{:<7} {:>7} {:>8} {:>6} {:>+8.1f}   {:<16} {:<16}{}\n", b.id, pct(b.lab_C), pct(b.model_C.mean),
                     n > 1 ? pct(b.model_C.sd) : "", b.error_pp, to_string(b.lab_class), model_cls,
                     b.class_compared ? (b.class_agrees ? "" : "  <- differs") : "");
  }
  o += fmt::format("mean absolute C error: {:.2f} pp over {} blocks (max {:.1f} pp)", s.mae_pp, s.blocks_compared,
                   s.max_abs_error_pp);
  if (n > 1)
    o += fmt::format("; single realizations {:.2f} +- {:.2f} pp", s.realization_mae_pp.mean, s.realization_mae_pp.sd);
  o += "\ncentre column (mean of M_22k and M_32k):\n";
  o += fmt::format("  {:<6} {:>7} {:>8} {:>6} {:>8}\n", "layer", "lab C%", "model C%", n > 1 ? "sd" : "", "err pp");
  for (const auto& c : s.centre)
    o += fmt::format("  {:<6} {:>7} {:>8} {:>6} {:>+8.1f}\n", c.k, pct(c.lab_C), pct(c.model_C),
                     n > 1 ? pct(c.model_sd) : "", c.error_pp);
  o += fmt::format("  centre-column mean absolute error: {:.2f} pp\n", s.centre_mae_pp);
  o += fmt::format("S classes (no rock / S < 100 % / capped; model blocks with < {:g} g rock count as no rock, the "
                   "lab's weighing resolution): {} of {} compared blocks agree\n",
                   1e3 * s.no_rock_below, s.classes_agree, s.classes_compared);
  o += s.S_compared ? fmt::format("S values (void filling, capped at 100 %): mean absolute error {:.1f} pp over the {} "
                                  "blocks where lab and model both have one\n",
                                  s.S_mae_pp, s.S_compared)
                    : "S values: no block where lab and model both have one (no K, or no rock)\n";
  const char* verdict = s.model_cone == s.lab_cone ? (s.lab_cone ? "reproduced" : "agrees (no cone in either)")
                        : (s.lab_cone ? "NOT reproduced" : "the model has a cone the lab does not");
  o += fmt::format("unmixed cone (C >= 90 % in M_221 and M_321): model {} ({} %, {} %), lab {} ({} %, {} %): {}\n",
                   s.model_cone ? "yes" : "no", pct(s.cone_221), pct(s.cone_321), s.lab_cone ? "yes" : "no",
                   pct(s.lab_cone_221), pct(s.lab_cone_321), verdict);
  o += fmt::format("rock: poured {}; mixed (submerged) {}; unmixed (above the surface) {}; outside the grid's "
                   "blocks {}; escaped (left the simulation's domain) {}; lab recovered {:.4f} kg in its 36 blocks\n",
                   kg(s.poured, n), kg(s.mixed, n), kg(s.unmixed, n), kg(s.outside_grid, n), kg(s.escaped, n),
                   s.lab_recovered_rock);
  o += "rock per layer (kg, sum of 12 blocks):";
  for (std::size_t k = 0; k < s.lab_layer_rock.size(); ++k)
    o += fmt::format("  layer {}: lab {:.4f}, model {}", k + 1, s.lab_layer_rock[k],
                     n > 1 ? fmt::format("{:.4f} +- {:.4f}", s.model_layer_rock[k].mean, s.model_layer_rock[k].sd)
                           : fmt::format("{:.4f}", s.model_layer_rock[k].mean));
  o += fmt::format("\ndeep share (rock in layers 2-3 / rock in all blocks): lab {} %, model {} %{}\n",
                   pct(s.lab_deep_share), pct(s.model_deep_share.mean),
                   n > 1 ? fmt::format(" +- {}", pct(s.model_deep_share.sd)) : std::string());
  return o;
}

std::string score_csv(const Score& s) {
  std::string o =
      "block_id,i,j,k,lab_C_percent,model_C_mean_percent,model_C_sd_percent,C_error_pp,lab_S_class,model_S_class,"
      "model_S_class_share,S_class_agrees,lab_S_percent,model_S_mean_percent,model_S_sd_percent,model_S_n,S_error_pp\n";
  for (const auto& b : s.blocks)
    o += fmt::format("{},{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{},{},{:.3f},{},{:.4f},{:.4f},{:.4f},{},{:.4f}\n", b.id, b.i,
                     b.j, b.k, 100 * b.lab_C, 100 * b.model_C.mean, 100 * b.model_C.sd, b.error_pp,
                     to_string(b.lab_class), to_string(b.model_class), b.model_class_share,
                     b.class_compared ? (b.class_agrees ? "yes" : "no") : "not compared", 100 * b.lab_S,
                     100 * b.model_S.mean, 100 * b.model_S.sd, b.model_S.n,
                     b.S_compared ? 100 * (b.model_S.mean - b.lab_S) : std::nan(""));
  return o;
}

namespace {

// [headline]: did the rock go where the lab found it?
std::string headline_toml(const Score& s) {
  std::string o;
  o += "[headline]  # did the rock go where the lab found it? (analysis/score/score.h)\n";
  o += fmt::format("state = {}\nlayers_matched = {}\nlayer_tolerance_rule = {}\n",
                   toml_string(s.all_at_rest() ? "at rest" : "NOT AT REST (--allow-moving)"), s.layers_matched,
                   toml_string("max(15 % of the lab's layer mass, 2 model sd, 10 g): the lab's 36 blocks recovered "
                               "0.85-1.02 kg of the 1 kg poured, one specimen per case"));
  {
    std::vector<std::string> lab, mean, sd, rel, tol, ok;
    for (const auto& h : s.headline) {
      lab.push_back(toml_number(h.lab));
      mean.push_back(toml_number(h.model.mean));
      sd.push_back(toml_number(h.model.sd));
      rel.push_back(toml_number(h.rel_error));
      tol.push_back(toml_number(h.tolerance));
      ok.push_back(h.matched ? "true" : "false");
    }
    o += fmt::format("lab_layer_rock_kg = [{}]\nmodel_layer_rock_kg = [{}]\nmodel_layer_rock_sd_kg = [{}]\n"
                     "layer_rel_error = [{}]\nlayer_tolerance_kg = [{}]\nlayer_matched = [{}]\n",
                     fmt::join(lab, ", "), fmt::join(mean, ", "), fmt::join(sd, ", "), fmt::join(rel, ", "),
                     fmt::join(tol, ", "), fmt::join(ok, ", "));
  }
  o += fmt::format("lab_deep_share = {}\nmodel_deep_share = {}\nmodel_deep_share_sd = {}\n",
                   toml_number(s.lab_deep_share), toml_number(s.model_deep_share.mean),
                   toml_number(s.model_deep_share.sd));
  {
    std::vector<std::string> lab, model;
    for (const auto& c : s.centre) {
      lab.push_back(toml_number(100 * c.lab_C));
      model.push_back(toml_number(100 * c.model_C));
    }
    o += fmt::format("centre_lab_C_percent = [{}]\ncentre_model_C_percent = [{}]\n", fmt::join(lab, ", "),
                     fmt::join(model, ", "));
  }
  o += fmt::format("cone_model = {}\ncone_lab = {}\ncone_reproduced = {}\n\n", s.model_cone, s.lab_cone,
                   s.model_cone && s.lab_cone);
  return o;
}

// [score]: the C errors over the blocks and the S classes.
std::string score_section_toml(const Score& s) {
  std::string o;
  o += "[score]\n";
  o += fmt::format("C_mean_abs_error_pp = {}\nC_max_abs_error_pp = {}\nblocks_compared = {}\n", toml_number(s.mae_pp),
                   toml_number(s.max_abs_error_pp), s.blocks_compared);
  o += fmt::format("realization_C_mean_abs_error_pp = {}  # mean over single realizations\n"
                   "realization_C_mean_abs_error_sd_pp = {}\n",
                   toml_number(s.realization_mae_pp.mean), toml_number(s.realization_mae_pp.sd));
  o += fmt::format("S_values_compared = {}\nS_mean_abs_error_pp = {}\n", s.S_compared, toml_number(s.S_mae_pp));
  o += fmt::format("centre_column_mean_abs_error_pp = {}\nS_classes_compared = {}\nS_classes_agree = {}\n"
                   "S_no_rock_below_g = {}  # model blocks with less rock count as 'no rock' (lab resolution)\n\n",
                   toml_number(s.centre_mae_pp), s.classes_compared, s.classes_agree, toml_number(1e3 * s.no_rock_below));
  return o;
}

// [centre_column]: the two centre blocks of each layer.
std::string centre_toml(const Score& s) {
  std::string o;
  o += "[centre_column]  # mean of M_22k and M_32k, k = layer 1 (top) .. 3\n";
  std::vector<std::string> lab, model, sd, err;
  for (const auto& c : s.centre) {
    lab.push_back(toml_number(100 * c.lab_C));
    model.push_back(toml_number(100 * c.model_C));
    sd.push_back(toml_number(100 * c.model_sd));
    err.push_back(toml_number(c.error_pp));
  }
  o += fmt::format("lab_C_percent = [{}]\nmodel_C_percent = [{}]\nmodel_C_sd_percent = [{}]\nerror_pp = [{}]\n\n",
                   fmt::join(lab, ", "), fmt::join(model, ", "), fmt::join(sd, ", "), fmt::join(err, ", "));
  return o;
}

// [unmixed_cone]: the two top centre blocks.
std::string cone_toml(const Score& s) {
  std::string o;
  o += "[unmixed_cone]  # reproduced when the model's C >= 90 % in both top centre blocks\n";
  o += fmt::format("model_C_M_221_percent = {}\nmodel_C_M_321_percent = {}\nlab_C_M_221_percent = {}\n"
                   "lab_C_M_321_percent = {}\nmodel_has_cone = {}\nlab_has_cone = {}\n"
                   "reproduced = {}  # both have it\n\n",
                   toml_number(100 * s.cone_221), toml_number(100 * s.cone_321), toml_number(100 * s.lab_cone_221),
                   toml_number(100 * s.lab_cone_321), s.model_cone, s.lab_cone, s.model_cone && s.lab_cone);
  return o;
}

// [rock_mass_kg]: where the poured rock ended, ensemble mean and sd.
std::string rock_toml(const Score& s) {
  std::string o;
  o += "[rock_mass_kg]  # ensemble mean and sd; mixed = submerged, unmixed = above the final surface; escaped = left the simulation's domain (outflow)\n";
  o += fmt::format("above_surface_counted_in_layer_1 = {}\n", s.top_open);
  auto ms = [&](const char* name, const Summary& m) {
    o += fmt::format("{} = {}\n{}_sd = {}\n", name, toml_number(m.mean), name, toml_number(m.sd));
  };
  ms("poured", s.poured);
  ms("mixed", s.mixed);
  ms("unmixed", s.unmixed);
  ms("outside_grid", s.outside_grid);
  ms("escaped", s.escaped);
  o += fmt::format("lab_recovered = {}\n", toml_number(s.lab_recovered_rock));
  {
    std::vector<std::string> lab, mean, sd;
    for (std::size_t k = 0; k < s.lab_layer_rock.size(); ++k) {
      lab.push_back(toml_number(s.lab_layer_rock[k]));
      mean.push_back(toml_number(s.model_layer_rock[k].mean));
      sd.push_back(toml_number(s.model_layer_rock[k].sd));
    }
    o += fmt::format("lab_layer = [{}]\nmodel_layer = [{}]\nmodel_layer_sd = [{}]\n", fmt::join(lab, ", "),
                     fmt::join(mean, ", "), fmt::join(sd, ", "));
    o += fmt::format("lab_deep_share = {}\nmodel_deep_share = {}\nmodel_deep_share_sd = {}\n",
                     toml_number(s.lab_deep_share), toml_number(s.model_deep_share.mean),
                     toml_number(s.model_deep_share.sd));
  }
  return o;
}

// One [[realization]] table per result file scored.
std::string realizations_toml(const Score& s) {
  std::string o;
  for (const auto& r : s.realizations) {
    o += "\n[[realization]]\n";
    o += fmt::format("file = {}\nseed = {}\nscene_hash = {}\nsnapshot = {}\ntime_s = {}\nC_mean_abs_error_pp = {}\n",
                     toml_string(r.path), r.seed, toml_string(r.scene_hash), r.snapshot, toml_number(r.time_s),
                     toml_number(r.mae_pp));
    o += fmt::format("at_rest = {}\nmoving_mass_kg = {}\nin_flight_mass_kg = {}\nmax_speed_m_s = {}\n",
                     r.state.at_rest, toml_number(r.state.moving_mass), toml_number(r.state.in_flight_mass),
                     toml_number(r.state.max_speed));
  }
  return o;
}

}  // namespace

std::string score_toml(const Score& s, const std::string& software, const std::string& command,
                       const std::string& created, const std::string& lab_h5) {
  std::string o = "# pastemix score: model mixing maps vs the lab's cut-block grid (thesis ch. 3).\n"
                  "# C in percent; errors in percentage points (pp) = model ensemble mean - lab.\n";
  o += fmt::format("software = {}\ncommand = {}\ncreated = {}\nlab_h5 = {}\ncase = {}\n", toml_string(software),
                   toml_string(command), toml_string(created), toml_string(lab_h5), s.case_id);
  o += fmt::format("K_kg_m3 = {}\nK_source = {}\nrealizations = {}\n\n", toml_number(s.K), toml_string(s.K_source),
                   s.realizations.size());
  o += headline_toml(s);
  o += score_section_toml(s);
  o += centre_toml(s);
  o += cone_toml(s);
  o += rock_toml(s);
  o += realizations_toml(s);
  return o;
}

}  // namespace pastemix::analysis
