// SPDX-License-Identifier: MIT
// The smoothing kernel that carries particle quantities (volume, later force) onto the flow grid's cells and
// cell quantities (the fluid velocity) back to a particle.
//
// Kernel. A product of three 1-D Epanechnikov kernels, K(x) = k(x1) k(x2) k(x3) with
//   k(s) = 3 / (4 a) (1 - (s/a)^2) for |s| <= a, 0 beyond,   a = c d / 2 (m): half-width, d the diameter.
// Why this one: its 1-D cumulative is a cubic, so the integral of K over a box cell is a product of three
// exact differences (no quadrature), and the weights of one particle sum to 1 to round-off; its 1-D marginal
// at c = 1 is the sphere's own (pi (r^2 - s^2)): the kernel is the sphere's volume smeared no wider than needed.
// Its support follows the particle, not the cell (Sun & Xiao 2015's point, without their diffusion solve):
// a 1.18 mm grain in a 10 mm cell lands in one or two cells, a 50 mm rock in 5 mm cells spreads over ~20.
//
// Width. c >= kMinWidthFactor: the peak of one sphere's smoothed solid fraction is 27 pi / (48 c^3) (the
// kernel's centre value times the sphere's volume), which exceeds 1 (a fluid fraction below 0) for c below
// (27 pi / 48)^(1/3) = 1.2091. The default c = 2 puts that peak at 0.22.
//
// Walls. On a bounded axis the part of k beyond a wall is folded back (the mirror image at the wall), so
// nothing is lost and nothing crosses the wall; one fold each side is exact while a <= the box length along
// that axis (checked: std::invalid_argument). On a periodic axis the kernel wraps.
//
// Deposit and interpolation use the same weights w_pc (the kernel's integral over cell c): deposit puts
// q_p w_pc into cell c, interpolation returns sum_c w_pc f_c. They are adjoint, sum_c (deposit q)_c f_c =
// sum_p q_p (interpolate f)_p, which is what will make the drag on the particles equal minus the force on the
// fluid to round-off.
#pragma once

#include <array>
#include <span>
#include <utility>
#include <vector>

#include "model/flow/advection.h"
#include "model/flow/grid.h"

namespace pastemix::coupling {

inline constexpr double kMinWidthFactor = 1.2091;  // (27 pi / 48)^(1/3), rounded up
inline constexpr double kDefaultWidthFactor = 2.0;

// The cells a particle's kernel reaches and their weights, one list per axis (the 3-D weight of cell (i, j, k)
// is the product). Empty when the centre lies outside the grid's box along a bounded axis.
struct Stencil {
  std::array<std::vector<std::pair<int, double>>, 3> axis;
  bool empty() const { return axis[0].empty(); }
};

// Throws std::invalid_argument for c below kMinWidthFactor, a non-positive or non-finite diameter or centre,
// or a half-width a = c d / 2 longer than the box along a bounded axis.
Stencil stencil(const flow::Grid& g, const std::array<double, 3>& centre, double diameter, double width_factor);

// cells[c] += amount w_pc (cells sized g.cell_count()).
void deposit(const flow::Grid& g, const Stencil& s, double amount, std::vector<double>& cells);
// sum_c w_pc f_c.
double interpolate(const flow::Grid& g, const Stencil& s, const std::vector<double>& cell_values);
// Sum of the particle's weights (1 to round-off when its centre is inside the box, 0 when outside).
double weight_sum(const Stencil& s);

// The MAC faces. The velocity at a particle is the kernel's mean of the cell velocities, each component the
// mean of the cell's two faces along it (flow::FlowSolver::cell_velocity); the adjoint spreads an amount (a
// force, N) onto the faces: w_pc / 2 to each of cell c's two faces per component. So sum over the faces of
// (deposit_faces F) u = F . interpolate_velocity(u), and the faces receive exactly F (a wall face's share is
// the wall's: its velocity is fixed).
std::array<double, 3> interpolate_velocity(const flow::Grid& g, const Stencil& s, const flow::Faces& u);
void deposit_faces(const flow::Grid& g, const Stencil& s, const std::array<double, 3>& amount, flow::Faces& faces);

// Solid volume fraction per cell, sum_p V_p w_pc / V_cell (V_p = pi d^3 / 6), from particle centres (m) and
// diameters (m). Particles are added in order, serially: the result is independent of the thread count.
std::vector<double> solid_fraction(const flow::Grid& g, std::span<const std::array<double, 3>> centres,
                                   std::span<const double> diameters, double width_factor);
// The same from the particles' stencils at those centres (stencils[p] = stencil(g, centres[p], ...)).
std::vector<double> solid_fraction(const flow::Grid& g, std::span<const Stencil> stencils, std::span<const double> diameters);

}  // namespace pastemix::coupling
