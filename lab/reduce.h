// SPDX-License-Identifier: MIT
// `pastemix lab reduce DIR`: every ingester the manifest names, in one pass, into one ReduceResult.
//
// The steps are a plain table (reduce_steps()): each row names the manifest table it reads and a function
// that reads that table (the only place its keys appear) and appends to the result. A step whose table is
// absent from the manifest does not run. To add a step, add one row, e.g. for the drag curve:
//   {"drag_curve", "settling spheres -> Cd(Re') curve", run_drag_curve},
// where run_drag_curve appends its std::vector<lab::Parameter> (keys drag_curve.*) to result.parameters.
// All inputs are read and checked (and Params::finish() run) before anything is written.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "base/params.h"
#include "lab/ingest/block_cut.h"
#include "lab/ingest/mixing_program.h"
#include "lab/ingest/sieve.h"
#include "lab/manifest.h"
#include "lab/parameter.h"

namespace pastemix::lab {

struct NamedSieve {
  std::string name;    // [[sieve]] name, used as psd.<name>
  std::string source;  // file, relative to the dataset folder
  std::string note;    // e.g. why the file is an assumption
  Provenance provenance = Provenance::measured;
  SieveResult result;
};

// Options of `lab reduce` beyond the manifest.
struct ReduceOptions {
  // A paste-rheology calibration record (`pastemix calibrate rheology`); empty: the model's shape parameter
  // is its prior (lab/rheology/paste_rheology.h).
  std::string rheology_calibration;
};

struct ReduceResult {
  ReduceOptions options;
  std::string dataset_dir;    // as given
  std::string manifest;       // path of manifest.toml
  std::string dataset_name;   // [dataset] name
  std::vector<std::string> steps_run;
  std::vector<std::string> inputs;  // files read, relative to the dataset folder
  std::vector<Parameter> parameters;
  std::vector<Warning> warnings;
  std::vector<MixingCase> mixing_cases;
  std::string mixing_source;  // file of the mixing programme, relative to the dataset folder
  std::vector<NamedSieve> sieves;
  std::optional<BlockCutResult> block_cut;
};

using ReduceStepFn = void (*)(const Params& table, const Manifest& manifest, ReduceResult& result);
struct ReduceStep {
  const char* key;   // manifest table
  const char* what;  // one line for --help and the outputs
  ReduceStepFn run;
};
const std::vector<ReduceStep>& reduce_steps();

// Reads DIR/manifest.toml and runs every step whose table is present. Throws InputError on any bad input.
ReduceResult reduce(const std::filesystem::path& dir, const ReduceOptions& options = {});

}  // namespace pastemix::lab
