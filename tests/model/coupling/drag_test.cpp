// SPDX-License-Identifier: MIT
// The exchange's drag (model/coupling/drag.h) with the project's registry laws: Bingham-Dedegil on the Stokes
// curve against its closed form (rest part (pi^2/4 + 3 pi) d^2 tau_y, slope 3 pi eta_B d), Di Felice's voidage
// exponent at known points, a lone sphere seeing eps = 1 exactly, the kernel's self-mobility against Monte
// Carlo and a cube's closed value, and bad input.
#include "model/coupling/drag.h"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "base/drag_curves.h"
#include "model/fluid/drag_kick.h"
#include "model/laws/bingham_dedegil.h"
#include "model/laws/newtonian_stokes.h"

using namespace pastemix;
using coupling::DragClosure;
using coupling::SphereDrag;

namespace {

constexpr double pi = std::numbers::pi;

template <class Law>
SphereDrag registry_drag(const typename Law::Params& prm, const drag::DragCurve& curve, double d, double y,
                         double tau_y, double eta) {
  const auto sphere = Law::sphere(prm, curve, d, y);
  SphereDrag s;
  s.magnitude = [sphere](double v) { return Law::magnitude(sphere, v); };
  s.reynolds = [=](double v) { return drag::bingham_reynolds(prm.density, v, tau_y, eta, d); };
  s.rest = Law::magnitude(sphere, model::fluid::kRestSpeed);
  s.rest_speed = model::fluid::kRestSpeed;
  return s;
}

}  // namespace

TEST_CASE("coupling drag: Bingham-Dedegil on the Stokes curve splits into its closed-form yield part and slope") {
  const model::BinghamDedegil::Params prm{1843.0, 136.0, 0.7};
  const drag::DragCurve stokes{drag::CurveId::stokes, {}};
  const double d = 0.0126;
  const SphereDrag law = registry_drag<model::BinghamDedegil>(prm, stokes, d, 0.1, 136.0, 0.7);
  const double rest = (pi * pi / 4.0 + 3.0 * pi) * d * d * 136.0, slope = 3.0 * pi * 0.7 * d;
  CHECK(law.rest == doctest::Approx(rest).epsilon(1e-9));
  const DragClosure none{false, false};
  for (double slip : {0.0, 1e-6, 0.01, 0.3, 2.0}) {
    const auto c = coupling::drag_coefficients(law, d, 2.0, slip, 1.0, 0.7, {0.01, 0.01, 0.01}, none, 0.0);
    CHECK(c.yield_force == doctest::Approx(rest).epsilon(1e-9));
    // At slip 0 the slope is the difference at 1e-9 m/s over a rest part of ~0.2 N: round-off ~3e-7 of it.
    CHECK(c.beta == doctest::Approx(slope).epsilon(slip > 1e-4 ? 1e-9 : 1e-6));
  }
}

TEST_CASE("coupling drag: Di Felice's exponent and the voidage factor eps^(1 - chi) on a Stokes drag") {
  CHECK(coupling::di_felice_chi(std::pow(10.0, 1.5)) == doctest::Approx(3.05).epsilon(1e-14));
  CHECK(coupling::di_felice_chi(0.0) == 3.7);
  CHECK(coupling::di_felice_chi(1e-8) == doctest::Approx(3.7).epsilon(1e-12));
  CHECK(coupling::di_felice_chi(1.0) == doctest::Approx(3.7 - 0.65 * std::exp(-1.125)).epsilon(1e-14));
  const model::NewtonianStokes::Params water{1000.0, 1e-3};
  const drag::DragCurve stokes{drag::CurveId::stokes, {}};
  const double d = 1e-3;
  const SphereDrag law = registry_drag<model::NewtonianStokes>(water, stokes, d, 0.0, 0.0, 1e-3);
  const DragClosure voidage{true, false};
  for (double eps : {1.0, 0.9, 0.7, 0.45}) {
    const double slip = 1e-4;  // Re = rho eps slip d / mu = 0.1 eps
    const double chi = coupling::di_felice_chi(1000.0 * eps * slip * d / 1e-3);
    const auto c = coupling::drag_coefficients(law, d, 2.0, slip, eps, 1e-3, {0.01, 0.01, 0.01}, voidage, 0.0);
    CHECK(c.beta == doctest::Approx(3.0 * pi * 1e-3 * d * std::pow(eps, 1.0 - chi)).epsilon(1e-9));
    CHECK(c.yield_force < 1e-16);  // D(1e-12 m/s): the Stokes rest value, 3 pi mu d 1e-12
  }
}

