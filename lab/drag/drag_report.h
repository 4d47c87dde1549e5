// SPDX-License-Identifier: MIT
// Outputs of `pastemix lab drag-fit`: the score table, per-sphere and summary CSVs, the curve TOML the engine
// loads by name, the parameter-store entries, and the plots (one /usr/bin/python3 matplotlib script).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "lab/drag/scoring.h"
#include "lab/parameter.h"

namespace pastemix::lab::drag {

std::string score_table(const DragFitResult& r);
std::string spheres_csv(const DragFitResult& r);
std::string summary_csv(const DragFitResult& r);
std::string curves_csv(const DragFitResult& r);  // Cd(Re') of every curve on a log grid, for the plot
std::string drag_curve_toml(const DragFitResult& r);

// Parameter-store entries: drag_curve.chosen (text = family) and drag_curve.<family>.<coef> (value, sd).
std::vector<Parameter> drag_curve_parameters(const DragFitResult& r);
// The parameters of one candidate's in-sample fit, with how it was chosen (`lab reduce` fits only the
// family and target that `lab drag-fit` selected on held-out suspensions, named in the manifest).
std::vector<Parameter> candidate_parameters(const Candidate& c, const std::string& choice_method,
                                            const std::string& choice_note, const std::string& sources);
// For `pastemix lab reduce`: runs the whole fit on the dataset folder and returns the entries above.
std::vector<Parameter> drag_curve_parameters(const std::filesystem::path& dataset_dir);

struct DragFitOutputs {
  std::vector<std::filesystem::path> written;
  std::string plot_message;  // empty if the plots were made; else why not
};
// Writes everything under `out_dir` through a StagedOutput (nothing half-written). Plots are made only if
// `plots` and /usr/bin/python3 with matplotlib runs; otherwise the rest is still written and the reason
// returned.
DragFitOutputs write_drag_fit_outputs(const DragFitResult& r, const std::filesystem::path& out_dir, bool plots);

}  // namespace pastemix::lab::drag
