// SPDX-License-Identifier: MIT
#include "app/study/calibrate_rheology.h"

#include <algorithm>
#include <map>
#include <cmath>
#include <mutex>
#include <optional>
#include <thread>

#include <Eigen/Dense>
#include <fmt/format.h>
#include <omp.h>

#include "analysis/maps/mixing_map.h"
#include "analysis/maps/motion.h"
#include "analysis/maps/result_file.h"
#include "analysis/score/lab_case.h"
#include "app/study/tasks.h"
#include "base/error.h"
#include "base/stats.h"
#include "model/output.h"
#include "model/checkpoint.h"
#include "model/run.h"

namespace pastemix::app::study {

namespace fs = std::filesystem;
namespace rh = lab::rheology;

namespace {

// Per-layer rock mass (kg) of a result file, by the maps code on the layout (rock above the surface in layer 1).
// A state not at rest (the maps' own test, analysis/maps/motion.h) is a failed run, as `pastemix maps` refuses it.
std::array<double, 3> layer_rock(const fs::path& h5, const analysis::BlockLayout& layout) {
  const analysis::ResultSnapshot r = analysis::read_result(h5, {});
  const analysis::Motion motion = analysis::motion_of(r, {});
  if (!motion.at_rest()) throw RuntimeFailure(motion.refusal(r));
  const analysis::MixingInputs in = analysis::mixing_inputs(r, layout);
  const analysis::MixingMap m = analysis::mixing_map(in, analysis::ParticleView{r.position, r.radius, r.density});
  std::array<double, 3> out{};
  for (int i = 1; i <= layout.count[0]; ++i)
    for (int j = 1; j <= layout.count[1]; ++j)
      for (int k = 1; k <= 3; ++k) out[static_cast<std::size_t>(k - 1)] += m.rock_mass[layout.index(i, j, k)];
  return out;
}

// J of the seed-mean layers, its jackknife se, and the per-seed J_s summary.
void summarise_point(CalPoint& p, const std::array<double, 3>& target) {
  const std::size_t n = p.runs.size();
  std::vector<double> js;
  for (int k = 0; k < 3; ++k) {
    std::vector<double> v;
    for (const auto& r : p.runs) v.push_back(r.layers[static_cast<std::size_t>(k)]);
    const Summary s = summarize(v);
    p.layers[static_cast<std::size_t>(k)] = s.mean, p.layers_sd[static_cast<std::size_t>(k)] = s.sd;
  }
  for (auto& r : p.runs) js.push_back(r.J = layer_objective(r.layers, target));
  const Summary sj = summarize(js);
  p.J_seed_mean = sj.mean, p.J_seed_sd = sj.sd;
  p.J = layer_objective(p.layers, target);
  if (n < 2) return;
  std::vector<double> jack;
  for (std::size_t leave = 0; leave < n; ++leave) {
    std::array<double, 3> m{};
    for (std::size_t s = 0; s < n; ++s)
      if (s != leave)
        for (int k = 0; k < 3; ++k) m[static_cast<std::size_t>(k)] += p.runs[s].layers[static_cast<std::size_t>(k)] / static_cast<double>(n - 1);
    jack.push_back(layer_objective(m, target));
  }
  const Summary sj2 = summarize(jack);
  // Jackknife: se = sqrt((n-1)/n sum_i (J_(-i) - mean)^2) = sd (n-1)/sqrt(n).
  p.J_se = sj2.sd * static_cast<double>(n - 1) / std::sqrt(static_cast<double>(n));
}

struct SeedTask {
  std::size_t point, seed_index;
  model::SceneDoc doc;
};

// One (point, seed) run's layers (kg) from its result file OUT/runs/<hash>.h5 (run_kept).
RunRecord run_seed(const model::SceneDoc& doc, const fs::path& runs, const std::string& hash,
                   const RheologyCalOptions& o, From& from) {
  RunRecord r = run_kept(doc, runs, hash, o.checkpoint_wall_s, o.resume_with, from);
  const std::array<double, 3> l = layer_rock(runs / (hash + ".h5"), o.layout);
  r.qoi = {l[0], l[1], l[2]};
  return r;
}

// Runs (or finds) every task through the studies' one runner (tasks.h); each finished run stays on disk
// under runs/<hash>.h5, and its layers go into the ledger.
void run_tasks(std::vector<CalPoint>& pts, std::vector<SeedTask>& tasks, const RheologyCalOptions& o,
               const std::array<double, 3>& target, int& executed) {
  const fs::path runs = o.out / "runs";
  fs::create_directories(runs);
  std::vector<Task> list;
  std::map<std::string, std::pair<std::size_t, std::size_t>> where;
  for (const SeedTask& t : tasks) {
    const SeedRun& sr = pts[t.point].runs[t.seed_index];
    where[sr.hash] = {t.point, t.seed_index};
    // A sensitivity run (eta_B x F) names its factor: the ledger rows of x1 and x F differ only by their key.
    const std::string eta = o.eta_factor == 1.0 ? "" : fmt::format(" eta x {:g}", o.eta_factor);
    list.push_back({sr.hash, fmt::format("shape {:.10g}{} seed {}", pts[t.point].shape, eta, sr.seed),
                    [&t, &o, runs, hash = sr.hash](From& from) { return run_seed(t.doc, runs, hash, o, from); }});
  }
  StudyIo io = study_io(o, fmt::format("calibrate rheology case {}", o.case_id));
  if (!o.quiet)
    io.on_done = [&](const Task& t, const RunRecord& rec, From from) {
      const auto [point, seed] = where.at(t.key);
      fmt::print(stderr, "  shape {:.6g} seed {}: {}\n", pts[point].shape, pts[point].runs[seed].seed,
                 rec.failed ? "FAILED: " + rec.failure
                            : fmt::format("layers {:.2f} / {:.2f} / {:.2f} g ({})", 1e3 * rec.qoi.at(0),
                                          1e3 * rec.qoi.at(1), 1e3 * rec.qoi.at(2), to_string(from)));
    };
  TaskCounts counts;
  const std::vector<Finished> done = run_tasks(list, io, counts);
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    CalPoint& p = pts[tasks[i].point];
    SeedRun& sr = p.runs[tasks[i].seed_index];
    const RunRecord& rec = done[i].outcome;
    sr.cached = done[i].from == From::disk || done[i].from == From::ledger || done[i].from == From::record;
    sr.resumed = done[i].from == From::resumed;
    if (rec.failed) {
      p.failure = fmt::format("seed {}: {}", sr.seed, rec.failure);
    } else {
      if (rec.qoi.size() != 3)
        throw InputError(o.ledger ? o.ledger->path().string() : "", 0, "qoi",
                         fmt::format("task {} has {} values, not the 3 layer masses", sr.hash, rec.qoi.size()));
      sr.layers = {rec.qoi[0], rec.qoi[1], rec.qoi[2]};
    }
  }
  executed += counts.computed();
  for (auto& p : pts)
    if (p.failure.empty() && !p.runs.empty()) summarise_point(p, target);
}

// Adds the points `shapes` (those not already there) with their seeds' scenes as tasks.
void add_points(std::vector<CalPoint>& pts, std::vector<SeedTask>& tasks, const std::vector<double>& shapes,
                const model::SceneDoc& base, const rh::Model& model, double cw, const RheologyCalOptions& o,
                double min_gap) {
  const long seed0 = scene_seed(base);
  for (double s : shapes) {
    bool known = false;
    for (const auto& p : pts) known = known || std::abs(p.shape - s) < min_gap;
    if (known) continue;
    CalPoint p;
    p.shape = s;
    rh::Model m = model;
    m.shape = s;
    p.tau_y = rh::yield_stress(m, cw);
    p.eta_B = rh::plastic_viscosity(m, cw) * o.eta_factor;
    p.density = rh::density(m.anchor, cw);
    const model::SceneDoc d = with_rheology(base, p.tau_y, p.eta_B, p.density);
    for (int k = 0; k < o.seeds; ++k) {
      model::SceneDoc ds = d;
      ds.set("seed", std::to_string(seed0 + k));
      p.runs.push_back({seed0 + k, model::scene_hash(ds.text()), {}, 0.0, false});
      tasks.push_back({pts.size(), static_cast<std::size_t>(k), std::move(ds)});
    }
    pts.push_back(std::move(p));
  }
}

QuadFit fit_near_best(const std::vector<CalPoint>& pts) {
  std::vector<const CalPoint*> ok;
  for (const auto& p : pts)
    if (p.failure.empty()) ok.push_back(&p);
  QuadFit f;
  if (ok.size() < 3) {
    f.why = fmt::format("{} usable point(s): a quadratic needs 3", ok.size());
    return f;
  }
  const CalPoint* best = *std::min_element(ok.begin(), ok.end(), [](auto* a, auto* b) { return a->J < b->J; });
  std::sort(ok.begin(), ok.end(), [&](auto* a, auto* b) {
    return std::abs(a->shape - best->shape) < std::abs(b->shape - best->shape);
  });
  ok.resize(std::min<std::size_t>(ok.size(), 5));
  std::vector<double> p, J, se;
  for (auto* q : ok) p.push_back(q->shape), J.push_back(q->J), se.push_back(q->J_se);
  return fit_quadratic(p, J, se);
}

}  // namespace

