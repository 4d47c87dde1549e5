// SPDX-License-Identifier: MIT
#include "app/study/sweep.h"

#include <algorithm>
#include <map>
#include <chrono>
#include <cmath>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <omp.h>

#include <fmt/format.h>

#include "app/study/qoi.h"
#include "app/study/run_cache.h"
#include "app/study/tasks.h"
#include "model/checkpoint.h"
#include "model/run.h"
#include "base/error.h"
#include "base/staged_output.h"
#include "model/output.h"
#include "base/stats.h"

namespace pastemix::app::study {
namespace {

std::string lit(double v) { return fmt::format("{:.10g}", v); }

std::string material_name(const model::SceneDoc& d, const SweepOptions& o) {
  return o.material.empty() ? d.string("material.0.name") : o.material;
}

std::string psd_of(std::size_t factory) { return fmt::format("factory.{}.psd", factory); }

// Smallest interval lower sieve (m) over every [[factory]]'s PSD; 0 when no factory has one.
double smallest_d_min(const model::SceneDoc& d) {
  double m = 0.0;
  for (std::size_t f = 0; f < d.size("factory"); ++f)
    for (std::size_t i = 0; i < d.size(psd_of(f)); ++i) {
      const double v = d.number(fmt::format("{}.{}.d_min", psd_of(f), i));
      if (v > 0 && (m == 0.0 || v < m)) m = v;
    }
  return m;
}

// Drops the PSD intervals of every factory with d_max <= cut (m) and renormalises the fractions kept.
void cut_psd(model::SceneDoc& d, const std::string& scene, double cut) {
  if (d.size("factory") == 0) throw InputError(scene, 0, "factory", "--vary psd_cut needs a [[factory]] with a PSD");
  for (std::size_t f = 0; f < d.size("factory"); ++f) {
    const std::string psd = psd_of(f);
    double kept = 0.0;
    for (std::size_t i = 0; i < d.size(psd); ++i)
      if (d.number(fmt::format("{}.{}.d_max", psd, i)) > cut) kept += d.number(fmt::format("{}.{}.fraction", psd, i));
    for (std::size_t i = d.size(psd); i-- > 0;)  // from the end: erasing keeps the lower indices
      if (d.number(fmt::format("{}.{}.d_max", psd, i)) <= cut) d.erase(fmt::format("{}.{}", psd, i));
    if (d.has(psd) && (d.size(psd) == 0 || kept <= 0))
      throw InputError(scene, 0, "psd_cut", fmt::format("a cut at {} m removes every interval", cut));
    for (std::size_t i = 0; i < d.size(psd); ++i) {
      const std::string fraction = fmt::format("{}.{}.fraction", psd, i);
      d.set_number(fraction, d.number(fraction) / kept);
    }
  }
}

// The walls lifted at a constant speed: those whose velocity has a positive z component.
std::vector<std::size_t> lifted_walls(const model::SceneDoc& d) {
  std::vector<std::size_t> w;
  for (std::size_t i = 0; i < d.size("wall"); ++i)
    if (d.size(fmt::format("wall.{}.velocity", i)) == 3 && d.number(fmt::format("wall.{}.velocity.2", i)) > 0) w.push_back(i);
  if (w.empty()) throw InputError(d.path(), 0, "wall.velocity", "--vary lift_speed needs a [[wall]] lifted (velocity z > 0)");
  return w;
}

double lift_speed(const model::SceneDoc& d) { return d.number(fmt::format("wall.{}.velocity.2", lifted_walls(d).front())); }

// Every lifted wall at `v` (m/s, upwards), and end_time stretched so that the lift covers the same height
// while the settling after it keeps its length: end = start + (end0 - start - settle) v0 / v + settle
// (start: the first lifted wall's move_start, 0 if none; settle in s).
void set_lift_speed(model::SceneDoc& d, double v, double settle) {
  if (!(v > 0)) throw InputError(d.path(), 0, "lift_speed", fmt::format("{:g} m/s must be positive", v));
  const std::vector<std::size_t> walls = lifted_walls(d);
  const double v0 = lift_speed(d);
  const std::string start_key = fmt::format("wall.{}.move_start", walls.front());
  const double start = d.has(start_key) ? d.number(start_key) : 0.0;
  const double end0 = std::stod(d.get("end_time"));
  if (!(settle >= 0 && settle < end0 - start))
    throw InputError(d.path(), 0, "--settle", fmt::format("{:g} s must be >= 0 and shorter than end_time - move_start", settle));
  for (std::size_t w : walls) d.set_number(fmt::format("wall.{}.velocity.2", w), v);
  d.set("end_time", lit(start + (end0 - start - settle) * v0 / v + settle));
}

}  // namespace

model::SceneDoc at_value(const model::SceneDoc& base, const SweepOptions& o, double value) {
  model::SceneDoc d = base;
  if (o.vary == "dt") {
    d.set("time_step", lit(value));
  } else if (o.vary == "youngs_modulus") {
    const std::string key = "material." + material_name(base, o) + ".youngs_modulus";
    const double e0 = std::stod(base.get(key));
    const double dt0 = std::stod(base.get("time_step"));
    d.set(key, lit(value));
    d.set("time_step", lit(dt0 * std::sqrt(e0 / value)));
  } else if (o.vary == "psd_cut") {
    cut_psd(d, base.path(), value);
    const double d0 = smallest_d_min(base), d1 = smallest_d_min(d);
    if (!o.fixed_dt && d0 > 0 && d1 > 0)
      d.set("time_step", lit(std::stod(base.get("time_step")) * d1 / d0));
  } else if (o.vary == "lift_speed") {
    set_lift_speed(d, value, o.settle_s);
  } else {
    throw InputError("", 0, "--vary", "'" + o.vary + "' is not one of dt, youngs_modulus, psd_cut, lift_speed");
  }
  return d;
}

std::vector<double> default_ladder(const model::SceneDoc& base, const SweepOptions& o) {
  std::vector<double> v;
  if (o.vary == "dt") {
    const double dt = std::stod(base.get("time_step"));
    for (int k = 0; k < o.levels; ++k) v.push_back(dt / std::pow(2.0, k));
  } else if (o.vary == "youngs_modulus") {
    const double e0 = std::stod(base.get("material." + material_name(base, o) + ".youngs_modulus"));
    for (int k = o.levels - 1; k >= 0; --k) v.push_back(e0 / std::pow(10.0, k));
  } else if (o.vary == "lift_speed") {
    // Fast -> the scene's speed (the reference, as the thesis lifted).
    const double v0 = lift_speed(base);
    for (int k = o.levels - 1; k >= 0; --k) v.push_back(v0 * std::pow(2.0, k));
  } else if (o.vary == "psd_cut") {
    std::vector<double> cuts;
    for (std::size_t f = 0; f < base.size("factory"); ++f)
      for (std::size_t i = 0; i < base.size(psd_of(f)); ++i)
        cuts.push_back(base.number(fmt::format("{}.{}.d_min", psd_of(f), i)));
    std::sort(cuts.begin(), cuts.end(), std::greater<>());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    // Coarsest first: the largest cut that keeps an interval, down to no cut.
    for (double c : cuts) v.push_back(c);
    if (!v.empty()) v.erase(v.begin());  // cutting at the largest d_min would remove everything
    v.push_back(0.0);
  }
  return v;
}

RunCost run_once(const model::SceneDoc& doc, const std::string& qoi_name, const std::filesystem::path& save_h5) {
  const QoiDef& q = find_qoi(qoi_name);
  const model::Scene s = doc.load();
  model::World w = model::make_world(s);
  const auto t0 = std::chrono::steady_clock::now();
  const long n = static_cast<long>(std::llround(s.end_time / s.config.dt));
  if (n < 1)
    throw InputError(doc.path(), 0, "time_step",
                     fmt::format("{:g} s is longer than end_time {:g} s: the run would take no step", s.config.dt,
                                 s.end_time));
  double best = -1e300;
  model::RestMonitor rest(s.stop, s.config.dt, n);  // [stop] rule = "at_rest" ends the run early
  for (long k = 0; k < n; ++k) {
    w.step();
    if (k % 50 == 0) w.check();
    if (q.max_over_steps) best = std::max(best, q.eval(w));
    if (rest.check(w, k + 1)) break;
  }
  if (s.stop.at_rest && !rest.fired()) {
    const model::MotionCensus c = model::census(w, s.stop);
    throw RuntimeFailure(fmt::format("end_time {:g} s reached before the rock came to rest: {:.4g} g moving faster "
                                     "than {:g} m/s (a failed point: raise end_time)",
                                     s.end_time, 1e3 * c.moving_mass, s.stop.speed));
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!save_h5.empty()) {
    StagedOutput staged;
    {
      model::RunOutput out(staged.path(save_h5), save_h5.filename().string(), s);
      out.snapshot(w);
      out.sample(w);
      staged.write_text(std::filesystem::path(save_h5).replace_extension(".xmf"), out.finish(w, wall, 1));
    }
    staged.commit();
  }
  return {q.max_over_steps ? best : q.eval(w), wall, static_cast<double>(w.steps()) * static_cast<double>(s.particles.size()),
          s.particles.size()};
}

RunCost run_qoi_task(const model::SceneDoc& doc, const std::string& qoi_name, const TaskFiles& files, From& from) {
  const QoiDef& q = find_qoi(qoi_name);
  // A QoI over every step is taken in-process, step by step (the short analytic checks); so is every run
  // of a study that keeps no files.
  if (q.max_over_steps || files.dir.empty()) return run_once(doc, qoi_name, files.save_h5);
  model::Scene s = doc.load();
  const bool keep = !files.save_h5.empty();
  const std::filesystem::path dir = keep ? files.save_h5.parent_path() : files.dir;
  const std::string stem = keep ? files.save_h5.stem().string() : files.stem;
  if (!keep) s.output_interval = s.energy_interval = std::max(s.end_time, s.config.dt);  // first and last state only
  model::RunOptions ro;
  ro.progress = false;
  ro.stem = stem;
  ro.checkpoint_wall_s = files.checkpoint_wall_s;
  ro.resume_with = files.resume_with;
  ro.resume = std::filesystem::exists(model::checkpoint_path(dir, stem));
  if (ro.resume) from = From::resumed;
  double value = 0.0;
  std::string qoi_failure;
  ro.at_end = [&](const model::World& w) {
    try {
      value = q.eval(w);
    } catch (const RuntimeFailure& e) {
      qoi_failure = e.what();
    }
  };
  const model::RunSummary r = model::run_scene(s, dir, ro);
  if (!keep) {
    std::error_code ec;
    std::filesystem::remove(r.h5, ec);
    std::filesystem::remove(r.xmf, ec);
  }
  if (r.failed_to_rest())
    throw RuntimeFailure(fmt::format("end_time {:g} s reached before the rock came to rest: {:.4g} g moving faster "
                                     "than {:g} m/s (a failed point: raise end_time)",
                                     s.end_time, 1e3 * r.stop.last.moving_mass, s.stop.speed));
  if (!qoi_failure.empty()) throw RuntimeFailure(qoi_failure);
  return {value, r.wall_seconds, static_cast<double>(r.steps) * static_cast<double>(s.particles.size()),
          s.particles.size()};
}

RunRecord record_of(const RunCost& c) {
  RunRecord r;
  r.qoi = {c.qoi};
  r.wall_s = c.wall_s, r.work = c.work, r.particles = c.particles;
  return r;
}

namespace {

// One (ladder value, seed) run of a sweep; the scenes are built (and checked) before any run starts.
struct SweepRun {
  std::size_t point;
  long seed;
  model::SceneDoc doc;
  std::optional<RunCost> cost;
  std::string failure;
};

// The checks of the options that need the scene's seed.
void check_seeds_jobs(const model::SceneDoc& base, const SweepOptions& o) {
  if (o.seeds > 1 && !base.has("seed"))
    throw InputError(base.path(), 0, "seed", "--seeds > 1 needs a top-level seed key");
  if (o.jobs < 1) throw InputError("", 0, "--jobs", "must be >= 1");
}

// The ladder x seeds as tasks; `time_step` gets each point's step (s).
std::vector<SweepRun> make_tasks(const model::SceneDoc& base, const SweepOptions& o, const std::vector<double>& values,
                             long seed0, std::vector<double>& time_step) {
  std::vector<SweepRun> tasks;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const model::SceneDoc d = at_value(base, o, values[k]);
    time_step.push_back(std::stod(d.get("time_step")));
    for (int s = 0; s < o.seeds; ++s) {
      model::SceneDoc ds = d;
      if (o.seeds > 1) ds.set("seed", std::to_string(seed0 + s));
      tasks.push_back({k, seed0 + s, std::move(ds), std::nullopt, {}});
    }
  }
  return tasks;
}

// The per-run line on stderr.
void print_task(const SweepOptions& o, double value, long seed, const RunRecord& r, From f) {
  const std::string from = f == From::ran ? "" : fmt::format(" ({})", to_string(f));
  if (!r.failed)
    fmt::print(stderr, "  {} = {:.4g} seed {}: {} = {:.6g} ({} particles, {:.0f} steps, {:.2f} s){}\n", o.vary,
               value, seed, o.qoi, r.qoi.at(0), r.particles, r.work / static_cast<double>(std::max<std::size_t>(1, r.particles)),
               r.wall_s, from);
  else
    fmt::print(stderr, "  {} = {:.4g} seed {}: FAILED: {}{}\n", o.vary, value, seed, r.failure, from);
}

// Runs (or finds) every task through the studies' one runner (tasks.h); a RuntimeFailure is kept in its task.
void run_sweep_tasks(std::vector<SweepRun>& tasks, const SweepOptions& o, const std::vector<double>& values,
                     SweepResult& r) {
  std::vector<study::Task> list;
  std::vector<std::filesystem::path> save;
  for (const SweepRun& t : tasks) {
    const double value = values[t.point];
    save.push_back(o.save.empty() ? std::filesystem::path{}
                                  : o.save / fmt::format("{}_{:.6g}_seed{}.h5", o.vary, value, t.seed));
    TaskFiles files{o.runs, run_key(t.doc, o.qoi), o.checkpoint_wall_s, o.resume_with, save.back()};
    list.push_back({files.stem, fmt::format("{} = {:.10g} seed {}", o.vary, value, t.seed),
                    [&t, &o, files](From& from) { return record_of(run_qoi_task(t.doc, o.qoi, files, from)); }});
  }
  StudyIo io = study_io(o, fmt::format("sweep {} {}", o.vary, o.qoi), o.runs);
  const auto index = index_by_key(list);
  if (!o.quiet)
    io.on_done = [&](const study::Task& st, const RunRecord& rec, From f) {
      const SweepRun& t = tasks[index.at(st.key)];
      print_task(o, values[t.point], t.seed, rec, f);
    };
  TaskCounts counts;
  const std::vector<Finished> done = run_tasks(list, io, counts);
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    SweepRun& t = tasks[i];
    const RunRecord& rec = done[i].outcome;
    // With --save, the state file is part of the result: a task found finished whose file is gone is redone.
    if (!o.save.empty() && !rec.failed && !std::filesystem::exists(save[i]) && done[i].from != From::ran &&
        done[i].from != From::resumed) {
      From from = From::ran;
      try {
        t.cost = run_qoi_task(t.doc, o.qoi, {o.runs, list[i].key, o.checkpoint_wall_s, o.resume_with, save[i]}, from);
      } catch (const RuntimeFailure& e) {
        t.failure = e.what();
      }
      ++counts.ran;
      if (!o.quiet) print_task(o, values[t.point], t.seed, t.cost ? record_of(*t.cost) : RunRecord::failed_with(t.failure), from);
    } else if (rec.failed) {
      t.failure = rec.failure;
    } else {
      t.cost = RunCost{rec.qoi.at(0), rec.wall_s, rec.work, rec.particles};
    }
  }
  r.executed = counts.computed(), r.read_back = counts.read_back();
}

