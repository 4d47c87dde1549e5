// SPDX-License-Identifier: MIT
// parameters.toml: the reduced parameters, human-readable and machine-readable.
//
// One table per parameter under its dotted key ([paste.yield_stress]) with value, sd, n, unit, provenance,
// method, source (file relative to the dataset folder) and per-trial values; one table per PSD
// ([mixing.case_1.psd], [psd.<sieve name>]). A comment line above each table states the value in words.
#pragma once

#include <string>

#include "lab/reduce.h"
#include "lab/run_info.h"

namespace pastemix::lab {

std::string parameters_toml(const ReduceResult& result, const RunInfo& info);

}  // namespace pastemix::lab
