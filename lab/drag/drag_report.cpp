// SPDX-License-Identifier: MIT
#include "lab/drag/drag_report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>
#include <map>

#include <fmt/format.h>

#include "base/error.h"
#include "base/staged_output.h"
#include "base/units.h"
#include "lab/drag/drag_plots.h"

namespace pastemix::lab::drag {

namespace {

using pastemix::drag::curve_info;

std::string num(double x) { return std::isfinite(x) ? fmt::format("{:.6g}", x) : std::string("nan"); }
// Shortest text that reads back to the same double: coefficients the engine must reproduce exactly.
// Always with a '.' or an exponent so TOML reads a float (0 would be an integer).
std::string exact(double x) {
  if (!std::isfinite(x)) return "nan";
  std::string s = fmt::format("{}", x);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

std::string score_line(const std::string& tag, const Score& s) {
  return fmt::format("{:<44} {:>4} {:>8.1f} {:>8.1f} {:>6} {:>8.1f} {:>7} {:>9}\n", tag, s.n, 100 * s.mean_abs,
                     100 * s.median_abs, s.above_20, 100 * s.max_abs, s.trapped, s.suspended);
}

const char* kSources = "valentik_whitmore_1965_spheres.csv; valentik_whitmore_1965_suspensions.csv";

std::string method_of(const Candidate& c) {
  return fmt::format("Ceres AutoDiff fit of {} ({}), one residual per sphere, {} loss; sd from ceres::Covariance "
                     "scaled by the residual variance",
                     c.options.target == FitTarget::log_cd ? "ln Cd(Re') to eq. 4.17/4.18"
                                                          : "ln v_terminal through the implicit force balance (4.9)",
                     curve_info(c.family).formula, c.options.loss == FitLoss::cauchy ? "Cauchy" : "squared");
}

void score_toml(std::string& out, const std::string& key, const Score& s) {
  out += fmt::format("[{}]\nlabel = {}\nn = {}\nmean_abs_rel_error = {}\nmedian_abs_rel_error = {}\n"
                     "above_20_percent = {}\nmax_abs_rel_error = {}\ntrapped = {}\nsuspended = {}\n\n",
                     key, toml_string(s.label), s.n, num(s.mean_abs), num(s.median_abs), s.above_20,
                     num(s.max_abs), s.trapped, s.suspended);
}

}  // namespace

std::string score_table(const DragFitResult& r) {
  const auto& b = r.best();
  std::string out = fmt::format(
      "Re'/Cd recomputed vs printed (Table 4.3, {} spheres): max |err| Re' {:.2f} % (row {}), Cd {:.2f} % (row {})\n\n",
      r.data.spheres.size(), 100 * r.data.max_re_error, r.data.max_re_row, 100 * r.data.max_cd_error,
      r.data.max_cd_row);
  out += fmt::format("Terminal velocity |v_pred/v_meas - 1| (%)\n{:<44} {:>4} {:>8} {:>8} {:>6} {:>8} {:>7} {:>9}\n",
                     "curve", "n", "mean", "median", ">20%", "max", "trapped", "suspended");
  out += score_line("(a) published 4.19", r.published_score);
  out += score_line(fmt::format("(b) {} in-sample", b.name()), b.in_sample_score);
  out += score_line(fmt::format("(c) {} LOSO", b.name()), b.loso_score);
  out += score_line("(d) thesis model, Table A.1", r.thesis_score);
  out += "\nLike for like with (d), on the Table 4.3 spheres that A.1 reports:\n";
  out += score_line("(a) published 4.19, A.1 spheres", r.published_on_thesis_spheres);
  out += score_line(fmt::format("(c) {} LOSO, A.1 spheres", b.name()), r.loso_on_thesis_spheres);
  const auto& chk = r.published_vs_thesis_model;
  out += fmt::format("Solver check: published 4.19 through this force balance vs the thesis f-EDEM speeds (A.1), {} "
                     "spheres: median |diff| {:.2f} %, mean {:.2f} %, max {:.1f} % (at the trap, where the DEM "
                     "chatters)\n",
                     chk.n, 100 * chk.median_abs, 100 * chk.mean_abs, 100 * chk.max_abs);
  out += "\nAll fitted candidates (chosen: lowest LOSO mean):\n";
  for (const auto& c : r.candidates) {
    out += score_line(c.name() + " in-sample", c.in_sample_score);
    out += score_line(c.name() + " LOSO", c.loso_score);
  }
  const auto& info = curve_info(b.family);
  out += fmt::format("\nChosen curve: {} ({}), fitted to {}:\n", info.name, info.formula, to_string(b.options.target));
  for (int i = 0; i < info.n_coefficients; ++i)
    out += b.in_sample.at_bound[i]
               ? fmt::format("  {} = {}  (on its bound: held there, no sd)\n", info.coefficient_names[i],
                             num(b.in_sample.curve.coefficients[i]))
               : fmt::format("  {} = {} +- {}\n", info.coefficient_names[i], num(b.in_sample.curve.coefficients[i]),
                             num(b.in_sample.sd[i]));
  out += fmt::format("  rms residual {} (ln units), Ceres: {}\n", num(b.in_sample.rms), b.in_sample.brief_report);
  out += "(d) trapped = thesis model speed with Re' in 0.8-1.25, i.e. stuck at the 4.19 jump (v ~ sqrt(tau_y/rho_f)).\n";
  return out;
}

std::string spheres_csv(const DragFitResult& r) {
  std::map<int, double> thesis;  // Table 4.3 row -> thesis model speed
  for (const auto& row : r.thesis_rows)
    if (row.spheres_row_id && row.v_model) thesis[*row.spheres_row_id] = *row.v_model;
  const auto& b = r.best();
  std::string out =
      "row_id,suspension,diameter_m,sphere_density_kg_m3,v_measured_m_s,Re_prime,Cd,Re_prime_printed,Cd_printed,"
      "v_published_m_s,published_outcome,v_fit_in_sample_m_s,v_fit_loso_m_s,loso_outcome,v_thesis_model_m_s\n";
  for (std::size_t i = 0; i < r.data.spheres.size(); ++i) {
    const auto& s = r.data.spheres[i];
    auto it = thesis.find(s.row_id);
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", s.row_id, s.suspension, num(s.sphere.d),
                       num(s.sphere.rho_p), num(s.v), num(s.re), num(s.cd), num(s.re_printed), num(s.cd_printed),
                       num(r.published[i].v_predicted), to_string(r.published[i].outcome),
                       num(b.in_sample_predictions[i].v_predicted), num(b.loso_predictions[i].v_predicted),
                       to_string(b.loso_predictions[i].outcome), it == thesis.end() ? "" : num(it->second));
  }
  return out;
}

std::string summary_csv(const DragFitResult& r) {
  std::string out = "row,label,n,mean_abs_rel_error,median_abs_rel_error,above_20_percent,max_abs_rel_error,"
                    "trapped,suspended,chosen\n";
  auto line = [&](const std::string& row, const Score& s, bool chosen) {
    out += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", row, s.label, s.n, num(s.mean_abs), num(s.median_abs),
                       s.above_20, num(s.max_abs), s.trapped, s.suspended, chosen ? 1 : 0);
  };
  line("a", r.published_score, false);
  line("b", r.best().in_sample_score, true);
  line("c", r.best().loso_score, true);
  line("d", r.thesis_score, false);
  for (std::size_t i = 0; i < r.candidates.size(); ++i) {
    line("candidate", r.candidates[i].in_sample_score, static_cast<int>(i) == r.chosen);
    line("candidate", r.candidates[i].loso_score, static_cast<int>(i) == r.chosen);
  }
  return out;
}