TEST_CASE("coupling drag: a lone sphere's own part of the interpolated solid fraction is removed exactly") {
  flow::Grid g;
  g.n = {10, 8, 9};
  g.h = {0.005, 0.005, 0.005};
  for (auto& b : g.bc) b.type = flow::BoundaryType::no_slip;
  g.bc[0].type = g.bc[1].type = flow::BoundaryType::periodic;
  for (double d : {0.00118, 0.006, 0.02}) {
    const std::array<double, 3> x{0.0213, 0.0011 + d / 2, 0.0233};  // near the y wall: the folded kernel
    const std::vector<std::array<double, 3>> centres{x};
    const std::vector<double> diameters{d};
    const std::vector<double> eps_s = coupling::solid_fraction(g, centres, diameters, 2.0);
    const coupling::Stencil s = coupling::stencil(g, x, d, 2.0);
    const double seen = coupling::interpolate(g, s, eps_s), own = coupling::own_solid_fraction(g, s, d);
    CHECK(seen > 0.0);
    CHECK(std::abs((1.0 - seen) + own - 1.0) < 1e-15);
  }
}

TEST_CASE("coupling drag: the kernel's self-mobility against Monte Carlo and the cube's limit, and the correction") {
  // E[1/|X - Y|] of the unit kernel plus a cell of q half-widths: Monte Carlo with 8e6 pairs (numpy, seed 7;
  // noise ~4e-4) at q = 0, 0.5, 1, 2, 8; a cube of side q: 1.882312645 / q (twice the electrostatic self-energy
  // of a uniform cube, 0.9411563 Q^2 / (4 pi eps0 a)).
  const double q[] = {0.001, 0.5, 1.0, 2.0, 8.0}, mc[] = {1.2195135, 1.1662135, 1.0375827, 0.7544890, 0.2308843};
  for (int i = 0; i < 5; ++i) CHECK(coupling::kernel_inverse_distance(q[i]) == doctest::Approx(mc[i]).epsilon(2e-3));
  CHECK(coupling::kernel_inverse_distance(500.0) * 500.0 == doctest::Approx(1.882312645).epsilon(2e-3));
  const double d = 0.01, c = 2.0, mu = 0.7, h = 0.01;  // a = d = h: q = 1
  const double g0 = coupling::self_mobility(d, c, {h, h, h}, mu);
  CHECK(g0 == doctest::Approx(coupling::kernel_inverse_distance(1.0) / (0.5 * c * d) / (6.0 * pi * mu)).epsilon(1e-4));
  const model::NewtonianStokes::Params paste{1843.0, mu};
  const drag::DragCurve stokes{drag::CurveId::stokes, {}};
  const SphereDrag law = registry_drag<model::NewtonianStokes>(paste, stokes, d, 0.0, 0.0, mu);
  const double beta = 3.0 * pi * mu * d;
  const auto k = coupling::drag_coefficients(law, d, c, 0.01, 1.0, mu, {h, h, h}, DragClosure{false, true}, 0.0);
  CHECK(beta * g0 < 0.9);
  CHECK(k.beta == doctest::Approx(beta / (1.0 - beta * g0)).epsilon(1e-9));
  // In a regularised plug (viscosity 1e6 times higher) the fluid does not move: no correction left.
  const auto plug = coupling::drag_coefficients(law, d, c, 0.01, 1.0, mu * 1e6, {h, h, h}, DragClosure{false, true}, 0.0);
  CHECK(plug.beta == doctest::Approx(beta).epsilon(1e-5));
  // The disturbance's own pressure k (drag.h): beta / (1 + k - beta g0).
  const auto kp = coupling::drag_coefficients(law, d, c, 0.01, 1.0, mu, {h, h, h}, DragClosure{false, true}, 0.02);
  CHECK(kp.beta == doctest::Approx(beta / (1.02 - beta * g0)).epsilon(1e-9));
}

