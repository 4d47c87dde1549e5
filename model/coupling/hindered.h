// SPDX-License-Identifier: MIT
// The `hindered` case of issue 18 (a consistency check of the voidage closure): a uniform suspension of equal
// spheres settling through a Newtonian fluid in a periodic box (coupled_flow.h), the mixture held by the mean
// pressure gradient as in `sphere`, against Richardson & Zaki (1954), v_s = v_t eps^n with n = 4.65 at low Re;
// v_s is the spheres' velocity in the zero-volume-flux frame, eps (v_p - u_f), v_t the isolated Stokes
// velocity. No contacts: the centres are uniform random (seeded), overlaps allowed. One realization differs
// from the next by several per cent (the box's density fluctuations drive a resolved convection): the
// figures in VALIDATION.md are means over seeds.
#pragma once

namespace pastemix::coupling {

struct HinderedSettings {
  double solid_fraction = 0.1;         // -, of the box
  double diameter = 0.005;             // m
  // Cells of 4 d (box 32 d): at 2 d (c = 2) the disturbance correction with Di Felice's drag is near its
  // singularity (beta g0 = 0.377 eps^(1 - chi), 0.99 at phi 0.3; VALIDATION.md).
  double cell = 0.02;                  // m
  int cells = 8;                       // per axis
  double rho_particle = 2000.0, rho_fluid = 1000.0, viscosity = 5.0;  // kg/m3, kg/m3, Pa s
  bool voidage = true;                 // Di Felice (drag.h)
  bool disturbance = true;             // the self-induced velocity correction (drag.h)
  double width_factor = 2.0;           // kernel c
  double coupling_interval = 0.005;    // s, one DEM step per flow step
  int cycles = 200;                    // the mean is over the second half
  unsigned seed = 5;
};

struct HinderedResult {
  int spheres = 0;
  double ratio = 0.0;      // v_s / v_t
  double exponent = 0.0;   // log(ratio) / log(eps)
  double reference = 0.0;  // eps^4.65
  // The settling's parts over the window, over v_t (downward positive): the slip the drag sees, mean_p
  // (v_p - W u at x_p), times eps; what the fluid at the particles does beyond its volume mean, mean_p (W u) -
  // mean u (the resolved flow the particles ride); the particles' mean drag coefficient over the closure's
  // at eps = 1 - phi; the resolved pressure force (model A's -V_p grad p beyond the mean gradient) over the
  // mean buoyant weight V_p (rho_p - rho_mix) g, upward positive.
  double local_slip = 0.0, carried = 0.0, beta_ratio = 0.0, pressure_share = 0.0;
  double seconds = 0.0;
};

HinderedResult run_hindered(const HinderedSettings& s);

}  // namespace pastemix::coupling
