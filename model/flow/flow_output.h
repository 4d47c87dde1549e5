// SPDX-License-Identifier: MIT
// The flow's HDF5 schema and its XDMF companion (ParaView opens the .xmf: cell data on a 3DCoRectMesh).
//
//   /flow                          attributes: nx, ny, nz (cells), hx, hy, hz (m), origin_x, origin_y,
//                                  origin_z (m), boundary (6 names, x_lo x_hi y_lo y_hi z_lo z_hi),
//                                  rho_paste, rho_air (kg/m3), eta_air (Pa s), rheology, cfl, source
//   /flow/snapshots/time           (S) s
//   /flow/snapshots/NNNNNN/        one group per snapshot (attribute time_s), arrays [k][j][i] (z slowest):
//       velocity (nz x ny x nx x 3, m/s, cell centre = mean of the two faces), pressure (Pa),
//       paste_fraction (-), viscosity (Pa s)
//   /flow/timeseries/              per step: time (s), dt (s), paste_volume (m3), max_speed (m/s),
//                                  pressure_iterations, viscous_iterations (int64), relative_divergence (-)
//   /flow/cost                     attributes: steps, cells, wall_seconds, cell_steps_per_second, threads
//
// The engine's particles go in their own file (model/output.h); both .xmf open side by side in ParaView.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "base/h5.h"
#include "model/flow/solver.h"

namespace pastemix::flow {

class FlowWriter {
 public:
  // h5_path: where to write now (may be a staging name); h5_name: the final file name the .xmf points to.
  FlowWriter(const std::filesystem::path& h5_path, std::string h5_name, const FlowSolver& s, const std::string& source);
  ~FlowWriter();
  void snapshot(const FlowSolver& s);
  void record_step(const FlowSolver& s);  // one timeseries row (after a step)
  // Writes the timeseries and cost, closes the file; returns the XDMF text.
  std::string finish(const FlowSolver& s, int threads);

 private:
  std::unique_ptr<H5Writer> h5_;
  std::string h5_name_;
  std::vector<double> times_;
  std::vector<double> ts_time_, ts_dt_, ts_volume_, ts_speed_, ts_div_;
  std::vector<std::int64_t> ts_piter_, ts_viter_;
  Grid grid_;
};

}  // namespace pastemix::flow
