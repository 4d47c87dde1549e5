// SPDX-License-Identifier: MIT
// The place-aware self-mobility of a particle's smoothed force on the MAC grid (issue 18, `sphere` at h >= c d):
// the velocity its own reaction induces at it, read back through the same face weights that spread it.
//
// Why. drag.h's g0 is a continuum model averaged over the particle's place in its cell (kernel + a uniform
// offset over the cell). Where the kernel spans a few cells that is within 0.8 % of what the grid does; where
// its support is no wider than a cell (h >= c d) the real self-induced velocity depends on the place: at
// h/d = 2 the sphere settled 19 % fast at a cell's centre (the force on one cell's faces) and 11 % slow on the
// faces (spread over two) with the place-averaged g0 (VALIDATION.md).
//
// The grid's own Green's function. Steady Stokes on the MAC grid (the 7-point Laplacian on each component's
// faces, the staggered divergence and gradient) is diagonal in Fourier space: with s_d = 2 - 2 cos(k_d h),
// lambda = sum_d s_d / h^2 and the difference symbols D_d = (exp(i k_d h) - 1) / h (|D_d|^2 = s_d / h^2),
//   G^(k) = (I - D D^H / lambda) / (mu lambda),   k != 0,
// so a force F on one face of component c moves the faces of component c at offset r (cells) by
//   u = F G_cc(r) / (mu h),   G_cc(r) = (1 / N^3) sum_{k != 0} (lambda - s_c) / lambda^2 prod_d cos(k_d r_d)
// (unit h; the periodic N^3 box; even in each r_d). Tabulated once for |r_d| <= reach by a direct sum over the
// k of one octant (LatticeStokes). The box's images are then taken out with Hasimoto's (1959) self-term: a point
// force in a periodic box of side L moves at its free-space velocity less 2.8373 F / (6 pi mu L) (isotropic,
// the mean velocity 0; the next terms are O(r^2 / L^3)), so G_free = G_periodic + 2.8373 / (6 pi N): the
// table is the unbounded grid's. (The simulation's own periodic box is physical and stays in the flow.)
// Check: G_xx(0) = (2/3) W / 2 = 0.168487 (W = 0.505462, Watson's simple-cubic integral: the trace of the
// projector is 2 and the scalar lattice Green's function at 0 is W / 2), and N = 32 and 64 agree (test).
//
// The particle's mobility. The exchange (exchange.h) reads u_p,c = sum_f W_cf u_f and spreads -F_c W_cf, with
// W_cf the kernel's cell weights w_x w_y w_z, split half to each of the cell's two faces along c. Per axis the
// weights are 1-D lists, so the self-mobility is separable in the offsets:
//   M_cc = sum_r G_cc(r) prod_d A_d^c(r_d) / (mu h),   A_d^c(r) = sum_i v_i v_{i+r},
// v the axis's face weights (d = c) or cell weights (d != c): (2m + 1)^3 terms for m weights per axis.
// Not used (std::nullopt, the caller keeps the place-averaged table): on non-cubic cells, where the kernel
// reaches a bounded axis's end cells (the kernel's reflection and the wall's no-slip make the free-space G
// wrong either way: today's table kept there), where it spans more than half a periodic axis, or past the
// table's reach.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "model/coupling/kernel.h"
#include "model/flow/grid.h"

namespace pastemix::coupling {

// Hasimoto's (1959) self-term of a periodic cubic array of point forces: -kHasimotoSelf F / (6 pi mu L).
inline constexpr double kHasimotoSelf = 2.837297;

// G_xx(r) of the unit MAC grid (unit h, unit mu) for 0 <= r_d <= reach, from a periodic n^3 box; the other
// components by permuting the axes.
class LatticeStokes {
 public:
  // free_space: add Hasimoto's self-term 2.8373 / (6 pi n). Throws std::invalid_argument unless
  // 2 reach + 2 <= n, n even.
  LatticeStokes(int n, int reach, bool free_space = true);
  int reach() const { return reach_; }
  // G_cc at offset r (cells; any sign, |r_d| <= reach).
  double component(int c, const std::array<int, 3>& r) const;
  // G_cc(x, y, z) = data()[x s0 + y s1 + z s2] for 0 <= x, y, z <= reach, {s0, s1, s2} = strides(c).
  const double* data() const { return table_.data(); }
  std::array<std::size_t, 3> strides(int c) const;

 private:
  double xx(int rx, int ry, int rz) const {
    const std::size_t r1 = reach_ + 1;
    return table_[(rx * r1 + ry) * r1 + rz];
  }
  int reach_;
  std::vector<double> table_;
};

// The free-space table the drag uses (n = 128, reach 6), built on first use (~5 ms; thread-safe).
const LatticeStokes& lattice_stokes();

// m/(N s): M_cc, c = 0..2, the particle's self-mobility through its own face weights (above), or nullopt where
// it does not apply. table: the lattice to use (lattice_stokes() by default).
std::optional<std::array<double, 3>> place_mobility(const flow::Grid& g, const Stencil& s, double viscosity,
                                                    const LatticeStokes& table = lattice_stokes());

// The place-aware g0 is used where the kernel's half-width a = c d / 2 is at most this many cells (h >= c d / 4:
// h >= d / 2 at c = 2). There its place-averaged mean is the table's to 0.04 % and a single place is within
// 0.2 % of it (the switch does not jump); at h = c d / 2 a single place is -0.2 to +1.3 % off the table, at
// h = c d -29 to +53 % (zz; VALIDATION.md). Wider kernels keep the table (their offsets pass the lattice's reach).
inline constexpr double kPlaceAwareHalfWidth = 2.0;

// m/(N s): the g0 the drag's disturbance correction uses (drag.h) for a particle of `diameter` at stencil s:
// the place-aware M along the slip (sum_c n_c^2 M_cc, n = slip / |slip|; the mean of the three at zero slip:
// the drag, its reaction and the read-back are along the slip) where a <= kPlaceAwareHalfWidth h and M applies,
// else the place-averaged table (self_mobility).
double disturbance_mobility(const flow::Grid& g, const Stencil& s, double diameter, double width_factor,
                            double viscosity, const std::array<double, 3>& slip);

}  // namespace pastemix::coupling