// One ladder point per value whose runs all succeeded (mean and sd over the seeds); a point with a failed run
// goes to r.failed instead, and its time step is dropped from r.time_step.
void gather_points(const std::vector<SweepRun>& tasks, const SweepOptions& o, const std::vector<double>& values,
                   SweepResult& r) {
  std::vector<double> kept_dt;
  for (std::size_t k = 0; k < values.size(); ++k) {
    std::vector<double> q, wall;
    double work = 0.0;
    bool ok = true;
    for (const SweepRun& t : tasks) {
      if (t.point != k) continue;
      if (!t.cost) {
        r.failed.push_back({values[k], t.seed, t.failure});
        ok = false;
        continue;
      }
      q.push_back(t.cost->qoi);
      wall.push_back(t.cost->wall_s);
      work += t.cost->work / o.seeds;
    }
    if (!ok) continue;
    const auto sq = summarize(q), sw = summarize(wall);
    r.points.push_back({values[k], sq.mean, o.seeds > 1 ? sq.sd : 0.0, o.seeds, sw.mean, work});
    r.per_seed.push_back(q);
    kept_dt.push_back(r.time_step[k]);
  }
  r.time_step = kept_dt;
  if (r.points.empty())
    throw RuntimeFailure(fmt::format("sweep: every run failed; the first: {} = {:g} seed {}: {}", o.vary,
                                     r.failed.front().value, r.failed.front().seed, r.failed.front().reason));
}