// The data's median yield number: where curves that depend on Y are sampled for the Cd(Re') plot.
double median_yield_number(const DragFitResult& r) {
  std::vector<double> y;
  for (const auto& s : r.data.spheres) y.push_back(pastemix::drag::yield_number(s.sphere, units::g));
  std::sort(y.begin(), y.end());
  return y.empty() ? 0.0 : y[y.size() / 2];
}

// Curves that depend on the yield number Y are sampled at the data's median Y (the CSV's y_sampled column).
std::string curves_csv(const DragFitResult& r) {
  const double y = median_yield_number(r);
  std::string out = "Re_prime,y_sampled,published_4_19,stokes";
  for (const auto& c : r.candidates) out += fmt::format(",{}", c.name());
  out += "\n";
  for (int i = 0; i <= 700; ++i) {
    const double re = std::pow(10.0, -3.0 + 7.0 * i / 700.0);
    out += fmt::format("{},{},{},{}", num(re), num(y), num(DragCurve{pastemix::drag::CurveId::published_4_19, {}}.cd(re, y)),
                       num(24.0 / re));
    for (const auto& c : r.candidates) out += fmt::format(",{}", num(c.in_sample.curve.cd(re, y)));
    out += "\n";
  }
  return out;
}

std::string drag_curve_toml(const DragFitResult& r) {
  const auto& b = r.best();
  const auto& info = curve_info(b.family);
  std::string out = "# Drag curve Cd(Re') for a sphere in a Bingham fluid, written by `pastemix lab drag-fit`.\n"
                    "# The engine evaluates drag_curve.chosen by name (base/drag_curves.h) with these coefficients.\n"
                    "# Re' = rho_f v^2 / (tau_y + eta_B v / d) (4.18); drag F = (pi d/2)^2 tau_y + Cd rho_f v^2 pi d^2/8.\n\n";
  out += fmt::format("[drag_curve]\nchosen = {}\nformula = {}\ntarget = {}\nloss = {}\n", toml_string(std::string(info.name)),
                     toml_string(std::string(info.formula)), toml_string(to_string(b.options.target)),
                     toml_string(b.options.loss == FitLoss::cauchy ? "cauchy" : "none"));
  out += fmt::format("selection = {}\n", toml_string("lowest leave-one-suspension-out mean |v_pred/v - 1| among the "
                                                     "fitted candidates (family x target)"));
  double re_min = INFINITY, re_max = 0.0;
  for (const auto& s : r.data.spheres) re_min = std::min(re_min, s.re), re_max = std::max(re_max, s.re);
  out += fmt::format("# Fitted over this Re' range only; below it the curve is an extrapolation (e.g. k = 0 drops\n"
                     "# the Stokes 1/Re' term, which a Newtonian fluid at Re' << 1 would need).\n"
                     "fitted_re_prime_range = [{}, {}]\n",
                     exact(re_min), exact(re_max));
  double y_min = INFINITY, y_max = 0.0;
  for (const auto& s : r.data.spheres) {
    const double y = pastemix::drag::yield_number(s.sphere, units::g);
    y_min = std::min(y_min, y), y_max = std::max(y_max, y);
  }
  out += fmt::format("# Y = tau_y / (g d (rho_p - rho_f)), per sphere; an input of curves with uses_yield_number.\n"
                     "uses_yield_number = {}\nfitted_yield_number_range = [{}, {}]\n",
                     info.uses_yield_number, exact(y_min), exact(y_max));
  out += fmt::format("dataset = {}\nsource = {}\nn = {}\ng_m_s2 = {}\n\n", toml_string(r.dataset_dir.string()),
                     toml_string(kSources), b.in_sample.n, num(units::g));
  for (const auto& p : drag_curve_parameters(r)) {
    if (!p.text.empty()) continue;
    out += fmt::format("[{}]\nvalue = {}\n", p.key, exact(p.value));
    if (std::isfinite(p.sd)) out += fmt::format("sd = {}\n", exact(p.sd));
    out += fmt::format("n = {}\nunit = {}\nprovenance = {}\nmethod = {}\nsource = {}\n", p.n, toml_string(p.unit),
                       toml_string(to_string(p.provenance)), toml_string(p.method), toml_string(p.source));
    if (!p.note.empty()) out += fmt::format("note = {}\n", toml_string(p.note));
    out += "\n";
  }
  out += fmt::format("[drag_curve.{}_fit]\ncoefficient_names = [", info.name);
  for (int i = 0; i < info.n_coefficients; ++i)
    out += fmt::format("{}{}", i ? ", " : "", toml_string(std::string(info.coefficient_names[i])));
  out += "]\ncovariance = [";
  if (b.in_sample.covariance_ok)
    for (int i = 0; i < info.n_coefficients; ++i) {
      out += i ? ",\n  [" : "\n  [";
      for (int j = 0; j < info.n_coefficients; ++j) out += (j ? ", " : "") + exact(b.in_sample.covariance(i, j));
      out += "]";
    }
  out += fmt::format("]\ncovariance_ok = {}\nrms_ln_residual = {}\nceres = {}\n\n", b.in_sample.covariance_ok,
                     num(b.in_sample.rms), toml_string(b.in_sample.brief_report));
  score_toml(out, "drag_curve.scores.a_published_4_19", r.published_score);
  score_toml(out, "drag_curve.scores.b_in_sample", b.in_sample_score);
  score_toml(out, "drag_curve.scores.c_leave_one_suspension_out", b.loso_score);
  score_toml(out, "drag_curve.scores.d_thesis_model", r.thesis_score);
  return out;
}