RunRecord run_kept(const model::SceneDoc& doc, const fs::path& runs, const std::string& hash,
                   double checkpoint_wall_s, const std::string& resume_with, From& from) {
  const fs::path h5 = runs / (hash + ".h5");
  RunRecord r;
  if (fs::exists(h5)) {
    from = From::disk;
    return r;
  }
  model::RunOptions ro;
  ro.progress = false;
  ro.stem = hash;
  ro.checkpoint_wall_s = checkpoint_wall_s;
  ro.resume_with = resume_with;
  // A run killed part-way left its checkpoint: continue it rather than start again.
  ro.resume = fs::exists(model::checkpoint_path(runs, hash));
  if (ro.resume) from = From::resumed;
  const model::Scene s = doc.load();
  const model::RunSummary sum = model::run_scene(s, runs, ro);
  r.wall_s = sum.wall_seconds;
  r.work = static_cast<double>(sum.steps) * static_cast<double>(s.particles.size());
  r.particles = s.particles.size();
  return r;
}

long scene_seed(const model::SceneDoc& d) {
  if (!d.has("seed")) throw InputError(d.path(), 0, "seed", "the scene needs a top-level seed (common random numbers)");
  return std::stol(d.get("seed"));
}

double scene_solids(const model::SceneDoc& d) {
  if (d.size("fluid") == 0) throw InputError(d.path(), 0, "fluid", "the scene has no [[fluid]]");
  for (std::size_t k = 0; k < d.size("fluid"); ++k)
    if (const std::string f = fmt::format("fluid.{}", k); d.has(f + ".rheology_from") && d.has(f + ".solids_fraction"))
      return d.number(f + ".solids_fraction");
  throw InputError(d.path(), 0, "fluid.rheology_from",
                   "no [[fluid]] reads its rheology from the store (rheology_from + solids_fraction): the "
                   "calibration varies the store's model, never numbers in the scene");
}

