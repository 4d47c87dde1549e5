// SPDX-License-Identifier: MIT
// The drag of the moving paste on a particle, for the exchange (exchange.h; issue 18, layer 3): the project's
// drag law (the same registry law the at-rest pass uses, laws/drag_law.h) on the slip w = v_p - u_f(x_p),
// split into the bounded yield part F_y (N) and a velocity-dependent coefficient beta (kg/s, F = beta (u_f - v_p)),
// with two corrections. Nothing here knows a law: the caller hands in the law's D(s) and its Reynolds number.
//
// Split (as fluid/drag_kick.h): D(s) = D0 + k(s) s with D0 = D(0+) (Dedegil's yield term plus the rest part of
// Cd's 24/Re' branch: (pi^2/4 + 3 pi) d^2 tau_y with the Stokes curve), F_y = D0, beta = k.
//
// 1. Voidage (Di Felice 1994, Int. J. Multiphase Flow 20, 153-159): in a suspension of fluid fraction eps the
//    drag is the isolated sphere's at the superficial slip eps |w|, times eps^-chi,
//      F = [D(eps s) - D0] eps^-chi,   chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2 / 2),  Re at eps s,
//    so beta = k(eps s) eps^(1 - chi) (Stokes: 3 pi mu d eps^(1 - chi); with model A's mixture buoyancy a
//    suspension settles at v_t eps^(1 + chi) = v_t eps^4.7 at Re -> 0, against Richardson & Zaki's 4.65). The
//    yield part is not corrected (no source for one: stated). eps is the fluid fraction the others leave at
//    the particle: the kernel mean of eps_f plus the particle's own part (own_solid_fraction), so that a lone
//    sphere sees eps = 1 exactly and gets the isolated drag.
// 2. Disturbance (the particle's own contribution to u_f(x_p)): the reaction spread by the kernel drags the
//    fluid at the particle along with it, u_f = u_undisturbed - g0 F (F the force on the particle), so beta
//    applied to u_f under-drags. Solving F = beta (u_undisturbed - v) for the measured u_f gives
//    beta_c = beta / (1 - beta g0), beta g0 held at 0.9 at most (see drag.cpp)
//    (Horwitz & Mani 2016, J. Comput. Phys. 318, 85-109; Balachandar, Liu & Lakhote 2019, J. Comput. Phys.
//    376, 160-185). g0 (m/(N s)) is the self-mobility of the smoothed force: the Stokeslet averaged over the
//    source and the read-back, g0 = E[1 / |X - Y|] / (6 pi mu) (its isotropic part; Maxey & Patel 2001: for a
//    Gaussian of standard deviation sigma this is 1 / (6 pi^(3/2) mu sigma), the Stokes velocity of a sphere
//    of radius sigma sqrt(pi)), with X, Y independent draws of what the grid holds of the particle: the kernel
//    (Epanechnikov of half-width a per axis) plus a uniform offset over the cell (the force is spread onto
//    cells and read back from them). E[1 / |X - Y|] = F(h / a) / a is computed exactly by quadrature
//    (kernel_inverse_distance; tabulated in log(h / a)): 2-3.5 % below the moment-matched Gaussian's
//    (sigma^2 = a^2/5 + h^2/12, used before; `sphere` settled 2.4-5.9 % slow with it). mu is the local
//    viscosity of the flow (the kernel mean of the cells' viscosity): in a regularised plug it is huge and the
//    correction vanishes, as the fluid there does not move. Non-cubic cells use h = (h_x h_y h_z)^(1/3).
//    The place. That table is the mean over the particle's place in its cell. Where the kernel's half-width is
//    at most two cells (h >= c d / 4) the caller hands in the place's own g0 instead (mobility.h,
//    disturbance_mobility: the MAC grid's discrete Stokes Green's function, 1 / (mu h) times a lattice sum of
//    G(f - f') w_f w_f' over the particle's own face weights, the component along its slip): at h >= c d the
//    support is no wider than a cell, and g0 moves by -29 to +53 % across it (h/d = 2, c = 2), which the
//    settling sphere followed with the table (-11 to +19 %). Below that width both agree within 0.2 %; by a wall
//    and on non-cubic cells the table stays (the free-space G is not the walled grid's either).
//    The same reaction also returns to the particle through the pressure: the flow's projection gives the
//    longitudinal part of the spread force as grad p, and model A hands the particle -V_p grad p (its kernel
//    mean), k F_d along its drag F_d, k = own_pressure_share (1/3 of the particle's own face-weighted solid
//    fraction: the longitudinal projector averages to 1/3 over the directions, exact for a force on one face
//    of a periodic cubic grid and in the continuum, V_p int K^2 / 3). Maxey & Riley (1983, Phys. Fluids 26,
//    883-889) write the pressure-gradient force with the undisturbed flow; the disturbance's own pressure is
//    part of the Stokes drag (2 pi mu a U of its 6 pi mu a U), so counted again it over-drags (`sphere`: the
//    resolved pressure was +1.6 % of the drag at h = d, +3.5 % at h = d/2). With it, F_d (1 + k) =
//    beta (u_f + g0 F_d - v): beta_c = beta / (1 + k - beta g0).
#pragma once

