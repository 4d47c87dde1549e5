// SPDX-License-Identifier: MIT
// The two drag-fit figures, drawn by one matplotlib script run with /usr/bin/python3:
//   cd_re.png:            Cd vs Re' (log-log), the 121 spheres by suspension, the published, Stokes and
//                         fitted curves;
//   velocity_parity.png:  predicted vs measured terminal velocity, (a) published, (c) chosen fit held out,
//                         (d) thesis model, with the 1:1 and +-20 % lines.
#pragma once

#include <filesystem>
#include <string>

#include "base/staged_output.h"
#include "lab/drag/scoring.h"

namespace pastemix::lab::drag {

// Runs the script on the (staged) CSVs and stages the PNGs (and the script itself) in `out`.
// Returns an empty string on success, else why no plots were made (the caller reports it; the numeric
// outputs do not depend on the plots).
std::string make_drag_plots(StagedOutput& out, const DragFitResult& r, const std::filesystem::path& spheres_csv,
                            const std::filesystem::path& curves_csv, const std::filesystem::path& out_dir);

}  // namespace pastemix::lab::drag