// The reference (Richardson where the kept points are successive halvings of dt; a failed coarse point leaves
// them so) and the cheapest point within the tolerance.
void choose_point(const SweepOptions& o, SweepResult& r) {
  bool halving = o.vary == "dt";
  for (std::size_t k = 1; halving && k < r.points.size(); ++k)
    halving = std::abs(r.points[k - 1].value / r.points[k].value - 2.0) < 1e-9;
  r.ref = reference_of(r.points, halving ? 2.0 : 0.0);
  r.choice = choose(r.points, r.ref, o.tol);
}

// The speed-vs-error table without its last line (the choice).
std::string sweep_table(const model::SceneDoc& base, const SweepOptions& o, const SweepResult& r) {
  const double cost_ref = r.points.back().work;
  std::ostringstream t;
  t << fmt::format("sweep {} on {}: QoI {} ({}), tol {:g}, {} seed(s)\n", o.vary, base.path(), o.qoi,
                   find_qoi(o.qoi).unit, o.tol, o.seeds);
  t << fmt::format("reference {} = {:.6g} from {}\n", o.qoi, r.ref.qoi, r.ref.method);
  t << "cost = particle-steps (deterministic); wall s = the step loop on this machine\n";
  t << fmt::format("  {:>12} | {:>9} | {:>12} | {:>9} | {:>10} | {:>10} | {:>9} | {:>10}\n", o.vary, "dt s",
                   "QoI (mean)", "sd", "rel error", "p-steps", "wall s", "cost/finest");
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    const auto& p = r.points[k];
    t << fmt::format("  {:>12.4g} | {:>9.3g} | {:>12.6g} | {:>9.3g} | {:>10.3e} | {:>10.4g} | {:>9.1f} | {:>10.4f}{}\n",
                     p.value, r.time_step[k], p.qoi, p.qoi_sd, r.choice.rel_error[k], p.work, p.wall_s,
                     p.work / cost_ref, static_cast<int>(k) == r.choice.index ? "  <- chosen" : "");
  }
  for (const auto& f : r.failed)
    t << fmt::format("  {:>12.4g} | FAILED (seed {}): {}\n", f.value, f.seed, f.reason);
  return t.str();
}