#include <array>
#include <functional>
#include <optional>

#include "model/coupling/kernel.h"
#include "model/flow/grid.h"

namespace pastemix::coupling {

// One sphere's drag law, as the caller's registry law gives it (SI): D(s) >= 0 (N) non-decreasing, D(0+), and
// the law's Reynolds number at speed s (the Re' of thesis eq. 4.14 for the project's laws).
struct SphereDrag {
  std::function<double(double)> magnitude;  // N, at s (m/s) >= 0
  std::function<double(double)> reynolds;   // -, at s (m/s) > 0
  double rest = 0.0;                        // N, D(0+)
  double rest_speed = 0.0;                  // m/s, where `rest` was evaluated (fluid/drag_kick.h's kRestSpeed)
};

struct DragClosure {
  bool voidage = true;      // Di Felice
  bool disturbance = true;  // self-induced velocity
};

struct DragCoefficients {
  double beta = 0.0;         // kg/s, velocity-dependent part (F = beta (u_f - v_p))
  double yield_force = 0.0;  // N, bounded yield part (sticks against the frozen fluid)
  // m/(N s): the self-mobility g0 the disturbance correction used; 0 without the correction and where beta g0
  // is held at 0.9 (below: the correction is then a bound, not the particle's disturbance). The other force the
  // particle induces at itself, its own hole (coupled_flow.h), is taken out with this value: with the raw g0
  // where the correction is held (the air's viscosity at a free surface: g0 ~ 3e5 m/(N s) for a 10 mm sphere)
  // the hole's velocity was metres per second (the flow tests' air runaways); with the held value 0.9 / beta
  // the dense block of `piston-dem` (Di Felice's factor puts it past the hold), at rest after the push, kept a
  // 5 mm/s shift through its own pressure and dragged the paste down (rise +24 % at 1 cm cells; VALIDATION.md).
  double mobility = 0.0;
};

// Di Felice's exponent at Reynolds number re (> 0; re -> 0 gives 3.7).
double di_felice_chi(double re);
// E[1 / |X - Y|] for X, Y independent, each per axis the unit Epanechnikov kernel plus a uniform offset over a
// cell of width q (in kernel half-widths); by quadrature over E exp(-t^2 Z^2) (1/r = (2 / sqrt(pi)) int
// exp(-r^2 t^2) dt, the axes independent). q -> infinity: 1.8823 / q (two points in a cube).
double kernel_inverse_distance(double q);
// m/(N s): E[1 / |X - Y|] / (6 pi mu) for a = c d / 2 and the cell h.
double self_mobility(double diameter, double width_factor, const std::array<double, 3>& cell, double viscosity);
// The kernel mean of the particle's own solid fraction: V_p sum_c w_pc^2 / V_cell (its own share of the
// interpolated eps_s, removed before the voidage correction).
double own_solid_fraction(const flow::Grid& g, const Stencil& s, double diameter);
// k of the disturbance's pressure (above): V_p prod_axes sum w^2 / V_cell / 3, along each component with the
// face weights (w_pc / 2 to the cell's two faces), the mean of the three components.
double own_pressure_share(const flow::Grid& g, const Stencil& s, double diameter);

// slip: |v_p - u_f(x_p)| (m/s); eps: the fluid fraction the others leave (clamped to (0, 1]); viscosity: local
// (Pa s), for the disturbance; cell: the grid's h; own_pressure: k (own_pressure_share; 0 where the particle's
// reaction does not reach the flow's pressure); mobility: the g0 to use (m/(N s): mobility.h's
// disturbance_mobility at the particle's place), or nullopt for the place-averaged self_mobility at `cell`.
// Throws std::invalid_argument on a negative slip, eps <= 0, a negative k, non-finite inputs or a decreasing D.
DragCoefficients drag_coefficients(const SphereDrag& law, double diameter, double width_factor, double slip, double eps,
                                   double viscosity, const std::array<double, 3>& cell, const DragClosure& closure,
                                   double own_pressure, std::optional<double> mobility = std::nullopt);

}  // namespace pastemix::coupling
