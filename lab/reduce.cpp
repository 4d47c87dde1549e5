// SPDX-License-Identifier: MIT
#include "lab/reduce.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "base/error.h"
#include "base/units.h"
#include "lab/drag/drag_report.h"
#include "lab/drag/settling.h"
#include "lab/ingest/block_cut_corrections.h"
#include "lab/ingest/rebound.h"
#include "lab/ingest/slump.h"
#include "lab/ingest/tilt.h"
#include "lab/rheology/reduce_rheology.h"

namespace pastemix::lab {

namespace {

// Appends an ingester's result, naming sources relative to the dataset folder (as the manifest does).
void append(ReduceResult& r, IngestResult in, const ManifestInput& input) {
  for (auto& p : in.parameters) {
    p.source = input.relative;
    r.parameters.push_back(std::move(p));
  }
  for (auto& w : in.warnings) r.warnings.push_back(std::move(w));
  r.inputs.push_back(input.relative);
}

template <class Ingest>
void run_simple(const Params& table, const Manifest& m, ReduceResult& r, const std::vector<ColumnSpec>& specs,
                Ingest ingest) {
  const ManifestInput in = m.input(table, specs);
  append(r, ingest(Manifest::read(in), in.units), in);
}

void run_slump(const Params& t, const Manifest& m, ReduceResult& r) { run_simple(t, m, r, slump_columns(), ingest_slump); }
void run_rebound(const Params& t, const Manifest& m, ReduceResult& r) {
  run_simple(t, m, r, rebound_columns(), ingest_rebound);
}
void run_tilt(const Params& t, const Manifest& m, ReduceResult& r) { run_simple(t, m, r, tilt_columns(), ingest_tilt); }

void run_mixing_program(const Params& t, const Manifest& m, ReduceResult& r) {
  const ManifestInput in = m.input(t, mixing_program_columns());
  r.mixing_cases = ingest_mixing_program(Manifest::read(in), in.units);
  r.inputs.push_back(in.relative);
  r.mixing_source = in.relative;
  for (const auto& c : r.mixing_cases) {
    auto add = [&](std::string name, double value, const char* unit, const char* method) {
      Parameter p;
      p.key = fmt::format("mixing.case_{}.{}", c.case_id, name);
      p.value = value;
      p.unit = unit;
      p.method = method;
      p.source = in.relative;
      r.parameters.push_back(p);
    };
    add("falling_height", c.falling_height, "m", "as recorded (Table 3.1)");
    add("paste_solids_fraction", c.solids_fraction, "-", "as recorded (Table 3.1)");
  }
}

void run_block_cut(const Params& t, const Manifest& m, ReduceResult& r) {
  const ManifestInput in = m.input(t, block_cut_columns());
  std::map<int, KInput> K;
  for (const Params& k : t.tables("K")) {
    const long id = k.integer("case");
    if (id < 1) k.fail("case", "expected a case number >= 1");
    if (K.count(static_cast<int>(id))) k.fail("case", fmt::format("K given twice for case {}", id));
    const std::string unit = k.string("unit");
    if (unit != "kg/m3") k.fail("unit", fmt::format("K = rho_wr/n_wr is a density: expected \"kg/m3\", got \"{}\"", unit));
    K[static_cast<int>(id)] = KInput{k.number("value", Range::positive), k.string("provenance")};
  }
  const CsvTable masses = Manifest::read(in);
  BlockCutResult result = ingest_block_cut(masses, in.units, K);
  r.inputs.push_back(in.relative);
  if (auto c = t.optional_table("corrections")) {
    const ManifestInput cin = m.input(*c, block_cut_correction_columns());
    apply_block_cut_corrections(result, Manifest::read(cin), cin.units);
    r.inputs.push_back(cin.relative);
  }
  for (auto& p : result.parameters) r.parameters.push_back(p);
  for (auto& w : result.warnings) r.warnings.push_back(w);
  r.block_cut = std::move(result);
}

// Settling spheres -> the drag curve. The family and fit target are named in the manifest because choosing
// them needs the leave-one-suspension-out study of `pastemix lab drag-fit` (seconds of Ceres fits); reduce
// refits that choice in-sample, with its covariance, so the engine gets coefficients with uncertainties.
void run_drag_curve(const Params& t, const Manifest& m, ReduceResult& r) {
  const std::string spheres = t.string("spheres"), suspensions = t.string("suspensions");
  const std::string family_name = t.choice("family", {"power_sum", "power_blend", "yield_blend"});
  const std::string target = t.choice("target", {"velocity", "log_cd"});
  const std::string chosen_by = t.string("chosen_by");
  for (const auto& [key, file] : {std::pair{"spheres", spheres}, std::pair{"suspensions", suspensions}})
    if (!std::filesystem::exists(m.dir() / file)) t.fail(key, fmt::format("file '{}' not found in {}", file, m.dir().string()));
  const drag::SettlingData data = drag::read_settling_data(m.dir() / spheres, m.dir() / suspensions);
  drag::Candidate c;
  c.family = *pastemix::drag::find_curve(family_name);
  c.options.target = target == "velocity" ? drag::FitTarget::velocity : drag::FitTarget::log_cd;
  c.in_sample = drag::fit_drag_curve(c.family, data.spheres, c.options, units::g);
  const std::string sources = fmt::format("{}; {}", spheres, suspensions);
  for (auto& p : drag::candidate_parameters(c, chosen_by, c.in_sample.brief_report, sources)) r.parameters.push_back(p);
  r.inputs.push_back(spheres);
  r.inputs.push_back(suspensions);
}

void run_sieves(const Params& sieve, const Manifest& m, ReduceResult& r) {
  NamedSieve s;
  s.name = sieve.string("name");
  // The name becomes a TOML key (psd.<name>) and an HDF5 group (/sieve/<name>).
  const bool ok = !s.name.empty() && s.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") == std::string::npos;
  if (!ok) sieve.fail("name", fmt::format("'{}': use lower-case letters, digits and '_'", s.name));
  for (const auto& other : r.sieves)
    if (other.name == s.name) sieve.fail("name", fmt::format("sieve name '{}' used twice", s.name));
  s.note = sieve.string_or("note", "");
  s.provenance = sieve.choice_or("provenance", {"measured", "assumed", "literature"}, "measured") == "assumed"
                     ? Provenance::assumed
                     : Provenance::measured;
  const double cut = sieve.number_or("cut_mm", 0.0, Range::non_negative) * 1e-3;
  const ManifestInput in = m.input(sieve, sieve_columns());
  s.source = in.relative;
  s.result = ingest_sieve(Manifest::read(in), in.units, cut);
  for (auto& w : s.result.warnings) r.warnings.push_back(w);
  r.inputs.push_back(in.relative);
  r.sieves.push_back(std::move(s));
}

}  // namespace

const std::vector<ReduceStep>& reduce_steps() {
  static const std::vector<ReduceStep> steps{
      {"slump", "slump tests -> paste yield stress (Pashias-Boger)", run_slump},
      {"rebound", "rebound tests -> restitution", run_rebound},
      {"tilt", "tilt tests -> static friction", run_tilt},
      {"mixing_program", "mixing-test programme -> per-case PSD, fall height, paste", run_mixing_program},
      {"block_cut", "cut blocks -> C and S grids per case (+ Table 3.3 correction)", run_block_cut},
      {"drag_curve", "settling spheres -> fitted Cd(Re') drag curve", run_drag_curve},
      {"paste_rheology", "the 75 % paste + a one-parameter model -> rheology at every case's solids content",
       rheology::run_paste_rheology},
  };
  return steps;
}

ReduceResult reduce(const std::filesystem::path& dir, const ReduceOptions& options) {
  const Manifest m = Manifest::load(dir);
  ReduceResult r;
  r.options = options;
  r.dataset_dir = dir.string();
  r.manifest = m.path().string();
  const Params& root = m.root();
  if (auto ds = root.optional_table("dataset")) {
    r.dataset_name = ds->string("name");
    ds->ignore("description");
  }
  for (const auto& step : reduce_steps()) {
    auto table = root.optional_table(step.key);
    if (!table) continue;
    step.run(*table, m, r);
    r.steps_run.push_back(step.key);
  }
  // Sieve files are many of one kind, hence an array of tables rather than a step of their own.
  const std::vector<Params> sieves = root.tables("sieve");  // (call once: each call makes tables finish() checks)
  for (const Params& s : sieves) run_sieves(s, m, r);
  if (!sieves.empty()) r.steps_run.push_back("sieve");
  root.finish();
  std::set<std::string> keys;
  for (const auto& p : r.parameters)
    if (!keys.insert(p.key).second)
      throw InputError(m.path().string(), 0, "", fmt::format("two steps produce the parameter '{}'", p.key));
  if (!options.rheology_calibration.empty() &&
      std::find(r.steps_run.begin(), r.steps_run.end(), "paste_rheology") == r.steps_run.end())
    throw InputError(m.path().string(), 0, "paste_rheology",
                     "a rheology calibration was given but the manifest has no [paste_rheology] table");
  if (r.steps_run.empty())
    throw InputError(m.path().string(), 0, "", "the manifest names no step (expected tables such as [slump])");
  return r;
}

}  // namespace pastemix::lab
