// SPDX-License-Identifier: MIT
#include "app/study/calibrate.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "app/study/sweep.h"
#include "base/error.h"
#include "base/stats.h"

namespace pastemix::app::study {

model::SceneDoc with_rolling_resistance(const model::SceneDoc& base, double mu) {
  model::SceneDoc d = base;
  if (base.size("interaction") == 0) throw InputError(base.path(), 0, "interaction", "the scene has no [[interaction]]");
  for (std::size_t i = 0; i < base.size("interaction"); ++i)
    d.set("interaction." + std::to_string(i) + ".rolling_friction", fmt::format("{:.10g}", mu));
  return d;
}

namespace {

// Runs (or finds) the (mu, seed) tasks of `mus` and adds them to r.runs.
void run_points(const model::SceneDoc& base, const RollingOptions& o, const std::vector<double>& mus,
                RollingResult& r) {
  const long seed0 = base.has("seed") ? std::stol(base.get("seed")) : 1;
  std::vector<model::SceneDoc> docs;
  std::vector<RollingRun> runs;
  for (double mu : mus)
    for (int k = 0; k < o.seeds; ++k) {
      model::SceneDoc d = with_rolling_resistance(base, mu);
      if (o.seeds > 1) d.set("seed", std::to_string(seed0 + k));
      docs.push_back(std::move(d));
      RollingRun run;
      run.mu = mu, run.seed = seed0 + k;
      runs.push_back(run);
    }
  const std::filesystem::path dir = o.no_cache ? std::filesystem::path{} : o.out / "runs";
  std::vector<Task> list;
  for (std::size_t i = 0; i < docs.size(); ++i) {
    TaskFiles files{dir, run_key(docs[i], "repose_angle"), o.checkpoint_wall_s, o.resume_with, {}};
    list.push_back({files.stem, fmt::format("mu_r = {:.10g} seed {}", runs[i].mu, runs[i].seed),
                    [&doc = docs[i], files](From& from) {
                      return record_of(run_qoi_task(doc, "repose_angle", files, from));
                    }});
  }
  StudyIo io = study_io(o, "calibrate rolling-resistance", dir);
  const auto index = index_by_key(list);
  if (!o.quiet)
    io.on_done = [&](const Task& t, const RunRecord& rec, From from) {
      const RollingRun& run = runs[index.at(t.key)];
      fmt::print(stderr, "  mu_r = {:.4f} seed {}: {}{}\n", run.mu, run.seed,
                 rec.failed ? "FAILED: " + rec.failure : fmt::format("{:.2f} deg ({:.1f} s)", rec.qoi.at(0), rec.wall_s),
                 from == From::ran ? "" : fmt::format(" ({})", to_string(from)));
    };
  const std::vector<Finished> done = run_tasks(list, io, r.counts);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    RollingRun& run = runs[i];
    const RunRecord& rec = done[i].outcome;
    run.failed = rec.failed, run.failure = rec.failure, run.from = done[i].from;
    if (!rec.failed) run.angle = rec.qoi.at(0), run.wall_s = rec.wall_s, run.work = rec.work;
    r.runs.push_back(run);
  }
}

void fit(RollingResult& r, const RollingOptions& o) {
  std::vector<double> mu, angle;
  for (const auto& run : r.runs)
    if (!run.failed) mu.push_back(run.mu), angle.push_back(run.angle);
  r.fit = fit_monotone(mu, angle);
  r.answer = invert(r.fit, o.target, o.target_sd);
}

}  // namespace