model::SceneDoc with_rheology(const model::SceneDoc& base, double tau_y, double eta_B, double density) {
  model::SceneDoc d = base;
  if (d.size("fluid") == 0) throw InputError(base.path(), 0, "fluid", "the scene has no [[fluid]]");
  int n = 0;
  for (std::size_t k = 0; k < d.size("fluid"); ++k) {
    const std::string f = fmt::format("fluid.{}", k);
    if (!d.has(f + ".rheology_from")) continue;
    for (const char* key : {"rheology_from", "rheology_at", "yield_stress", "plastic_viscosity", "density"})
      if (d.has(f + "." + key)) d.erase(f + "." + key);
    d.add_number(f, "yield_stress", tau_y);
    d.add_number(f, "plastic_viscosity", eta_B);
    d.add_number(f, "density", density);
    ++n;
  }
  if (n == 0) throw InputError(base.path(), 0, "fluid.rheology_from", "no [[fluid]] reads rheology_from");
  return d;
}

double layer_objective(const std::array<double, 3>& m, const std::array<double, 3>& t) {
  double J = 0.0;
  for (std::size_t k = 0; k < 3; ++k) J += std::pow((m[k] - t[k]) / t[k], 2.0) / 3.0;
  return J;
}

QuadFit fit_quadratic(const std::vector<double>& p, const std::vector<double>& J, const std::vector<double>& se) {
  QuadFit f;
  const std::size_t n = p.size();
  f.used = p;
  if (n < 3) {
    f.why = "fewer than 3 points";
    return f;
  }
  double jmax = 0.0;
  for (double v : J) jmax = std::max(jmax, std::abs(v));
  // A seed spread of exactly 0 (one seed, or identical runs) must not give one point infinite weight.
  const double floor = 1e-3 * jmax + 1e-15;
  f.p_ref = *std::min_element(p.begin(), p.end()) * 0.5 + *std::max_element(p.begin(), p.end()) * 0.5;
  Eigen::MatrixXd X(n, 3);
  Eigen::VectorXd y(n), w(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = p[i] - f.p_ref;
    X.row(static_cast<Eigen::Index>(i)) << 1.0, d, d * d;
    y(static_cast<Eigen::Index>(i)) = J[i];
    const double s = std::max(se[i], floor);
    w(static_cast<Eigen::Index>(i)) = 1.0 / (s * s);
  }
  const Eigen::MatrixXd A = X.transpose() * w.asDiagonal() * X;
  const Eigen::Vector3d c = A.ldlt().solve(X.transpose() * w.asDiagonal() * y);
  const Eigen::VectorXd res = y - X * c;
  const double chi2 = res.dot(w.asDiagonal() * res);
  const double scale = n > 3 ? std::max(1.0, chi2 / static_cast<double>(n - 3)) : 1.0;
  const Eigen::Matrix3d cov = A.inverse() * scale;
  f.c0 = c(0), f.c1 = c(1), f.c2 = c(2);
  if (!(f.c2 > 0.0)) {
    f.why = "the fitted objective has no minimum (curvature <= 0)";
    return f;
  }
  const double dv = -f.c1 / (2.0 * f.c2);
  f.vertex = f.p_ref + dv;
  const Eigen::Vector3d g(0.0, -1.0 / (2.0 * f.c2), f.c1 / (2.0 * f.c2 * f.c2));
  f.sd_delta = std::sqrt(std::max(0.0, g.dot(cov * g)));
  // Spread over curvature: where the surrogate rises by the se of J at the point nearest the vertex.
  std::size_t near = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (std::abs(p[i] - f.vertex) < std::abs(p[near] - f.vertex)) near = i;
  f.sd_curvature = std::sqrt(std::max(se[near], 0.0) / f.c2);
  f.sd = std::max(f.sd_delta, f.sd_curvature);
  const double lo = *std::min_element(p.begin(), p.end()), hi = *std::max_element(p.begin(), p.end());
  if (f.vertex < lo || f.vertex > hi) {
    f.why = fmt::format("the minimum ({:.6g}) lies outside the points fitted ([{:.6g}, {:.6g}])", f.vertex, lo, hi);
    return f;
  }
  f.ok = true;
  return f;
}