// The chosen setting `v` as override lines (`pastemix run --overrides`).
std::string chosen_overrides(const model::SceneDoc& base, const SweepOptions& o, double v) {
  const model::SceneDoc d = at_value(base, o, v);
  std::ostringstream ov;
  ov << fmt::format("# pastemix sweep --vary {} --qoi {} --tol {:g}: chosen {} = {:.6g}\n", o.vary, o.qoi, o.tol,
                    o.vary, v);
  if (o.vary == "psd_cut") {
    for (std::size_t i = 0; i < d.size("factory"); ++i)
      if (d.has(psd_of(i))) ov << psd_of(i) << " = " << d.get(psd_of(i)) << "\n";
    return ov.str();
  }
  if (o.vary == "youngs_modulus") {
    const std::string key = "material." + material_name(base, o) + ".youngs_modulus";
    ov << key << " = " << d.get(key) << "\n";
  }
  if (o.vary == "lift_speed") {
    for (std::size_t w : lifted_walls(base)) ov << fmt::format("wall.{0}.velocity = {1}\n", w, d.get(fmt::format("wall.{}.velocity", w)));
    ov << "end_time = " << d.get("end_time") << "\n";
  }
  ov << "time_step = " << d.get("time_step") << "\n";
  return ov.str();
}

}  // namespace