RollingResult calibrate_rolling(const model::SceneDoc& base, const RollingOptions& o) {
  if (o.seeds < 1) throw InputError("", 0, "--seeds", "must be >= 1");
  if (o.jobs < 1) throw InputError("", 0, "--jobs", "must be >= 1");
  if (o.seeds > 1 && !base.has("seed"))
    throw InputError(base.path(), 0, "seed", "--seeds > 1 needs a top-level seed key (common random numbers)");
  if (!(o.target_sd >= 0.0)) throw InputError("", 0, "--target-sd", "must be >= 0 (deg)");
  std::vector<double> mus = o.values;
  if (mus.empty()) {
    if (!(o.lo >= 0.0 && o.hi > o.lo)) throw InputError("", 0, "--bracket", "needs 0 <= lo < hi");
    if (o.points < 3) throw InputError("", 0, "--points", "must be >= 3 (the surrogate has 3 parameters)");
    for (int i = 0; i < o.points; ++i) mus.push_back(o.lo + (o.hi - o.lo) * i / (o.points - 1));
  }
  for (double m : mus)
    if (!(m >= 0.0)) throw InputError("", 0, "--values", fmt::format("mu_r = {:g} must be >= 0", m));
  RollingResult r;
  r.law = base.has("contact.rolling") ? base.get("contact.rolling") : "\"none\"";
  run_points(base, o, mus, r);
  fit(r, o);
  const double lo = *std::min_element(mus.begin(), mus.end()), hi = *std::max_element(mus.begin(), mus.end());
  for (int round = 0; round < o.refine && r.answer.ok; ++round) {
    const double h = std::max(2.0 * r.answer.sd, 0.05 * (hi - lo));
    std::vector<double> add;
    for (double m : {r.answer.mu - h, r.answer.mu + h}) {
      m = std::clamp(m, lo, hi);
      bool known = false;
      for (const auto& run : r.runs) known = known || std::abs(run.mu - m) < 1e-4 * (hi - lo);
      for (double a : add) known = known || std::abs(a - m) < 1e-4 * (hi - lo);
      if (!known) add.push_back(std::round(m * 1e6) / 1e6);  // a value that reads back the same
    }
    if (add.empty()) break;
    run_points(base, o, add, r);
    fit(r, o);
  }
  std::sort(r.runs.begin(), r.runs.end(),
            [](const auto& a, const auto& b) { return a.mu != b.mu ? a.mu < b.mu : a.seed < b.seed; });
  return r;
}

std::string rolling_table(const RollingResult& r, const RollingOptions& o) {
  std::ostringstream t;
  t << fmt::format("rolling law: {}; target {:.2f} deg{}; {} seed(s) per mu_r (common random numbers)\n", r.law,
                   o.target, o.target_sd > 0 ? fmt::format(" +- {:.2f}", o.target_sd) : "", o.seeds);
  t << fmt::format("  {:>8} | {:>5} | {:>10} | {:>6} | {:>10}\n", "mu_r", "runs", "angle deg", "sd", "surrogate");
  std::map<double, std::vector<double>> at;
  std::map<double, int> failed;
  for (const auto& run : r.runs) {
    at[run.mu];
    if (run.failed) ++failed[run.mu];
    else at[run.mu].push_back(run.angle);
  }
  for (const auto& [mu, v] : at) {
    const Summary s = v.empty() ? Summary{} : summarize(v);
    t << fmt::format("  {:>8.4f} | {:>5} | {:>10.2f} | {:>6.2f} | {:>10}{}\n", mu, v.size(), s.mean,
                     v.size() > 1 ? s.sd : 0.0, r.fit.ok ? fmt::format("{:.2f}", r.fit.angle(mu)) : "-",
                     failed.count(mu) ? fmt::format("  ({} FAILED)", failed.at(mu)) : "");
  }
  for (const auto& run : r.runs)
    if (run.failed) t << fmt::format("  FAILED mu_r = {:.4f} seed {}: {}\n", run.mu, run.seed, run.failure);
  if (r.fit.ok)
    t << fmt::format("surrogate angle = {:.3f} + {:.3f} (1 - exp(-{:.4g} (mu - {:.4f}))) / {:.4g} deg; noise {:.2f} deg "
                     "({}); lack of fit chi2/dof {:.2f}{}\n",
                     r.fit.a, std::exp(r.fit.beta), r.fit.k, r.fit.mu_ref, r.fit.k, r.fit.noise_sd, r.fit.noise_from,
                     r.fit.chi2_dof, r.fit.chi2_dof > 2.0 ? " (the form does not fit these points well)" : "");
  if (r.answer.ok)
    t << fmt::format("mu_r = {:.4f} +- {:.4f} (fit {:.4f}{}); the surrogate's angle there {:.2f} +- {:.2f} deg\n",
                     r.answer.mu, r.answer.sd, r.answer.sd_fit,
                     o.target_sd > 0 ? fmt::format(", target {:.4f}", r.answer.sd_target) : "", r.fit.angle(r.answer.mu),
                     r.fit.angle_sd(r.answer.mu));
  else
    t << "no mu_r: " << r.answer.why << "\n";
  t << fmt::format("runs: {} in all, {} computed now, {} read back\n", r.runs.size(), r.counts.computed(),
                   r.counts.read_back());
  return t.str();
}

void write_rolling_outputs(const RollingResult& r, const RollingOptions& o) {
  std::filesystem::create_directories(o.out);
  std::ofstream c(o.out / "points.csv");
  c << "mu_r,seed,angle_deg,wall_s,particle_steps,status\n";
  for (const auto& run : r.runs)
    c << fmt::format("{:.10g},{},{:.17g},{:.6g},{:.6g},{}\n", run.mu, run.seed, run.angle, run.wall_s, run.work,
                     run.failed ? "failed" : "done");
  std::ofstream(o.out / "table.txt") << rolling_table(r, o);
}

}  // namespace pastemix::app::study