TEST_CASE("coupling drag: the correction's mobility (for the own hole) is g0, and none where beta g0 is held or off") {
  const double d = 0.01, c = 2.0, mu = 0.7, h = 0.01;
  const model::NewtonianStokes::Params paste{1843.0, mu};
  const drag::DragCurve stokes{drag::CurveId::stokes, {}};
  const SphereDrag law = registry_drag<model::NewtonianStokes>(paste, stokes, d, 0.0, 0.0, mu);
  const double beta = 3.0 * pi * mu * d;
  const DragClosure on{false, true};
  const auto paste_side = coupling::drag_coefficients(law, d, c, 0.01, 1.0, mu, {h, h, h}, on, 0.0);
  CHECK(paste_side.mobility == coupling::self_mobility(d, c, {h, h, h}, mu));
  // The kernel in the air (its local viscosity 1.8e-5 Pa s, the paste's drag law): beta g0 ~ 2e4, held at 0.9;
  // the hole's mobility is then none (with g0 the hole's velocity was metres per second at a free surface).
  const double air = 1.8e-5;
  CHECK(beta * coupling::self_mobility(d, c, {h, h, h}, air) > 0.9);
  const auto air_side = coupling::drag_coefficients(law, d, c, 0.01, 1.0, air, {h, h, h}, on, 0.0);
  CHECK(air_side.beta == doctest::Approx(beta / (1.0 - 0.9)).epsilon(1e-9));
  CHECK(air_side.mobility == 0.0);
  CHECK(coupling::drag_coefficients(law, d, c, 0.01, 1.0, mu, {h, h, h}, DragClosure{false, false}, 0.0).mobility == 0.0);
  // A g0 handed in (mobility.h: the place's own) replaces the table, in the correction and for the hole.
  const double g_place = 1.3 * coupling::self_mobility(d, c, {h, h, h}, mu);
  const auto placed = coupling::drag_coefficients(law, d, c, 0.01, 1.0, mu, {h, h, h}, on, 0.01, g_place);
  CHECK(placed.beta == doctest::Approx(beta / (1.01 - beta * g_place)).epsilon(1e-9));
  CHECK(placed.mobility == g_place);
  CHECK_THROWS_AS(coupling::drag_coefficients(law, d, c, 0.01, 1.0, mu, {h, h, h}, on, 0.0, -1.0), std::invalid_argument);
}

TEST_CASE("coupling drag: the disturbance's own pressure share tends to V_p int K^2 / 3 on fine cells") {
  // Continuum: int k^2 = 3 / (5 a) per axis, so V_p (3 / (5 a))^3 / 3; c = 2 (a = d): 27 pi / 2250 = 0.0377.
  const double d = 0.01, c = 2.0, a = 0.5 * c * d;
  const double continuum = pi * d * d * d / 6.0 * std::pow(3.0 / (5.0 * a), 3) / 3.0;
  flow::Grid g;
  g.n = {64, 64, 64};
  g.h = {d / 16, d / 16, d / 16};
  for (auto& b : g.bc) b.type = flow::BoundaryType::periodic;
  const auto s = coupling::stencil(g, {0.0213, 0.0177, 0.0301}, d, c);
  CHECK(coupling::own_pressure_share(g, s, d) == doctest::Approx(continuum).epsilon(2e-3));
  // Coarse cells: the face weights along each component spread the kernel over one cell more, so k falls below
  // a third of own_solid_fraction (which is the cells' sum alone).
  g.n = {8, 8, 8};
  g.h = {d, d, d};
  const auto coarse = coupling::stencil(g, {0.0296, 0.0328, 0.0424}, d, c);
  const double k = coupling::own_pressure_share(g, coarse, d);
  CHECK(k > 0.0);
  CHECK(k < coupling::own_solid_fraction(g, coarse, d) / 3.0);
}

TEST_CASE("coupling drag: bad input is an error") {
  const model::NewtonianStokes::Params water{1000.0, 1e-3};
  const drag::DragCurve stokes{drag::CurveId::stokes, {}};
  const SphereDrag law = registry_drag<model::NewtonianStokes>(water, stokes, 1e-3, 0.0, 0.0, 1e-3);
  const std::array<double, 3> h{0.01, 0.01, 0.01};
  CHECK_THROWS_AS(coupling::drag_coefficients(law, 1e-3, 2.0, -1.0, 1.0, 1e-3, h, {}, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(coupling::drag_coefficients(law, 1e-3, 2.0, NAN, 1.0, 1e-3, h, {}, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(coupling::drag_coefficients(law, 1e-3, 2.0, 0.1, 0.0, 1e-3, h, {}, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(coupling::drag_coefficients(law, 1e-3, 2.0, 0.1, 1.0, 0.0, h, {}, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(coupling::drag_coefficients(law, 1e-3, 2.0, 0.1, 1.0, 1e-3, h, {}, -0.01), std::invalid_argument);
  SphereDrag bad = law;
  bad.rest = 1.0;  // above D(s) at small s: a decreasing law
  CHECK_THROWS_AS(coupling::drag_coefficients(bad, 1e-3, 2.0, 1e-6, 1.0, 1e-3, h, {}, 0.0), std::invalid_argument);
}
