// SPDX-License-Identifier: MIT
// Writing what `lab reduce` produced: parameters.toml, lab.h5 and one PNG per mixing case, all or nothing.
//
// Everything goes through a StagedOutput: files are written under temporary names and renamed into place
// only at the end. The PNGs come from one run of scripts/plot_lab_grids.py (/usr/bin/python3 with
// matplotlib and h5py) on the staged lab.h5; if Python or those modules are missing, or the script fails,
// that is a Warning and the other files are still written.
#pragma once

#include <filesystem>
#include <vector>

#include "lab/reduce.h"
#include "lab/run_info.h"

namespace pastemix::lab {

struct ReduceOutputs {
  std::vector<std::filesystem::path> written;
  std::vector<Warning> warnings;  // about the outputs (e.g. no plots)
};

// Python and script default to /usr/bin/python3 and the source tree's scripts/plot_lab_grids.py; the
// environment variables PASTEMIX_PYTHON and PASTEMIX_PLOT_SCRIPT override them.
ReduceOutputs write_reduce_outputs(const ReduceResult& result, const std::filesystem::path& out_dir,
                                   RunInfo info);

}  // namespace pastemix::lab
