// SPDX-License-Identifier: MIT
// Piecewise-linear interface geometry in one cell (PLIC): the paste in a cell is the part of it below a plane.
//
// Coordinates are the cell's unit cube [0,1]^3 (x_d = (X_d - cell corner_d) / h_d). The paste occupies
// { x : n . x <= a } for an outward normal n (pointing from paste into air). The volume below a plane is the
// closed form of Scardovelli & Zaleski (2000, J. Comput. Phys. 164, 228-237), and the inverse (the plane
// constant for a given fraction) a bracketed bisection on it, exact to round-off.
#pragma once

#include <array>

namespace pastemix::flow::plic {

// Fraction of the unit cube with m . x <= a, for m >= 0 (any scale, not all zero).
double cube_fraction(std::array<double, 3> m, double a);

// Plane constant a with the fraction `alpha` (0 < alpha < 1) of the unit cube below n . x = a (any signs).
double plane_constant(const std::array<double, 3>& n, double alpha);

// Fraction of the cell's volume that is paste AND inside the sub-box [lo, hi] of the unit cube.
double box_fraction(const std::array<double, 3>& n, double a, const std::array<double, 3>& lo,
                    const std::array<double, 3>& hi);

}  // namespace pastemix::flow::plic
