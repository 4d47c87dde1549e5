// SPDX-License-Identifier: MIT
// `pastemix maps RESULT.h5` (a result's mixing map on the lab's block grid) and
// `pastemix score RESULT.h5 [RESULT2.h5 ...] --lab CASE` (an ensemble scored against the lab's grid).
// Both read and check every input first, then write through one StagedOutput: a bad input writes nothing.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "analysis/maps/maps_h5.h"
#include "analysis/maps/mixing_map.h"
#include "analysis/maps/motion.h"
#include "analysis/maps/result_file.h"
#include "analysis/pile/repose_angle.h"
#include "analysis/plot.h"
#include "analysis/score/lab_case.h"
#include "analysis/score/realization_check.h"
#include "analysis/score/score.h"
#include "app/commands.h"
#include "base/error.h"
#include "base/h5.h"
#include "base/stats.h"
#include "base/staged_output.h"
#include "lab/run_info.h"

namespace pastemix::app {

namespace {

namespace fs = std::filesystem;
using namespace pastemix::analysis;

// Options shared by both commands. Grid defaults = the chapter-3 grid (BlockLayout's defaults).
struct CommonOpts {
  std::vector<double> origin{0.0, 0.0}, block_size{0.05, 0.055};  // m
  std::vector<int> blocks{4, 3};
  int layers = 3;
  double layer_thickness = 0.03;  // m
  std::string above_surface = "layer1";
  std::optional<double> surface_z, paste_density, solids, rock_density, K;
  std::optional<int> snapshot, lab_case;
  double rho_s = 2710.0, e_f = 0.6;
  double no_rock_below_g = 1e3 * kLabMassResolution;  // g
  double moving_speed = 0.01, moving_mass_g = 1.0;    // m/s, g: the at-rest limits (maps/motion.h)
  bool allow_moving = false;
  std::string lab_h5 = "out/lab/lab.h5", out;
  std::vector<std::string> results;
};

void add_common(CLI::App* cmd, CommonOpts& o) {
  cmd->add_option("--origin", o.origin, "grid corner (x, y) of block i = 1, j = 1, m")->delimiter(',')->expected(2)
      ->capture_default_str();
  cmd->add_option("--block-size", o.block_size, "block size along x (i) and y (j), m")->delimiter(',')->expected(2)
      ->capture_default_str();
  cmd->add_option("--blocks", o.blocks, "block counts along x (i) and y (j)")->delimiter(',')->expected(2)
      ->capture_default_str();
  cmd->add_option("--layers", o.layers, "layers, k = 1 (top) ..")->capture_default_str();
  cmd->add_option("--layer-thickness", o.layer_thickness, "layer thickness, m")->capture_default_str();
  cmd->add_option("--above-surface", o.above_surface,
                  "where rock above the final surface counts: layer1 (in the block under it, as the lab cut the "
                  "unmixed cone) or none (in no block)")
      ->check(CLI::IsMember({"layer1", "none"}))
      ->capture_default_str();
  cmd->add_option("--surface-z", o.surface_z, "final free-surface height, m (default: the file's fluid_surface_z)");
  cmd->add_option("--paste-density", o.paste_density, "paste density, kg/m3 (default: the file's fluid_density)");
  cmd->add_option("--solids", o.solids, "paste solids mass fraction, 0..1 (default: fluid_solids_fraction)");
  cmd->add_option("--rock-density", o.rock_density, "rock density for every particle, kg/m3 (default: "
                                                    "/material_density)");
  cmd->add_option("--snapshot", o.snapshot, "snapshot index (default: the last one)");
  cmd->add_option("--K", o.K, "K = rho_wr/n_wr of eq. 3.8, kg/m3 (default: the lab case's)");
  cmd->add_option("--rho-s", o.rho_s, "tailings particle density for S, kg/m3")->capture_default_str();
  cmd->add_option("--e-f", o.e_f, "final void ratio of the dried paste for S")->capture_default_str();
  cmd->add_option("--lab-h5", o.lab_h5, "lab.h5 from `pastemix lab reduce`")->capture_default_str();
  cmd->add_option("--moving-speed", o.moving_speed, "a particle faster than this is moving, m/s")->capture_default_str();
  cmd->add_option("--moving-mass", o.moving_mass_g, "a state with more moving rock is not at rest, g")
      ->capture_default_str();
  cmd->add_flag("--allow-moving", o.allow_moving,
                "map a state that is not at rest (an unfinished pour), marked as such in every output");
}

// The state's motion, printed; a state not at rest is refused (exit 2) unless --allow-moving.
Motion checked_motion(const ResultSnapshot& r, const CommonOpts& o) {
  if (!(o.moving_speed > 0.0) || !std::isfinite(o.moving_speed))
    throw InputError("--moving-speed", 0, "", "must be positive (m/s)");
  if (!(o.moving_mass_g >= 0.0) || !std::isfinite(o.moving_mass_g))
    throw InputError("--moving-mass", 0, "", "must be >= 0 (g)");
  const Motion m = motion_of(r, {o.moving_speed, 1e-3 * o.moving_mass_g});
  fmt::print("{}: {}", r.path, m.line(r));
  if (!m.at_rest() && !o.allow_moving) throw InputError(r.path, 0, "", m.refusal(r));
  if (!m.at_rest()) fmt::print("{}: --allow-moving: mapping an UNFINISHED state (not at rest); every output says so\n", r.path);
  return m;
}

BlockLayout layout_of(const CommonOpts& o) {
  auto positive = [](double v, const char* opt) {
    if (!(v > 0.0) || !std::isfinite(v)) throw InputError(opt, 0, "", fmt::format("must be positive (m), got {}", v));
  };
  BlockLayout L;
  for (double v : o.origin)
    if (!std::isfinite(v)) throw InputError("--origin", 0, "", "must be finite (m)");
  for (double v : o.block_size) positive(v, "--block-size");
  positive(o.layer_thickness, "--layer-thickness");
  for (int n : o.blocks)
    if (n < 1 || n > 1000) throw InputError("--blocks", 0, "", fmt::format("counts must be 1..1000, got {}", n));
  if (o.layers < 1 || o.layers > 1000) throw InputError("--layers", 0, "", "must be 1..1000");
  L.origin = {o.origin[0], o.origin[1]};
  L.size = {o.block_size[0], o.block_size[1]};
  L.count = {o.blocks[0], o.blocks[1]};
  L.layers = o.layers;
  L.layer_thickness = o.layer_thickness;
  L.top_open = o.above_surface == "layer1";
  return L;
}

StateMark state_of(const Motion& m) {
  return {m.at_rest(), m.known, m.moving_mass, m.in_flight_mass, m.max_speed, m.limits.speed, m.limits.mass_limit};
}

ResultOverrides overrides_of(const CommonOpts& o) {
  auto check = [](const std::optional<double>& v, const char* opt, bool positive) {
    if (v && (!std::isfinite(*v) || (positive && !(*v > 0.0))))
      throw InputError(opt, 0, "", fmt::format("must be {} , got {}", positive ? "positive" : "finite", *v));
  };
  check(o.surface_z, "--surface-z", false);
  check(o.paste_density, "--paste-density", true);
  check(o.solids, "--solids", true);
  check(o.rock_density, "--rock-density", true);
  if (o.solids && *o.solids > 1.0)
    throw InputError("--solids", 0, "", fmt::format("a mass fraction in (0, 1] (e.g. 0.75), got {}", *o.solids));
  if (!(o.rho_s > 0.0) || !std::isfinite(o.rho_s)) throw InputError("--rho-s", 0, "", "must be positive (kg/m3)");
  if (!(o.e_f >= 0.0) || !std::isfinite(o.e_f)) throw InputError("--e-f", 0, "", "must be >= 0");
  if (o.K && (!(*o.K > 0.0) || !std::isfinite(*o.K))) throw InputError("--K", 0, "", "must be positive (kg/m3)");
  return {o.surface_z, o.paste_density, o.solids, o.rock_density, o.snapshot};
}

MixingInputs inputs_for(const BlockLayout& L, const ResultSnapshot& r, double K, const CommonOpts& o) {
  MixingInputs in = mixing_inputs(r, L);
  in.K = K;
  in.rho_s = o.rho_s;
  in.e_f = o.e_f;
  return in;
}

std::string command_line(const char* name, const CommonOpts& o) {
  std::string c = fmt::format("pastemix {} {}", name, fmt::join(o.results, " "));
  if (o.lab_case) c += fmt::format(" --lab {} --lab-h5 {}", *o.lab_case, o.lab_h5);
  c += fmt::format(" --out {}", o.out);
  return c;
}

// Runs the plotting script into a scratch folder under `out` and stages the PNGs it made.
void stage_pngs(StagedOutput& staged, const fs::path& out, const std::vector<std::string>& args_before_dir,
                const std::vector<std::string>& names) {
  const fs::path tmp = out / fmt::format(".plots.partial-{}", static_cast<long>(::getpid()));
  fs::create_directories(tmp);
  std::vector<std::string> args = args_before_dir;
  args.push_back(tmp.string());
  const PlotResult p = run_plot_script(args);
  if (!p.ok) fmt::print("warning: {}\n", p.warning);
  for (const auto& n : names) {
    if (!p.ok) break;
    if (!fs::exists(tmp / n)) {
      fmt::print("warning: the plotting script did not write {}\n", n);
      continue;
    }
    fs::rename(tmp / n, staged.path(out / n));
  }
  std::error_code ec;
  fs::remove_all(tmp, ec);
}

void run_maps(const CommonOpts& o) {
  const BlockLayout L = layout_of(o);
  const ResultOverrides over = overrides_of(o);
  const ResultSnapshot r = read_result(o.results.front(), over);
  const Motion motion = checked_motion(r, o);
  double K = std::nan("");
  std::string K_source;
  if (o.K) {
    K = *o.K;
    K_source = "command line --K";
  } else if (o.lab_case) {
    const LabCase lc = read_lab_case(o.lab_h5, *o.lab_case, false);
    K = lc.K;
    K_source = lc.K_source;
    if (!lc.has_grid)
      fmt::print("note: case {} has no lab block grid in {} (reserved for blind validation); mapping anyway\n",
                 *o.lab_case, o.lab_h5);
  }
  const MixingInputs in = inputs_for(L, r, K, o);
  const MixingMap m = mixing_map(in, ParticleView{r.position, r.radius, r.density});
  fmt::print("{}", maps_table(m, r, in, K_source));

  const fs::path out = o.out;
  StagedOutput staged;
  const fs::path h5 = staged.path(out / "maps.h5");
  write_maps_h5(h5, m, in, r, {lab::software_version(), command_line("maps", o), lab::utc_now(), K_source},
                state_of(motion));
  stage_pngs(staged, out, {"maps", h5.string()}, {"maps.png"});
  staged.commit();
  for (const auto& p : staged.final_paths()) fmt::print("wrote {}\n", p.string());
}

void run_score(const CommonOpts& o) {
  const BlockLayout L = layout_of(o);
  if (L.count[0] != 4 || L.count[1] != 3 || L.layers != 3)
    throw InputError("--blocks", 0, "", "scoring compares with the lab's 4 x 3 blocks in 3 layers; keep that grid");
  const ResultOverrides over = overrides_of(o);
  if (!(o.no_rock_below_g >= 0.0) || !std::isfinite(o.no_rock_below_g))
    throw InputError("--no-rock-below", 0, "", "must be >= 0 (g)");
  const LabCase lc = read_lab_case(o.lab_h5, *o.lab_case, true);
  const double K = o.K ? *o.K : lc.K;
  LabCase lab = lc;
  if (o.K) {
    lab.K = *o.K;
    lab.K_source = "command line --K (the lab grid's S classes keep the lab's own K)";
  }
  std::vector<ResultSnapshot> results;
  for (const auto& path : o.results) results.push_back(read_result(path, over));
  analysis::check_realizations(lc, results);
  std::vector<MixingMap> maps;
  std::vector<Realization> reals;
  for (const auto& r : results) {
    for (const auto& n : r.notes) fmt::print("note: {}: {}\n", r.path, n);
    const Motion motion = checked_motion(r, o);
    const MixingInputs in = inputs_for(L, r, K, o);
    maps.push_back(mixing_map(in, ParticleView{r.position, r.radius, r.density}));
    reals.push_back({r.path, r.seed, r.scene_hash, r.snapshot, r.time_s, 0.0, state_of(motion)});
  }
  const Score s = score_against_lab(lab, maps, reals, 1e-3 * o.no_rock_below_g);
  fmt::print("{}", score_table(s));

  const fs::path out = o.out;
  StagedOutput staged;
  const fs::path csv = staged.path(out / "score.csv");
  write_file_synced(csv, score_csv(s));
  staged.write_text(out / "score.toml",
                    score_toml(s, lab::software_version(), command_line("score", o), lab::utc_now(), o.lab_h5));
  const std::string title = fmt::format("Mixing case {}: lab vs model ({} realization{}){}", s.case_id,
                                        s.realizations.size(), s.realizations.size() == 1 ? "" : "s",
                                        s.all_at_rest() ? "" : " - NOT AT REST (--allow-moving)");
  stage_pngs(staged, out, {"score", csv.string(), std::to_string(s.realizations.size()), title},
             {"score_layer_1.png", "score_layer_2.png", "score_layer_3.png"});
  staged.commit();
  for (const auto& p : staged.final_paths()) fmt::print("wrote {}\n", p.string());
}

// `pastemix repose RESULT.h5 ...`: the repose angle (analysis/pile/repose_angle.h) of the last snapshot of
// each result file, and their mean and sd when there are several (seeded repeats). It measures whatever the
// file holds: whether the pile had finished (funnel empty, at rest) is checked by the run (the sweep's QoI),
// not here.
struct ReposeOpts {
  std::vector<std::string> results;
  analysis::ReposeOptions o;
  std::vector<double> axis, flank;
};

void run_repose(const ReposeOpts& opts) {
  analysis::ReposeOptions o = opts.o;
  if (!opts.axis.empty()) o.axis_xy = std::array<double, 2>{opts.axis[0], opts.axis[1]};
  if (!opts.flank.empty()) {
    if (!(0 <= opts.flank[0] && opts.flank[0] < opts.flank[1] && opts.flank[1] <= 1))
      throw InputError("", 0, "--flank", "needs 0 <= lo < hi <= 1 (fractions of the pile height)");
    o.flank_lo = opts.flank[0];
    o.flank_hi = opts.flank[1];
  }
  std::vector<double> angles;
  std::string method;
  for (const auto& file : opts.results) {
    const H5Reader h5(file);
    const std::string g = fmt::format("/snapshots/{:06d}", analysis::snapshot_index(h5, file));
    const auto pos = h5.read_doubles(g + "/position");
    const auto radius = h5.read_doubles(g + "/radius");
    if (pos.size() != 3 * radius.size())
      throw InputError(file, 0, "dataset '" + g + "/position'", "expected N x 3 with N = the radius count");
    std::vector<Vec3> x(radius.size());
    for (std::size_t a = 0; a < x.size(); ++a) x[a] = {pos[3 * a], pos[3 * a + 1], pos[3 * a + 2]};
    const auto r = analysis::measure_repose_angle(x, radius, o);
    const std::int64_t seed = h5.has_attribute("/", "seed") ? h5.attribute_int("/", "seed") : -1;
    const double t = h5.has_attribute(g, "time_s") ? h5.attribute_double(g, "time_s") : std::nan("");
    fmt::print("{}: seed {}, t = {:g} s, {} spheres: angle {:.2f} deg (sd over {} sectors {:.2f}), height {:.1f} mm, "
               "diameter {:.1f} mm\n", file, seed, t, radius.size(), r.angle_deg, r.sectors_used, r.sd_deg,
               r.height * 1e3, r.diameter * 1e3);
    angles.push_back(r.angle_deg);
    method = r.method;
  }
  if (angles.size() > 1) {
    const auto st = summarize(angles);
    fmt::print("mean over {} files: {:.2f} +- {:.2f} deg (sd; standard error {:.2f})\n", st.n, st.mean, st.sd,
               st.sd / std::sqrt(static_cast<double>(st.n)));
  }
  fmt::print("method: {}\n", method);
}

}  // namespace

void register_analysis_commands(CLI::App& app) {
  // One options struct per subcommand: CLI11's default_val writes into the bound variable at registration.
  auto o = std::make_shared<CommonOpts>();
  auto* maps = app.add_subcommand("maps", "Mixing map (C, S per block) of a result file on the lab's block grid");
  maps->add_option("RESULT", o->results, "result file (HDF5) of `pastemix run`")->required()->expected(1);
  maps->add_option("--out", o->out, "output folder")->default_val("out/maps");
  maps->add_option("--lab", o->lab_case, "mixing case whose K (eq. 3.8) to use, read from --lab-h5");
  add_common(maps, *o);
  maps->callback([o] { run_maps(*o); });

  o = std::make_shared<CommonOpts>();
  auto* score = app.add_subcommand("score", "Score one or more results (an ensemble) against a lab case's grid");
  score->add_option("RESULT", o->results, "result files (HDF5), one per seeded realization")->required();
  score->add_option("--lab", o->lab_case, "mixing case to score against (1-5 have lab grids)")->required();
  score->add_option("--out", o->out, "output folder")->default_val("out/score");
  score->add_option("--no-rock-below", o->no_rock_below_g,
                    "for the S classes, model blocks with less rock (g) count as 'no rock' (the lab weighed to 0.1 g)")
      ->capture_default_str();
  add_common(score, *o);
  score->callback([o] { run_score(*o); });

  auto ro = std::make_shared<ReposeOpts>();
  auto* rep = app.add_subcommand("repose", "Repose angle of the pile in the last snapshot of result files");
  rep->add_option("RESULT", ro->results, "result files (HDF5): a run's, or a sweep's --save states")->required();
  rep->add_option("--axis", ro->axis, "pile axis x y (m); default the mass centre")->expected(2);
  rep->add_option("--sectors", ro->o.sectors, "azimuthal sectors")->capture_default_str()->check(CLI::Range(3, 360));
  rep->add_option("--bin", ro->o.bin, "radial bin width (m); 0 = 2 mean diameters")->capture_default_str();
  rep->add_option("--flank", ro->flank, "flank band lo hi, fractions of the pile height (default 0.15 0.75)")
      ->expected(2);
  rep->add_option("--base-z", ro->o.base_z, "floor height (m)")->capture_default_str();
  rep->callback([ro] { run_repose(*ro); });
}

}  // namespace pastemix::app
