// SPDX-License-Identifier: MIT
// Runs scripts/plot_mixing_maps.py once (with /usr/bin/python3, or $PASTEMIX_PYTHON) to draw PNGs into a
// scratch folder. Plots are a convenience: a missing python or matplotlib is a warning, never an error, and
// the numbers (maps.h5, score.csv, score.toml) are complete without them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pastemix::analysis {

struct PlotResult {
  bool ok = false;
  std::string warning;  // why no PNGs were made (empty when ok)
};

PlotResult run_plot_script(const std::vector<std::string>& args);

}  // namespace pastemix::analysis
