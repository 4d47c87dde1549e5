// SPDX-License-Identifier: MIT
// The thesis's multi-ball test (text 4.4.2): 68 steel balls of 12.6 mm poured from the funnel, 15 cm fall into
// the 75 % paste; the lab found every ball suspended between Z = 8.5 and 13.5 cm in a 20 x 16.5 x 15 cm frame.
//
// Model (what the text gives, and what is assumed):
// - Frame: a box 20 (x) x 16.5 (y) cm, corner at the origin, paste filled to its 15 cm rim; Z is measured from
//   the frame bottom (the thesis's Appendix B plot spans X 0-20, Y 0-16.5 cm).
// - Funnel: the thesis's standard funnel (19 cm top, 4.0 cm exit, 12 cm high cone, ch. 3/5/6) with a 2 cm exit
//   tube, on the frame axis; "falling height" is from the bottom of the exit tube to the paste surface, as the
//   thesis defines it for its pour tests (ch. 7: "from the funnel bottom to the paste surface").
// - Release: the balls are placed at random (seeded, no overlap) in the lowest `fill_height` of the cone, fall
//   onto a plate that closes the exit tube and come to rest; the plate is removed at t = `release` and the
//   balls discharge under gravity. This is how the same thesis released rock from its closed funnel (ch. 5
//   falling-height tests, ch. 3 mixing tests); the text of 4.4.2 says only "released from a funnel".
// - Contacts: Hertz-Mindlin, steel balls and steel funnel/plate/frame (E 200 GPa, nu 0.3, Table 4.4), with the
//   measured steel-steel restitution and static friction (Tables 4.6, 4.7) and rolling friction 0.002
//   (Table 4.4, literature; constant-torque law).
// - Time step: a fraction of the ball's Rayleigh time (see VALIDATION.md section 5 for the choice).
// - With `flow` (issue 22): the frame's paste is the region's dynamics = "flow" (the flow solver, coupled both
//   ways; issue 18), on a grid of nearly cubic cells (cells = [nx, ny, nz], the frame's 16.5 cm side in whole
//   cells) up to `air` above the rim. A regularised paste never holds a ball at exactly v = 0 (it creeps), so
//   a ball rests once |v| < rest_speed, and the run ends once every ball is out of the funnel and has rested
//   for rest_time; "in the paste" is the ball's bottom below the area-mean surface (the flow's paste volume plus
//   the balls' volume below the rim, over the frame's area).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/drag_curves.h"

namespace pastemix::validation {

struct PourFlow {
  double cell = 0.01;            // m, the requested cell (each axis takes the nearest whole number of cells)
  long coupling_interval = 50;   // DEM steps per flow interval
  double regularisation = 1000;  // s, Papanastasiou's m (model/flow/bingham.h)
  double kernel_width = 2.0;     // c of the balls' kernels (model/coupling/kernel.h)
  double air = 0.03;             // m of air in the flow box above the rim
  bool implicit_stick = false;   // a yield-held ball moves with the paste in the flow step (model/coupling/coupled_flow.h)
  double rest_speed = 1e-4;      // m/s
  double rest_time = 0.1;        // s
};

struct FunnelPour {
  int balls = 68;
  double ball_d = 0.0126;                                // m
  double rho_ball = 8135.0;                              // kg/m3 (Table 4.4)
  double box_x = 0.20, box_y = 0.165, paste_depth = 0.15;  // m
  double fall = 0.15;                                    // m, exit-tube bottom to paste surface
  double exit_d = 0.04, top_d = 0.19, cone_h = 0.12, tube = 0.02;  // m, the funnel
  double fill_height = 0.08;                             // m of the cone the balls are placed in at t = 0
  double release = 0.25;                                 // s, plate removed
  double end_time = 3.0;                                 // s, upper bound (the run stops when all balls rest)
  double dt_rayleigh = 0.5;                              // time step as a fraction of the Rayleigh time
  double youngs_modulus = 2e11, poisson = 0.3;           // Pa, - (balls, funnel, plate, frame)
  double restitution = 0.612, friction = 0.341, rolling = 0.002;
  // Paste.
  double rho_paste = 1843.0, tau_y = 138.0, eta_B = 0.7;  // kg/m3, Pa, Pa.s
  drag::DragCurve curve{drag::CurveId::published_4_19, {}};
  std::optional<PourFlow> flow;  // none: the paste at rest (model/fluid/field.h)
};

// Rayleigh time of the ball (s): pi r sqrt(rho/G) / (0.8766 + 0.163 nu).
double rayleigh_time(const FunnelPour& p);

struct BallPourResult {
  std::uint64_t seed = 0;
  std::vector<double> x, y, z;  // m, final centres (frame corner at the origin, z above the frame bottom)
  std::vector<std::int64_t> id; // particle ids at the end (must be 0..balls-1)
  double z_min = 0.0, z_max = 0.0;  // m, over the balls that left the funnel
  int at_rest = 0;        // balls at rest inside the paste, not on the floor: suspended (at rest: v == 0, or
                          // |v| < rest_speed with flow)
  int on_floor = 0;       // balls touching the frame floor (within 0.1 mm): not suspended
  int in_funnel = 0;      // balls still above the exit-tube bottom at the end (jammed or not yet out)
  int in_paste = 0;       // balls inside the paste region (submerged volume > 0)
  double surface = 0.0;   // m, final free surface
  double first_out = -1.0, last_out = -1.0;  // s, when the first / last ball passed the exit-tube bottom
  double t_end = 0.0;     // s simulated
  double dt = 0.0;        // s
  long steps = 0;
  long flow_cycles = 0;   // with flow: coupling cycles run, the flow's steps, its linear solves' iterations and
  long flow_steps = 0, pressure_iterations = 0, viscous_iterations = 0;  // its wall time (s): the cost's share
  double flow_seconds = 0.0;
  double max_speed = 0.0;  // m/s, the fastest ball at the end (out of the funnel)
  bool ids_ok = false;
};

std::string ball_pour_scene(const FunnelPour& p, std::uint64_t seed);
// The flow grid's cells along x, y, z for the requested cell (whole cells; the scene checks that they are nearly
// cubic), and the flow box's top (m).
std::array<int, 3> pour_flow_cells(const FunnelPour& p, const PourFlow& f);
// Runs one seeded pour until every ball rests in the paste (checked every 1000 steps) or end_time.
BallPourResult ball_pour(const FunnelPour& p, std::uint64_t seed);

}  // namespace pastemix::validation