std::vector<Parameter> candidate_parameters(const Candidate& b, const std::string& choice_method,
                                            const std::string& choice_note, const std::string& sources) {
  const auto& info = curve_info(b.family);
  std::vector<Parameter> out;
  Parameter chosen;
  chosen.key = "drag_curve.chosen";
  chosen.text = std::string(info.name);
  chosen.n = b.in_sample.n;
  chosen.unit = std::string(1, '-');
  chosen.method = choice_method;
  chosen.provenance = Provenance::fitted;
  chosen.source = sources;
  chosen.note = choice_note;
  out.push_back(chosen);
  for (int i = 0; i < info.n_coefficients; ++i) {
    Parameter p;
    p.key = fmt::format("drag_curve.{}.{}", info.name, info.coefficient_names[i]);
    p.value = b.in_sample.curve.coefficients[i];
    p.sd = b.in_sample.sd[i];
    p.n = b.in_sample.n;
    p.unit = std::string(1, '-');
    p.method = method_of(b);
    p.provenance = Provenance::fitted;
    p.source = sources;
    if (b.in_sample.at_bound[i]) p.note = "ended on its admissible bound (an active constraint): held there, so no sd; the covariance is that of the other coefficients";
    out.push_back(p);
  }
  return out;
}

std::vector<Parameter> drag_curve_parameters(const DragFitResult& r) {
  const auto& b = r.best();
  return candidate_parameters(
      b, "lowest leave-one-suspension-out mean |v_pred/v - 1| among fitted families x targets",
      fmt::format("LOSO: mean {:.1f} %, median {:.1f} %; published 4.19: mean {:.1f} %, median {:.1f} %",
                  100 * b.loso_score.mean_abs, 100 * b.loso_score.median_abs, 100 * r.published_score.mean_abs,
                  100 * r.published_score.median_abs),
      kSources);
}

std::vector<Parameter> drag_curve_parameters(const std::filesystem::path& dataset_dir) {
  return drag_curve_parameters(run_drag_fit(dataset_dir, units::g));
}

DragFitOutputs write_drag_fit_outputs(const DragFitResult& r, const std::filesystem::path& out_dir, bool plots) {
  DragFitOutputs result;
  StagedOutput out;
  // The plot script reads the staged (temporary) CSVs, so keep their temporary paths.
  auto stage = [&](const std::filesystem::path& final_path, const std::string& text) {
    return out.write_text(final_path, text);
  };
  const auto spheres = stage(out_dir / "drag_fit_spheres.csv", spheres_csv(r));
  const auto curves = stage(out_dir / "drag_curves_sampled.csv", curves_csv(r));
  stage(out_dir / "drag_fit_summary.csv", summary_csv(r));
  stage(out_dir / "drag_curve.toml", drag_curve_toml(r));
  stage(out_dir / "drag_fit_table.txt", score_table(r));
  result.plot_message = plots ? make_drag_plots(out, r, spheres, curves, out_dir) : "plots not requested";
  out.commit();
  result.written = out.final_paths();
  return result;
}

}  // namespace pastemix::lab::drag
