// SPDX-License-Identifier: MIT
#include "app/study/predict_rheology.h"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "analysis/maps/mixing_map.h"
#include "analysis/maps/motion.h"
#include "analysis/maps/result_file.h"
#include "analysis/score/lab_case.h"
#include "analysis/score/realization_check.h"
#include "analysis/score/score.h"
#include "app/study/calibrate_rheology.h"
#include "app/study/run_cache.h"
#include "app/study/tasks.h"
#include "base/error.h"

namespace pastemix::app::study {

namespace fs = std::filesystem;
namespace rh = lab::rheology;

const std::vector<std::string>& predict_quantity_names() {
  static const std::vector<std::string> n{"layer1_kg", "layer2_kg", "layer3_kg", "deep_share",
                                          "mixed_kg",  "unmixed_kg", "score_layers", "mae_pp"};
  return n;
}

namespace {

constexpr const char* kQoi = "predict rheology";

struct CaseInput {
  int case_id = 0;
  model::SceneDoc scene;
  double solids_fraction = 0.0;
  long seed0 = 0;
  std::optional<analysis::LabCase> lab;  // with its grid: the case is scored
};

// The map of a result file at rest (the maps' own test: a state not at rest fails the run).
struct Mapped {
  analysis::ResultSnapshot result;
  analysis::MixingMap map;
  analysis::Realization realization;
};

Mapped map_result(const fs::path& h5, const analysis::BlockLayout& layout, double K) {
  Mapped m;
  m.result = analysis::read_result(h5, {});
  const analysis::Motion motion = analysis::motion_of(m.result, {});
  if (!motion.at_rest()) throw RuntimeFailure(motion.refusal(m.result));
  analysis::MixingInputs in = analysis::mixing_inputs(m.result, layout);
  in.K = K;
  const auto& r = m.result;
  m.map = analysis::mixing_map(in, analysis::ParticleView{r.position, r.radius, r.density});
  analysis::StateMark state{true, motion.known, motion.moving_mass, motion.in_flight_mass, motion.max_speed,
                            motion.limits.speed, motion.limits.mass_limit};
  m.realization = {r.path, r.seed, r.scene_hash, r.snapshot, r.time_s, 0.0, state};
  return m;
}

// The quantities of one run (predict_quantity_names order).
std::vector<double> quantities(const fs::path& h5, const analysis::BlockLayout& layout,
                               const std::optional<analysis::LabCase>& lab) {
  const Mapped m = map_result(h5, layout, lab ? lab->K : std::nan(""));
  std::array<double, 3> layer{};
  double all = 0.0;
  for (int i = 1; i <= layout.count[0]; ++i)
    for (int j = 1; j <= layout.count[1]; ++j)
      for (int k = 1; k <= layout.layers; ++k) {
        const double rock = m.map.rock_mass[layout.index(i, j, k)];
        all += rock;
        if (k <= 3) layer[static_cast<std::size_t>(k - 1)] += rock;
      }
  const double deep = all > 0.0 ? (all - layer[0]) / all : 0.0;
  std::vector<double> q{layer[0], layer[1], layer[2], deep, m.map.mixed(), m.map.unmixed()};
  if (lab) {
    analysis::check_realizations(*lab, {m.result});
    const analysis::Score s = analysis::score_against_lab(*lab, {m.map}, {m.realization});
    q.push_back(s.layers_matched);
    q.push_back(s.mae_pp);
  }
  return q;
}

CaseInput read_case(int id, const PredictOptions& o) {
  const fs::path scene = o.scenes / fmt::format("mixing_case{}.toml", id);
  if (!fs::exists(scene))
    throw InputError(scene.string(), 0, "--cases", fmt::format("case {} has no scene (no such file)", id));
  CaseInput c{id, model::scene_with_overrides(scene, o.overrides, {}), 0.0, 0, std::nullopt};
  c.solids_fraction = scene_solids(c.scene);
  c.seed0 = o.seed0 ? *o.seed0 : scene_seed(c.scene);
  if (!o.lab_h5.empty()) {
    const analysis::LabCase lc = analysis::read_lab_case(o.lab_h5, id, false);
    if (lc.has_grid) {
      if (o.layout.count[0] != 4 || o.layout.count[1] != 3 || o.layout.layers != 3)
        throw InputError(o.lab_h5.string(), 0, fmt::format("case {}", id),
                         "has a lab grid: scoring needs the lab's 4 x 3 blocks in 3 layers");
      c.lab = lc;
    }
  }
  return c;
}

// The band's centre and sd, and the model (the store's anchor, the record's family).
void read_band(const PredictOptions& o, PredictResult& r) {
  r.model = rh::read_model(o.store.string());
  if (!o.calibration.empty()) {
    if (o.shape || o.shape_sd)
      throw InputError("--calibration", 0, "--shape", "give either a calibration record or --shape/--shape-sd");
    const rh::Calibration c = rh::read_calibration(o.calibration.string());
    r.model.family = c.family;
    r.model.shape = c.shape, r.model.shape_sd = c.sd;
    r.shape_source = fmt::format("{} (calibrated on case {})", o.calibration.string(), c.case_id);
  } else {
    if (!o.shape || !o.shape_sd)
      throw InputError("--calibration", 0, "", "give a calibration record (--calibration) or --shape and --shape-sd");
    r.model.shape = *o.shape, r.model.shape_sd = *o.shape_sd;
    r.shape_source = "--shape / --shape-sd";
  }
  const std::string where = o.calibration.empty() ? std::string("--shape") : o.calibration.string();
  if (!(r.model.shape_sd > 0.0) || !std::isfinite(r.model.shape_sd))
    throw InputError(where, 0, "sd", fmt::format("the band needs a positive, finite sd, got {}", r.model.shape_sd));
  r.prior = rh::prior(r.model.family, r.model.anchor);
  for (int k = -1; k <= 1; ++k)
    rh::check_shape(r.model.family, r.model.anchor, r.model.shape + k * r.model.shape_sd,
                    k == 0 ? where : fmt::format("{} (shape {} sd)", where, k < 0 ? "-" : "+"));
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void score_ensembles(PredictResult& r, const std::vector<CaseInput>& cases, const PredictOptions& o) {
  for (auto& g : r.groups) {
    if (!g.scored) continue;
    const CaseInput* c = nullptr;
    for (const auto& ci : cases) c = ci.case_id == g.case_id ? &ci : c;
    std::vector<analysis::MixingMap> maps;
    std::vector<analysis::Realization> reals;
    bool ok = true;
    for (const auto& run : g.runs) {
      const fs::path h5 = o.out / "runs" / (run.key + ".h5");
      ok = ok && run.failure.empty() && fs::exists(h5);  // a run from the ledger alone has no file here
      if (!ok) break;
      Mapped m = map_result(h5, o.layout, c->lab->K);
      maps.push_back(std::move(m.map));
      reals.push_back(std::move(m.realization));
    }
    if (!ok) continue;
    const analysis::Score s = analysis::score_against_lab(*c->lab, maps, reals);
    g.ensemble_layers_matched = s.layers_matched;
    g.ensemble_mae_pp = s.mae_pp;
  }
}

}  // namespace

PredictResult predict_rheology(const PredictOptions& o) {
  if (o.seeds < 1) throw InputError("", 0, "--seeds", "must be >= 1");
  if (o.jobs < 1) throw InputError("", 0, "--jobs", "must be >= 1");
  if (o.cases.empty()) throw InputError("", 0, "--cases", "give at least one mixing case");
  PredictResult r;
  read_band(o, r);
  if (!o.overrides.empty()) r.overrides_text = read_text(o.overrides);
  std::vector<CaseInput> cases;
  for (int id : o.cases) cases.push_back(read_case(id, o));

  const fs::path runs = o.out / "runs";
  fs::create_directories(runs);
  std::vector<Task> list;
  std::vector<model::SceneDoc> docs;  // one per task, alive while the tasks run
  std::vector<std::pair<std::size_t, std::size_t>> where;  // (group, run) of each task
  for (const auto& c : cases)
    for (int label = -1; label <= 1; ++label) {
      PredictGroup g;
      g.case_id = c.case_id, g.solids_fraction = c.solids_fraction, g.label = label;
      g.scored = c.lab.has_value();
      rh::Model m = r.model;
      m.shape = g.shape = r.model.shape + label * r.model.shape_sd;
      g.tau_y = rh::yield_stress(m, c.solids_fraction);
      g.eta_B = rh::plastic_viscosity(m, c.solids_fraction);
      g.density = rh::density(m.anchor, c.solids_fraction);
      const model::SceneDoc d = with_rheology(c.scene, g.tau_y, g.eta_B, g.density);
      for (int k = 0; k < o.seeds; ++k) {
        model::SceneDoc ds = d;
        ds.set("seed", std::to_string(c.seed0 + k));
        g.runs.push_back({c.seed0 + k, run_key(ds, kQoi), {}, "", false});
        docs.push_back(std::move(ds));
        where.emplace_back(r.groups.size(), static_cast<std::size_t>(k));
      }
      r.groups.push_back(std::move(g));
    }
  for (std::size_t i = 0; i < docs.size(); ++i) {
    const auto [gi, ri] = where[i];
    const PredictGroup& g = r.groups[gi];
    const std::optional<analysis::LabCase>* lab = nullptr;
    for (const auto& c : cases) lab = c.case_id == g.case_id ? &c.lab : lab;
    const std::string key = g.runs[ri].key;
    list.push_back({key, fmt::format("case {} {} = {:.6g} seed {}", g.case_id, r.prior.name, g.shape, g.runs[ri].seed),
                    [&o, &docs, i, runs, key, lab](From& from) {
                      RunRecord rec = run_kept(docs[i], runs, key, o.checkpoint_wall_s, o.resume_with, from);
                      rec.qoi = quantities(runs / (key + ".h5"), o.layout, *lab);
                      return rec;
                    }});
  }
  StudyIo io = study_io(o, kQoi);
  const auto index = index_by_key(list);
  if (!o.quiet)
    io.on_done = [&](const Task& t, const RunRecord& rec, From from) {
      if (rec.failed) {
        fmt::print(stderr, "  {}: FAILED: {}\n", t.what, rec.failure);
        return;
      }
      const auto& q = rec.qoi;
      std::string line = fmt::format("  {}: layers {:.2f} / {:.2f} / {:.2f} g, deep {:.1f} %, mixed {:.2f} g, "
                                     "unmixed {:.2f} g", t.what, 1e3 * q.at(0), 1e3 * q.at(1), 1e3 * q.at(2),
                                     100.0 * q.at(3), 1e3 * q.at(4), 1e3 * q.at(5));
      if (q.size() == kPredictScored) line += fmt::format(", score {:.0f}/3, MAE {:.2f} pp", q[6], q[7]);
      fmt::print(stderr, "{} ({})\n", line, to_string(from));
    };
  TaskCounts counts;
  const std::vector<Finished> done = run_tasks(list, io, counts);
  for (std::size_t i = 0; i < done.size(); ++i) {
    PredictGroup& g = r.groups[where[i].first];
    PredictRun& run = g.runs[where[i].second];
    const RunRecord& rec = done[i].outcome;
    run.computed = done[i].from == From::ran || done[i].from == From::resumed;
    if (rec.failed) {
      run.failure = rec.failure;
      continue;
    }
    const std::size_t want = g.scored ? kPredictScored : kPredictMaps;
    if (rec.qoi.size() != want)
      throw InputError(o.ledger ? o.ledger->path().string() : "", 0, "qoi",
                       fmt::format("task {} has {} values, not the {} of a predict run", run.key, rec.qoi.size(), want));
    run.q = rec.qoi;
  }
  r.runs_total = static_cast<int>(done.size());
  r.computed = counts.computed();
  r.read_back = counts.read_back();
  score_ensembles(r, cases, o);
  return r;
}

}  // namespace pastemix::app::study
