// SPDX-License-Identifier: MIT
// The Table 4.4 steel balls with the moving paste (issue 18's `steel-balls` acceptance): the at-rest harness's
// ball, mould and paste (validations.h: steel_ball_drop) with the region's dynamics = "flow", so that the paste
// is solved on a grid and coupled both ways. The drag law (with its yield part) acts on the slip against the
// local paste velocity, and the flow solver carries the paste's own (regularised) Bingham stress. A coupling that
// counts the yield resistance twice where cells are smaller than the ball (the resolved stress around the ball
// plus the drag law's yield part) stops the balls short of the at-rest table; the table beside it shows it.
//
// What differs from the at-rest harness, and why:
// - The fluid box: cubic cells must tile it, so its side is the mould's equal-area square (66.47 mm) cut into
//   n = round(side / cell) cells, the cell then side / n (the area, so the surface rise, stays the mould's); the
//   flow box reaches `air` above the paste (the open top).
// - Rest: a regularised paste never holds a ball at exactly v = 0 (it creeps, ~ Delta rho g d^2 / (18 tau_y m)),
//   so the ball is at rest once |v| stays below rest_speed for rest_time. A ball that is still moving at
//   t_fall + settle is reported as such, with its speed, not as a distance at rest.
#pragma once

#include "validation/fluid/validations.h"

namespace pastemix::validation {

struct FlowBallSettings {
  double cell = 0.0066;          // m, the requested cubic cell (adjusted to tile the box, above)
  long coupling_interval = 50;   // DEM steps per flow interval
  double regularisation = 1000;  // s, Papanastasiou's m (model/flow/bingham.h)
  double air = 0.03;             // m of air in the flow box above the paste
  double rest_speed = 1e-4;      // m/s
  double rest_time = 0.1;        // s
  double settle = 3.0;           // s after the fall (the at-rest balls stop within ~0.3 s)
};

// The vertical impulses (N s, upward positive) on the ball from its entry (its bottom at the initial surface)
// to the end: its velocity change times its mass = gravity + pressure + drag. The pressure is what the flow
// hands it (model A's -V_p grad p: buoyancy and the displaced paste's dynamic pressure together); hydrostatic
// is rho_f g times its volume below the initial surface (a spherical cap: the at-rest model's buoyancy, less its
// surface rise of ~0.24 mm for the 12.6 mm ball); drag = m dv + m g t - pressure (the drag law's velocity and
// yield parts; no contact touches a ball that rests suspended).
struct ImpulseSplit {
  double momentum = 0.0;     // m (v_end - v_entry)
  double gravity = 0.0;      // -m g t
  double pressure = 0.0;     // sum of F_p dt
  double hydrostatic = 0.0;  // sum of rho_f g V_sub dt
  double drag = 0.0;         // the rest
};

struct FlowBallDrop {
  BallDrop drop;             // distance (m, initial surface to the ball's bottom), time to rest, reached bottom
  bool at_rest = false;      // false: still moving at the end (speed_end)
  double speed_end = 0.0;    // m/s
  double cell = 0.0;         // m, the cell used
  long cycles = 0;           // flow intervals
  double seconds = 0.0;      // wall time
  ImpulseSplit split;        // from the entry into the paste to the end
};

FlowBallDrop steel_ball_drop_flow(const SteelBallPaste& paste, double d, double height, double eta_B,
                                  const FlowBallSettings& flow);

}  // namespace pastemix::validation
