// SPDX-License-Identifier: MIT
// The HDF5 schema of a run (the only model header the analysis layer needs) and its XDMF companion.
//
//   /                         attributes: scene_path, scene_text (the resolved scene file), scene_hash
//                             (FNV-1a 64 of the text, hex), seed, law, rolling, time_step_s, end_time_s,
//                             particle_count, and the resolved Plan/defaults: skin_m, rotation (0/1),
//                             history_width, output_interval_s, energy_interval_s
//   /materials                (M strings) material names; snapshots' `material` indexes this list
//   /material_density         (M) kg/m3, same order as /materials
//   fluid (only with [[fluid]]): root attributes fluid_surface_z (m, final surface of the first region),
//                             fluid_density (kg/m3), fluid_solids_fraction (-) of the first region,
//                             fluid_region_count; /timeseries/fluid_surface_z (samples x regions, m)
//   flow (only with [[fluid]] dynamics = "flow", model/fluid/flow_coupling.h): /flow attributes dynamics,
//                             cell_m, top_m, kernel_width, coupling_interval, regularisation_s, nx, ny, nz
//                             (cells), hx, hy, hz, origin_x, origin_y, origin_z (m), cycles, flow_steps, pressure_iterations, viscous_iterations, solver_seconds (s);
//                             /flow/snapshots/NNNNNN/ (attribute time_s: the flow's own time, the last
//                             coupling cycle's end) with the particle snapshot of the same number, arrays
//                             [k][j][i] (z slowest): paste_fraction, fluid_fraction (-), pressure (Pa),
//                             velocity (nz x ny x nx x 3, m/s, face means); /flow/timeseries/paste_volume (m3,
//                             per energy sample)
//   /snapshots/time           (S) s
//   /snapshots/NNNNNN/        one group per snapshot (attribute time_s):
//       position (N x 3, m), velocity (N x 3, m/s), radius (N, m), id (N, int64), material (N, int32),
//       angular_velocity (N x 3, rad/s; only with rotation); the last snapshot of a run whose [stop] rule
//       measures by displacement also mean_speed (N, m/s: |x(t) - x(t - check_interval)| / check_interval)
//   outflow: root attributes on_exit ("stop" | "remove"), escaped_count, escaped_mass (kg; 0 with "stop"),
//                             max_escaped_fraction (with "remove"); /escaped/ one entry per particle
//                             removed at the domain boundary, in order of removal (empty datasets if none):
//       id (int64), time (s), mass (kg), radius (m), material (int32), position (E x 3, m, just outside
//       the domain), velocity (E x 3, m/s, the half-step velocity then)
//   stop (how the run ended, model/stop_rule.h): root attributes stop_rule ("end_time" | "at_rest"),
//                             stop_fired (0/1: the at-rest rule ended the run before end_time), stop_time_s,
//                             stop_speed_m_s, stop_paste_speed_m_s, stop_moving_mass_limit_kg, and the census at
//                             the end: moving_mass_kg, in_flight_mass_kg, moving_count, max_speed_m_s
//   /timeseries/              sampled every energy_interval: time (s), kinetic, rotational, potential,
//                             elastic (J), pair_contacts, wall_contacts (int64)
//   /profile/stage (strings), /profile/seconds (wall s per stage); attributes steps, rebuilds,
//                             wall_seconds, steps_per_second, threads
//
// The .xmf file beside it is XDMF 2: a temporal collection of Polyvertex grids whose Geometry (XYZ) and
// attributes (radius, id, velocity) point into the .h5, so ParaView opens the particles directly
// (use "Point Gaussian" with radius as the scale array to see spheres). With a flow, a second temporal collection
// "paste" holds the flow's cell fields on a 3DCoRectMesh (paste_fraction, fluid_fraction, pressure, velocity).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "model/stop_rule.h"
#include "model/world.h"

namespace pastemix {
class H5Writer;
}

namespace pastemix::model {

struct Scene;
struct CheckpointAccess;

class RunOutput {
 public:
  // h5_path is where the data are written now (a staged temporary name); h5_final_name is the file name
  // the .xmf refers to (it sits beside the final .h5).
  RunOutput(const std::filesystem::path& h5_path, std::string h5_final_name, const Scene& scene);
  ~RunOutput();
  void snapshot(const World& w);
  // The last snapshot's mean_speed dataset (N, m/s, written in id order as the snapshot): the [stop]
  // displacement measure's speeds, given in the World's storage order.
  void mean_speed(const World& w, const std::vector<double>& speeds);
  void sample(const World& w);
  // How the run ended (model/stop_rule.h): root attributes stop_*, written once before finish().
  void stop_outcome(const StopOutcome& o, const StopRule& rule);
  // Writes the time series, the profile and closes the file; returns the XDMF text.
  std::string finish(const World& w, double wall_seconds, int threads);

 private:
  friend struct CheckpointAccess;  // model/checkpoint.cpp: the result so far travels in the checkpoint
  void write_escaped(const World& w);
  void flow_snapshot(const fluid::FlowCoupling& c, std::size_t k);
  std::string flow_xdmf(const fluid::FlowFields& f) const;  // the "paste" collection of the .xmf
  std::unique_ptr<H5Writer> h5_;
  std::string h5_name_;
  bool rotation_ = false;
  std::vector<double> snap_times_;
  std::vector<std::size_t> snap_counts_;
  std::vector<double> t_, ke_, rot_, pot_, el_;
  std::vector<std::int64_t> npair_, nwall_;
  std::vector<double> surface_;  // m, fluid surface per sample and region (row-major)
  std::vector<double> paste_volume_;  // m3, the flow's paste volume per sample (dynamics = "flow")
};

std::string scene_hash(const std::string& text);

}  // namespace pastemix::model