SweepResult sweep(const model::SceneDoc& base, const SweepOptions& o) {
  find_qoi(o.qoi);
  if (o.seeds < 1) throw InputError("", 0, "--seeds", "must be >= 1");
  if (!(o.tol > 0)) throw InputError("", 0, "--tol", "must be > 0");
  SweepResult r;
  const std::vector<double> values = o.values.empty() ? default_ladder(base, o) : o.values;
  if (values.empty()) throw InputError(base.path(), 0, "--values", "the ladder is empty");
  const long seed0 = base.has("seed") ? std::stol(base.get("seed")) : 1;
  check_seeds_jobs(base, o);
  std::vector<SweepRun> tasks = make_tasks(base, o, values, seed0, r.time_step);
  run_sweep_tasks(tasks, o, values, r);
  gather_points(tasks, o, values, r);
  choose_point(o, r);
  r.table = sweep_table(base, o, r);
  if (r.choice.index < 0) {
    r.table += "no setting is within the tolerance of the reference\n";
  } else {
    const double v = r.points[static_cast<std::size_t>(r.choice.index)].value;
    r.override_text = chosen_overrides(base, o, v);
    r.table += fmt::format("chosen: {} = {:.6g}\n", o.vary, v);
  }
  return r;
}

void write_outputs(const SweepResult& r, const SweepOptions& o) {
  std::filesystem::create_directories(o.out);
  {
    std::ofstream c(o.out / "sweep.csv");
    c << o.vary << ",time_step,qoi_mean,qoi_sd,seeds,rel_error,particle_steps,wall_s,cost_ratio,chosen,reference,"
                   "reference_method\n";
    for (std::size_t k = 0; k < r.points.size(); ++k) {
      const auto& p = r.points[k];
      c << fmt::format("{:.10g},{:.6g},{:.10g},{:.6g},{},{:.6g},{:.6g},{:.6g},{:.6g},{},{:.10g},\"{}\"\n", p.value,
                       r.time_step[k], p.qoi, p.qoi_sd, p.seeds, r.choice.rel_error[k], p.work, p.wall_s,
                       p.work / r.points.back().work, static_cast<int>(k) == r.choice.index ? 1 : 0, r.ref.qoi,
                       r.ref.method);
    }
  }
  if (!r.override_text.empty()) std::ofstream(o.out / "chosen_overrides.toml") << r.override_text;
  const std::string py = std::string(PASTEMIX_SOURCE_DIR) + "/scripts/plot_sweep.py";
  const std::string cmd = "/usr/bin/python3 '" + py + "' '" + (o.out / "sweep.csv").string() + "' '" +
                          (o.out / "sweep.png").string() + "' " + o.qoi + " " + fmt::format("{:g}", o.tol) + " >/dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) fmt::print(stderr, "warning: no PNG (python/matplotlib failed)\n");
}

}  // namespace pastemix::app::study