namespace {

// The per-layer rock target (kg): --target-layers, or the lab case's grid summed per layer (its solids fraction
// must be the scene's).
void read_target(const model::SceneDoc& base, const RheologyCalOptions& o, RheologyCalResult& r) {
  if (o.target_layers) {
    r.target = *o.target_layers;
    r.target_source = "--target-layers";
  } else {
    const analysis::LabCase lab = analysis::read_lab_case(o.lab_h5, o.case_id, true);
    if (std::abs(lab.solids_fraction - r.solids_fraction) > 1e-9)
      throw InputError(base.path(), 0, "fluid.solids_fraction",
                       fmt::format("{:g}, but case {} was run at {:g} ({})", r.solids_fraction, o.case_id,
                                   lab.solids_fraction, o.lab_h5.string()));
    for (int b = 0; b < lab::kBlocks; ++b) r.target[static_cast<std::size_t>(b % lab::kLayers)] += lab.grid.M_wr[b];
    r.target_source = fmt::format("{} case {} (sum of M_wr per layer)", o.lab_h5.string(), o.case_id);
  }
  for (double t : r.target)
    if (!(t > 0.0)) throw InputError(r.target_source, 0, "layers", "every target layer mass must be positive (kg)");
}

// The three shapes of the next refinement round: the surrogate's vertex (or, with no minimum yet, the best
// point) and one step either side, inside the prior; none when no point has succeeded.
std::optional<std::vector<double>> refinement(const RheologyCalResult& r) {
  const double range = r.prior.hi - r.prior.lo;
  const QuadFit f = fit_near_best(r.points);
  double v = f.vertex;
  if (!(f.c2 > 0.0)) {  // no minimum yet: refine around the best point
    const CalPoint* best = nullptr;
    for (const auto& p : r.points)
      if (p.failure.empty() && (!best || p.J < best->J)) best = &p;
    if (!best) return std::nullopt;
    v = best->shape;
  }
  v = std::clamp(v, r.prior.lo, r.prior.hi);
  const double h = std::clamp(2.0 * f.sd, 0.025 * range, 0.25 * range);
  return std::vector<double>{v, std::max(r.prior.lo, v - h), std::min(r.prior.hi, v + h)};
}

}  // namespace

