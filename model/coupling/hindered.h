// SPDX-License-Identifier: MIT
// The `hindered` case of issue 18 (a consistency check of the voidage closure, reported, not bounded): a uniform
// suspension of equal spheres settling through a Newtonian fluid in a periodic box (coupled_flow.h), the
// mixture held by the mean pressure gradient as in `sphere`, against Richardson & Zaki (1954), v_s = v_t eps^n
// with n = 4.65 at low Re; v_s is the spheres' velocity in the zero-volume-flux frame, eps (v_p - u_f), v_t the
// isolated Stokes velocity. No contacts: the centres are uniform random (seeded), overlaps allowed.
#pragma once

namespace pastemix::coupling {

struct HinderedSettings {
  double solid_fraction = 0.1;         // -, of the box
  double diameter = 0.005;             // m
  double cell = 0.01;                  // m
  int cells = 8;                       // per axis
  double rho_particle = 2000.0, rho_fluid = 1000.0, viscosity = 5.0;  // kg/m3, kg/m3, Pa s
  bool voidage = true;                 // Di Felice (drag.h)
  double coupling_interval = 0.005;    // s, one DEM step per flow step
  int cycles = 200;                    // the mean is over the second half
  unsigned seed = 5;
};

struct HinderedResult {
  int spheres = 0;
  double ratio = 0.0;      // v_s / v_t
  double exponent = 0.0;   // log(ratio) / log(eps)
  double reference = 0.0;  // eps^4.65
  double seconds = 0.0;
};

HinderedResult run_hindered(const HinderedSettings& s);

}  // namespace pastemix::coupling
