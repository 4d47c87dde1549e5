// SPDX-License-Identifier: MIT
// Settling-sphere reduction (Valentik & Whitmore 1965, thesis Tables 4.2, 4.3 and A.1): per sphere, the
// modified Reynolds number Re' (4.18) and the drag coefficient Cd (4.17) from the measured terminal velocity.
//
// The files are read strictly: unknown columns, a suspension id that is not in the suspensions file, a
// duplicate id, non-positive sizes or densities, a sphere lighter than its fluid, or a sphere whose yield
// term exceeds its net weight (Cd <= 0: it could not have settled) are InputErrors naming file:line.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "base/drag_curves.h"

namespace pastemix::lab::drag {

using pastemix::drag::BinghamSphere;

struct Suspension {
  int id = 0;
  int line = 0;
  double rho_f = 0.0;  // kg/m3
  double eta_B = 0.0;  // Pa.s
  double tau_y = 0.0;  // Pa
};

struct SettlingSphere {
  int row_id = 0;
  int line = 0;  // line in the spheres file
  int suspension = 0;
  BinghamSphere sphere;     // d, rho_p and the suspension's rheology
  double v = 0.0;           // measured terminal velocity, m/s
  double re_printed = 0.0;  // as printed in Table 4.3
  double cd_printed = 0.0;
  double re = 0.0;  // recomputed (4.18)
  double cd = 0.0;  // recomputed (4.17)
};

struct SettlingData {
  std::string spheres_file, suspensions_file;  // as given
  std::vector<Suspension> suspensions;
  std::vector<SettlingSphere> spheres;
  double max_re_error = 0.0;  // max |recomputed/printed - 1|
  double max_cd_error = 0.0;
  int max_re_row = 0, max_cd_row = 0;
};

std::vector<Suspension> read_suspensions(const std::filesystem::path& path);
// Reads the spheres and joins each with its suspension; recomputes Re' and Cd.
SettlingData read_settling_data(const std::filesystem::path& spheres, const std::filesystem::path& suspensions);
// The dataset folder's two files (valentik_whitmore_1965_{spheres,suspensions}.csv).
SettlingData read_settling_dataset(const std::filesystem::path& dir);

// One row of Appendix Table A.1: the thesis f-EDEM model's terminal velocity next to the measured one.
struct ThesisModelRow {
  int row_id = 0;
  int line = 0;
  int suspension = 0;
  BinghamSphere sphere;
  std::optional<double> v_measured, v_model;  // m/s; blank cells are empty
  std::optional<int> spheres_row_id;          // the same sphere in Table 4.3, if any
};
// Checks the clay properties printed on each row against the suspensions file.
std::vector<ThesisModelRow> read_thesis_model(const std::filesystem::path& path,
                                              const std::vector<Suspension>& suspensions);

}  // namespace pastemix::lab::drag
