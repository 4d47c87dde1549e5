// SPDX-License-Identifier: MIT
// `pastemix lab <kind> FILE` (one ingester on one file, units from the column names) and
// `pastemix lab reduce DIR` (every ingester the dataset's manifest names, written to OUTDIR).
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/commands.h"
#include "base/csv.h"
#include "base/error.h"
#include "base/units.h"
#include "base/params.h"
#include "base/psd.h"
#include "lab/ingest/block_cut.h"
#include "lab/ingest/block_cut_corrections.h"
#include "lab/ingest/block_id.h"
#include "lab/ingest/rebound.h"
#include "lab/ingest/sieve.h"
#include "lab/ingest/slump.h"
#include "lab/ingest/tilt.h"
#include "lab/reduce.h"
#include "lab/reduce_outputs.h"

namespace pastemix::app {

namespace {

using lab::format_value;

void print_parameters(const std::vector<lab::Parameter>& params) {
  fmt::print("{:<28} {:>10} {:>10} {:>3}  {:<6} {:<10} {}\n", "parameter", "value", "+- sd", "n", "unit",
             "provenance", "method");
  for (const auto& p : params) {
    fmt::print("{:<28} {:>10} {:>10} {:>3}  {:<6} {:<10} {}\n", p.key, format_value(p.value),
               std::isfinite(p.sd) ? format_value(p.sd) : "-", p.n, p.unit, lab::to_string(p.provenance), p.method);
    if (!p.trials.empty()) {
      std::vector<std::string> t;
      for (double v : p.trials) t.push_back(format_value(v));
      fmt::print("{:<28} trials: {}\n", "", fmt::join(t, ", "));
    }
  }
}

void print_warnings(const std::vector<lab::Warning>& warnings) {
  for (const auto& w : warnings) fmt::print("warning: {}: {}\n", w.where, w.message);
  if (warnings.empty()) fmt::print("no warnings: every printed value agrees with the recomputation\n");
}

template <class Ingest>
void add_simple(CLI::App& lab, const char* name, const char* help, const std::vector<lab::ColumnSpec>& specs,
                Ingest ingest) {
  auto* cmd = lab.add_subcommand(name, help);
  auto file = std::make_shared<std::string>();
  cmd->add_option("FILE", *file, "CSV file (units as in the column names)")->required();
  cmd->callback([file, &specs, ingest] {
    const CsvTable t = CsvTable::read(*file);
    const lab::IngestResult r = ingest(t, lab::ColumnUnits::defaults(specs));
    fmt::print("{}\n", *file);
    print_parameters(r.parameters);
    print_warnings(r.warnings);
  });
}

// Three layer panels side by side, j = 3 on top (as in the PNG maps), i = 1..4 left to right.
void print_grid(const lab::BlockGrid& g, bool s_field) {
  fmt::print("  {:<4}", s_field ? "S" : "C");
  for (int k = 1; k <= lab::kLayers; ++k)
    fmt::print("   {:<24}", k == 1 ? "layer 1 (top)" : fmt::format("layer {}", k));
  fmt::print("\n");
  for (int j = lab::kBlocksJ; j >= 1; --j) {
    fmt::print("  j={} ", j);
    for (int k = 1; k <= lab::kLayers; ++k) {
      fmt::print("   ");
      for (int i = 1; i <= lab::kBlocksI; ++i) {
        const int b = lab::block_index(i, j, k);
        std::string cell = fmt::format("{:.1f}", 100 * g.C[b]);
        if (s_field) switch (static_cast<lab::SFlag>(g.flag[b])) {
            case lab::SFlag::capped: cell = "100*"; break;
            case lab::SFlag::no_rock: cell = "rock0"; break;
            case lab::SFlag::no_K: cell = "-"; break;
            case lab::SFlag::value: cell = fmt::format("{:.1f}", 100 * g.S[b]); break;
          }
        fmt::print("{:>6}", cell);
      }
    }
    fmt::print("\n");
  }
}

void print_block_cut(const lab::BlockCutResult& r) {
  fmt::print("grids in %, seen from above: columns i = 1..4 (20 cm side), rows j = 3..1 (16.5 cm side); "
             "100* = capped, rock0 = no rock (S undefined), - = K unknown\n");
  for (const auto& g : r.cases) {
    fmt::print("case {}: K = {}\n", g.case_id,
               std::isfinite(g.K) ? fmt::format("{} kg/m3 ({})", g.K, g.K_source) : "unknown (S not computed)");
    print_grid(g, false);
    print_grid(g, true);
  }
  for (const auto& g : r.corrected) {
    int n = 0;
    for (int b = 0; b < lab::kBlocks; ++b) n += g.corrected[b];
    if (n == 0) continue;
    fmt::print("case {} after the Table 3.3 interface correction ({} blocks):\n", g.case_id, n);
    for (int b = 0; b < lab::kBlocks; ++b)
      if (g.corrected[b])
        fmt::print("  {}: C {:.1f} %, S {}\n", lab::block_id_of(b), 100 * g.C[b],
                   std::isfinite(g.S_raw[b]) ? fmt::format("{:.1f} %", 100 * g.S_raw[b]) : "-");
  }
  fmt::print("printed C: {} blocks, max |C - printed| = {:.3f} percentage points\n", r.printed.n_C,
             r.printed.max_C_error_pp);
  fmt::print("printed finite uncapped S: {} compared, max relative error = {:.3f} %\n", r.printed.n_S,
             100 * r.printed.max_S_rel_error);
  fmt::print("capped at 100 %: {} blocks\n", r.printed.n_capped);
  if (!r.corrected.empty())
    fmt::print("Table 3.3 (corrected): {} C compared, max error {:.2f} pp; {} S compared, max relative error "
               "{:.1f} %\n",
               r.printed_corrected.n_C, r.printed_corrected.max_C_error_pp, r.printed_corrected.n_S,
               100 * r.printed_corrected.max_S_rel_error);
  print_parameters(r.parameters);
  print_warnings(r.warnings);
}

std::map<int, lab::KInput> parse_K(const std::vector<std::string>& items) {
  std::map<int, lab::KInput> K;
  for (const auto& s : items) {
    const auto eq = s.find('=');
    long id = 0;
    auto value = eq == std::string::npos ? std::nullopt : parse_finite_double(s.substr(eq + 1));
    auto idv = eq == std::string::npos ? std::nullopt : parse_finite_double(s.substr(0, eq));
    if (idv) id = std::lround(*idv);
    if (!value || !idv || *idv != static_cast<double>(id) || id < 1)
      throw InputError("--K", 0, "", fmt::format("expected CASE=VALUE (kg/m3), e.g. 2=3570; got '{}'", s));
    if (!(*value > 0.0)) throw InputError("--K", 0, "", fmt::format("K must be positive, got '{}'", s));
    if (K.count(static_cast<int>(id)))
      throw InputError("--K", 0, "", fmt::format("case {} given twice ({} and {} kg/m3): give each case once", id,
                                                 K.at(static_cast<int>(id)).value, *value));
    K[static_cast<int>(id)] = lab::KInput{*value, "command line --K"};
  }
  return K;
}

void add_block_cut(CLI::App& lab) {
  auto* cmd = lab.add_subcommand("block-cut", "Cut-block masses -> C and S grids per case (eqs 3.1-3.8)");
  struct Opts {
    std::string file, corrections;
    std::vector<std::string> K;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("FILE", o->file, "block masses CSV (as datasets/thesis/block_cut_masses.csv)")->required();
  cmd->add_option("--corrections", o->corrections, "Table 3.3 interface corrections CSV");
  cmd->add_option("--K", o->K, "K = rho_wr/n_wr per case, CASE=VALUE in kg/m3 (e.g. --K 2=3570 3=3570)");
  cmd->callback([o] {
    const auto K = parse_K(o->K);
    const CsvTable t = CsvTable::read(o->file);
    auto r = lab::ingest_block_cut(t, lab::ColumnUnits::defaults(lab::block_cut_columns()), K);
    if (!o->corrections.empty())
      lab::apply_block_cut_corrections(r, CsvTable::read(o->corrections),
                                       lab::ColumnUnits::defaults(lab::block_cut_correction_columns()));
    print_block_cut(r);
  });
}

// --generate makes every particle of the mass: 1e12 g once took 2 GB in 8 s before anything was printed.
// The expected count (mass fraction / mass of a sphere at the interval's mid diameter) is checked first.
void check_generate_size(const Psd& psd, double mass_kg, double density) {
  constexpr double max_particles = 1e7;  // 10 million spheres: ~80 MB of diameters, seconds to make
  double expected = 0.0;
  for (const auto& iv : psd.intervals) {
    const double d = 0.5 * (iv.d_min + iv.d_max);
    expected += iv.mass_fraction * mass_kg / (units::pi / 6.0 * density * d * d * d);
  }
  if (!(expected <= max_particles))
    throw InputError("--generate", 0, "",
                     fmt::format("{:g} g would make about {:.3g} particles (at most {:g}); give a smaller mass",
                                 mass_kg * 1e3, expected, max_particles));
}

void add_sieve(CLI::App& lab) {
  auto* cmd = lab.add_subcommand("sieve", "Sieve masses -> PSD (intervals, cumulative passing), optional sizes");
  struct Opts {
    std::string file;
    double cut_mm = 0.0, mass_g = 0.0, density = 2760.0;
    std::uint64_t seed = 1;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("FILE", o->file, "CSV with columns sieve_mm, mass_retained_g (sieve 0 = pan)")->required();
  cmd->add_option("--cut", o->cut_mm, "PSD cut: drop intervals whose upper sieve is <= this (mm)");
  cmd->add_option("--generate", o->mass_g, "also generate particle sizes for this total mass (g)");
  cmd->add_option("--density", o->density, "particle density for --generate (kg/m3)")->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed for --generate")->capture_default_str();
  cmd->callback([o, cmd] {
    const CsvTable t = CsvTable::read(o->file);
    if (!(o->cut_mm >= 0.0) || !std::isfinite(o->cut_mm)) throw InputError("--cut", 0, "", "must be a number >= 0 mm");
    const bool generate = cmd->count("--generate") > 0;
    if (generate && !(o->mass_g > 0.0 && std::isfinite(o->mass_g)))
      throw InputError("--generate", 0, "", fmt::format("must be a positive mass in g, got {}", o->mass_g));
    if (!(o->density > 0.0 && std::isfinite(o->density)))
      throw InputError("--density", 0, "", fmt::format("must be a positive density in kg/m3, got {}", o->density));
    const auto r = lab::ingest_sieve(t, lab::ColumnUnits::defaults(lab::sieve_columns()), o->cut_mm * 1e-3);
    if (generate) check_generate_size(r.psd, o->mass_g * 1e-3, o->density);
    fmt::print("{}: total {:.2f} g, pan {:.2f} %{}\n", o->file, r.total_mass * 1e3, 100 * r.pan_fraction,
               r.cut > 0 ? fmt::format(", cut at {:g} mm", r.cut * 1e3) : "");
    fmt::print("{:>10} {:>12}\n", "sieve_mm", "passing_%");
    for (std::size_t k = 0; k < r.sieves.size(); ++k)
      fmt::print("{:>10g} {:>12.2f}\n", r.sieves[k] * 1e3, 100 * r.passing[k]);
    fmt::print("PSD (mass fractions, after pan exclusion and cut):\n{:>10} {:>10} {:>10}\n", "d_min_mm", "d_max_mm",
               "fraction");
    for (const auto& iv : r.psd.intervals)
      fmt::print("{:>10g} {:>10g} {:>10.4f}\n", iv.d_min * 1e3, iv.d_max * 1e3, iv.mass_fraction);
    if (generate) {
      const auto d = generate_diameters(r.psd, o->mass_g * 1e-3, o->density, o->seed);
      std::vector<double> mass(r.psd.intervals.size(), 0.0);
      double total = 0.0;
      for (double x : d) {
        const double m = units::pi / 6.0 * o->density * x * x * x;
        total += m;
        for (std::size_t k = 0; k < mass.size(); ++k)
          if (x >= r.psd.intervals[k].d_min && x <= r.psd.intervals[k].d_max) {
            mass[k] += m;
            break;
          }
      }
      fmt::print("generated {} particles, {:.3f} g (seed {}, Gaussian sigma/mu = 0.25 per interval)\n", d.size(),
                 total * 1e3, o->seed);
      fmt::print("{:>10} {:>10} {:>10} {:>10}\n", "d_min_mm", "target", "generated", "rel_err_%");
      for (std::size_t k = 0; k < mass.size(); ++k) {
        const double target = r.psd.intervals[k].mass_fraction, got = mass[k] / total;
        fmt::print("{:>10g} {:>10.4f} {:>10.4f} {:>10.2f}\n", r.psd.intervals[k].d_min * 1e3, target, got,
                   target > 0 ? 100 * (got - target) / target : 0.0);
      }
    }
    print_warnings(r.warnings);
  });
}

void add_reduce(CLI::App& lab) {
  std::string steps;
  for (const auto& s : lab::reduce_steps()) steps += fmt::format("\n  [{}] {}", s.key, s.what);
  auto* cmd = lab.add_subcommand("reduce", "Run every ingester in DIR/manifest.toml; write parameters.toml, lab.h5 "
                                           "and one PNG per mixing case. Steps:" + steps);
  struct Opts {
    std::string dir, out = "out/lab";
    lab::ReduceOptions options;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("DIR", o->dir, "dataset folder with manifest.toml (e.g. datasets/thesis)")->required();
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  cmd->add_option("--rheology-calibration", o->options.rheology_calibration,
                  "record of `pastemix calibrate rheology` (default: the paste-rheology model at its prior)");
  cmd->callback([o] {
    // Reads and checks every input before writing anything.
    const lab::ReduceResult r = lab::reduce(o->dir, o->options);
    std::string command = fmt::format("pastemix lab reduce {} --out {}", o->dir, o->out);
    if (!o->options.rheology_calibration.empty())
      command += " --rheology-calibration " + o->options.rheology_calibration;
    lab::RunInfo info{lab::software_version(), command, lab::utc_now()};
    const auto written = lab::write_reduce_outputs(r, o->out, info);
    print_parameters(r.parameters);
    if (r.block_cut)
      fmt::print("block cut: {} blocks, max |C - printed| {:.3f} pp; {} printed finite uncapped S, max relative "
                 "error {:.3f} %; {} blocks capped\n",
                 r.block_cut->printed.n_C, r.block_cut->printed.max_C_error_pp, r.block_cut->printed.n_S,
                 100 * r.block_cut->printed.max_S_rel_error, r.block_cut->printed.n_capped);
    std::vector<lab::Warning> all = r.warnings;
    all.insert(all.end(), written.warnings.begin(), written.warnings.end());
    print_warnings(all);
    for (const auto& p : written.written) fmt::print("wrote {}\n", p.string());
  });
}

// `pastemix lab param parameters.toml paste.yield_stress` prints one value of the parameter store, so a script
// (scripts/main.sh) can hand a measured value to a scene (`--set fluid.0.yield_stress=...`) without parsing TOML.
void add_param(CLI::App& lab) {
  auto* cmd = lab.add_subcommand("param", "Print one value (or --field) of a parameters.toml written by `lab reduce`");
  struct Opts {
    std::string file, key, field = "value";
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("FILE", o->file, "parameters.toml")->required();
  cmd->add_option("KEY", o->key, "dotted parameter key, e.g. paste.yield_stress")->required();
  cmd->add_option("--field", o->field, "field of the parameter table: value, sd, n, unit, provenance, ...")
      ->capture_default_str();
  cmd->callback([o] {
    const Params root = Params::parse_file(o->file);
    Params t = root;
    std::size_t start = 0;
    while (start <= o->key.size()) {  // walk the dotted path: each segment names a table
      const std::size_t dot = o->key.find('.', start);
      const std::string seg = o->key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      if (seg.empty()) throw InputError(o->file, 0, o->key, "empty segment in the dotted key");
      t = t.table(seg);
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    // Not finish()ed: the file holds every parameter; only one is read.
    if (o->field == "value" || o->field == "sd" || o->field == "n") {
      fmt::print("{}\n", t.number(o->field));  // shortest round-trip form: full precision for --set
    } else {
      fmt::print("{}\n", t.string(o->field));
    }
  });
}

}  // namespace

void register_lab_commands(CLI::App& app) {
  auto* lab = app.add_subcommand("lab", "Reduce laboratory measurements to model parameters");
  lab->require_subcommand(1);
  add_simple(*lab, "slump", "Slump tests -> paste yield stress (Pashias-Boger cylinder)", lab::slump_columns(),
             lab::ingest_slump);
  add_simple(*lab, "rebound", "Rebound (drop) tests -> restitution e = sqrt(H_r/H_f)", lab::rebound_columns(),
             lab::ingest_rebound);
  add_simple(*lab, "tilt", "Tilt tests -> static friction mu_s = H_l/L", lab::tilt_columns(), lab::ingest_tilt);
  add_sieve(*lab);
  add_block_cut(*lab);
  add_reduce(*lab);
  add_param(*lab);
  register_lab_drag_commands(*lab);
}

}  // namespace pastemix::app