RheologyCalResult calibrate_rheology(const model::SceneDoc& base, const RheologyCalOptions& o) {
  if (o.seeds < 1) throw InputError("", 0, "--seeds", "must be >= 1");
  if (o.jobs < 1) throw InputError("", 0, "--jobs", "must be >= 1");
  if (o.points < 3 && o.values.empty()) throw InputError("", 0, "--points", "must be >= 3");
  if (!(o.eta_factor > 0.0)) throw InputError("", 0, "--eta-factor", "must be positive");
  RheologyCalResult r;
  r.model = rh::read_model(o.store.string());
  if (!o.family.empty()) {
    const auto f = rh::find_family(o.family);
    if (!f) throw InputError("--family", 0, "family", fmt::format("unknown family '{}' (exponential, packing)", o.family));
    r.model.family = *f;
  }
  r.prior = rh::prior(r.model.family, r.model.anchor);
  for (double v : o.values) rh::check_shape(r.model.family, r.model.anchor, v, "--values");
  r.solids_fraction = scene_solids(base);
  read_target(base, o, r);
  const double range = r.prior.hi - r.prior.lo, gap = 1e-4 * range;
  std::vector<double> grid = o.values;
  if (grid.empty())
    for (int i = 0; i < o.points; ++i) grid.push_back(r.prior.lo + range * i / (o.points - 1));
  std::vector<SeedTask> tasks;
  add_points(r.points, tasks, grid, base, r.model, r.solids_fraction, o, gap);
  run_tasks(r.points, tasks, o, r.target, r.runs_executed);
  for (int round = 0; round < o.refine; ++round) {
    const std::optional<std::vector<double>> add = refinement(r);
    if (!add) break;
    tasks.clear();
    add_points(r.points, tasks, *add, base, r.model, r.solids_fraction, o, gap);
    if (tasks.empty()) break;
    run_tasks(r.points, tasks, o, r.target, r.runs_executed);
  }
  std::sort(r.points.begin(), r.points.end(), [](const auto& a, const auto& b) { return a.shape < b.shape; });
  for (const auto& p : r.points) r.runs_total += static_cast<int>(p.runs.size());
  r.fit = fit_near_best(r.points);
  if (r.fit.ok && (r.fit.vertex < r.prior.lo || r.fit.vertex > r.prior.hi)) {
    r.fit.ok = false;
    r.fit.why = fmt::format("{} = {:.6g} {} lies outside its prior range [{:.6g}, {:.6g}]", r.prior.name, r.fit.vertex,
                            r.prior.unit, r.prior.lo, r.prior.hi);
  }
  if (r.fit.ok) r.model.shape = r.fit.vertex, r.model.shape_sd = r.fit.sd;
  return r;
}

}  // namespace pastemix::app::study
