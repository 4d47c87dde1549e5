// SPDX-License-Identifier: MIT
#include "model/fluid/drag_kick.h"

#include <cmath>
#include <cstdio>

#include <doctest/doctest.h>

#include "model/fluid/buoyancy.h"
#include "model/laws/bingham_dedegil.h"
#include "model/laws/newtonian_stokes.h"

using namespace pastemix;
using namespace pastemix::model::fluid;
using pastemix::model::BinghamDedegil;

namespace {
constexpr double g = 9.81;
using Fluid = BinghamDedegil::Params;  // density, tau_y (0: the Newtonian limit), eta_B
const drag::DragCurve stokes{drag::CurveId::stokes, {}};
// The published curve (thesis eq. 4.19), with its jump at Re' = 1.
const drag::DragCurve published{drag::CurveId::published_4_19, {}};

// Dedegil's drag (the Bingham law, laws/bingham_dedegil.h) of fluid f with curve cd on a sphere of diameter d.
double drag_magnitude(const Fluid& f, const drag::DragCurve& cd, double s, double d) {
  return BinghamDedegil::magnitude(BinghamDedegil::sphere(f, cd, d, 0.0), s);
}

// One kick of the engine's kernel (drag_kick_implicit, as FluidField::kick calls it) with Dedegil's drag of
// fluid f and curve cd for a sphere of diameter d: a lone sphere, so the held rest resistance is D(0+).
Vec kick(const Fluid& f, const drag::DragCurve& cd, double d, const Vec& v, const Vec& F, double m, double h) {
  auto magnitude = [&](double s) { return drag_magnitude(f, cd, s, d); };
  const double d0 = magnitude(kRestSpeed);
  return drag_kick_implicit(magnitude, d0, d0, v, F, m, h);
}
}  // namespace

TEST_CASE("fluid: 0.1 mm grain settling in water matches v_t (1 - exp(-t / tau)) within 0.5 % at any dt") {
  // Thesis Table 4.1: d = 0.1 mm, 2700 kg/m3, water 1000 kg/m3, 1 mPa.s.
  const double d = 1e-4, rho_p = 2700, r = d / 2;
  const Fluid water{1000.0, 0.0, 1e-3};
  const double m = rho_p * kPi * d * d * d / 6.0;
  const double weight = (rho_p - water.density) * g * kPi * d * d * d / 6.0;  // N, gravity minus buoyancy
  const double v_t = (rho_p - water.density) * g * d * d / (18.0 * water.plastic_viscosity);
  const double tau = rho_p * d * d / (18.0 * water.plastic_viscosity);
  CHECK(v_t == doctest::Approx(0.009265).epsilon(1e-3));  // thesis eq. 4.21
  CHECK(tau == doctest::Approx(1.5e-3).epsilon(1e-3));
  (void)r;
  for (double dt : {1e-7, 1e-6, 1e-5, 2.5e-5, 1e-4, 5e-4, 1e-3}) {
    Vec v{0, 0, 0};
    double worst = 0.0;
    const int steps = static_cast<int>(std::lround(0.01 / dt));  // 10 ms = 6.7 tau
    for (int n = 1; n <= steps; ++n) {
      // Velocity Verlet's two half kicks with constant force.
      v = kick(water, stokes, d, v, Vec{0, 0, -weight}, m, 0.5 * dt);
      v = kick(water, stokes, d, v, Vec{0, 0, -weight}, m, 0.5 * dt);
      const double t = n * dt;
      worst = std::max(worst, std::abs(-v[2] - v_t * (1 - std::exp(-t / tau))) / v_t);
    }
    CAPTURE(dt);
    CHECK(worst < 0.005);
    MESSAGE("dt = " << dt << " s: max |v - v_analytic| / v_t = " << worst);
  }
}

TEST_CASE("fluid: a sphere at rest below the yield threshold stays exactly at rest, just above, it sinks") {
  // Paste of the thesis (75 % solids): 1843 kg/m3, tau_y 136 Pa, eta_B 0.7 Pa.s; a steel ball 8135 kg/m3.
  const Fluid paste{1843.0, 136.0, 0.7};
  for (auto curve : {0, 1}) {
    const drag::DragCurve& cd = curve == 0 ? stokes : published;
    // The threshold of this drag model: D(0+) = weight, D(0+) = tau_y d^2 (pi^2/4 + 12 pi/4) with the
    // 24/Re' branch, so tau_y / (g d drho) = (pi/6) / (pi^2/4 + 3 pi) = 0.0440 (Beris et al.: 0.048).
    const double drho = 8135.0 - paste.density;
    const double d_crit = paste.yield_stress / (g * drho * (kPi / 6.0) / (kPi * kPi / 4.0 + 3.0 * kPi));
    for (double factor : {0.99, 1.01}) {
      const double d = d_crit * factor;  // smaller ball: yield wins; larger: gravity wins
      const double m = 8135.0 * kPi * d * d * d / 6.0;
      const double w = drho * g * kPi * d * d * d / 6.0;
      Vec v{0, 0, 0};
      for (int n = 0; n < 20000; ++n) v = kick(paste, cd, d, v, Vec{0, 0, -w}, m, 1e-4);
      if (factor < 1.0) CHECK(v[2] == 0.0);
      else CHECK(v[2] < 0.0);
    }
    CHECK(paste.yield_stress / (g * d_crit * drho) == doctest::Approx(0.0440).epsilon(2e-3));
  }
}

TEST_CASE("fluid: a moving sphere under a sub-threshold force stops and never reverses") {
  const Fluid paste{1843.0, 136.0, 0.7};
  const double d = 0.0126, m = 8135.0 * kPi * d * d * d / 6.0;
  const double w = (8135.0 - 1843.0) * g * kPi * d * d * d / 6.0;  // below D(0+) for 12.6 mm (see above)
  Vec v{0, 0, -1.5};  // impact speed of a 15 cm fall
  bool stopped = false;
  for (int n = 0; n < 100000; ++n) {
    v = kick(paste, published, d, v, Vec{0, 0, -w}, m, 5e-6);
    CHECK(v[2] <= 0.0);  // never upward
    if (v[2] == 0.0) stopped = true;
    if (stopped) CHECK(v[2] == 0.0);  // and, once stopped, stays
  }
  CHECK(stopped);
}

TEST_CASE("fluid: the terminal state satisfies D(v) = net weight") {
  const Fluid clay{1280.0, 30.5, 0.0131};  // Valentik & Whitmore suspension 1
  const drag::DragCurve cd{drag::CurveId::power_sum, {24.0, 3.0, 0.5, 0.4}};  // 24/Re' + 3/sqrt(Re') + 0.4
  const double d = 0.0254, rho_p = 7800.0, m = rho_p * kPi * d * d * d / 6.0;
  const double w = (rho_p - clay.density) * g * kPi * d * d * d / 6.0;
  Vec v{0, 0, 0};
  for (int n = 0; n < 4000; ++n) v = kick(clay, cd, d, v, Vec{0, 0, -w}, m, 1e-3);
  CHECK(drag_magnitude(clay, cd, -v[2], d) == doctest::Approx(w).epsilon(1e-9));
}

TEST_CASE("fluid: submerged volume of a sphere below a free surface") {
  const double r = 0.01, full = 4.0 / 3.0 * kPi * r * r * r;
  CHECK(submerged_volume(0.5, r, 0.0) == 0.0);
  CHECK(submerged_volume(-0.5, r, 0.0) == doctest::Approx(full).epsilon(1e-14));
  CHECK(submerged_volume(0.0, r, 0.0) == doctest::Approx(0.5 * full).epsilon(1e-14));
  const double h = 0.3 * r;  // a cap of depth h
  CHECK(submerged_volume(r - h, r, 0.0) == doctest::Approx(kPi * h * h * (3 * r - h) / 3).epsilon(1e-14));
}

TEST_CASE("fluid: the kick's rest shortcut returns what the iterations return, on both sides of the threshold") {
  // drag_kick_implicit returns v = 0 at once for a sphere at rest whose |F| is below its held resistance
  // (minus 1e-12). The iterated kernel (drag_kick with the slope at 1e-9 m/s, as the iterations take it at
  // rest) must give v = 0 there too, and just above the threshold neither may stop the sphere.
  const Fluid paste{1843.0, 136.0, 0.7};
  const double d = 0.005, m = 2760.0 * kPi * d * d * d / 6.0, h = 5e-6;
  auto magnitude = [&](double s) { return drag_magnitude(paste, published, s, d); };
  const double d0 = magnitude(kRestSpeed);
  const DragSplit at_rest{d0, std::max(0.0, (magnitude(1e-9) - d0) / 1e-9)};
  for (double dir : {0.0, 0.3, 1.2}) {
    for (double rel : {0.5, 1.0 - 1e-9, 1.0 - 2e-12}) {
      const double f = d0 * rel;
      const Vec F{f * std::sin(dir), 0.0, -f * std::cos(dir)};
      const Vec fast = drag_kick_implicit(magnitude, d0, d0, Vec{0, 0, 0}, F, m, h);
      const Vec slow = drag_kick(Vec{0, 0, 0}, F, m, h, at_rest);
      for (int c = 0; c < 3; ++c) CHECK(fast[c] == slow[c]);
      CHECK(fast[2] == 0.0);
    }
    const double f = d0 * (1.0 + 1e-9);
    const Vec F{f * std::sin(dir), 0.0, -f * std::cos(dir)};
    CHECK(drag_kick_implicit(magnitude, d0, d0, Vec{0, 0, 0}, F, m, h)[2] < 0.0);
  }
}

TEST_CASE("fluid: the closed-form kick of a linear drag matches the iterated kernel within 1e-11 m/s") {
  // NewtonianStokes with the Stokes curve is D = 3 pi eta d s exactly: FluidField kicks it with linear_kick
  // (no rest part) instead of drag_kick_implicit, whose slope (D(s) - D(1e-12 m/s)) / s and held rest part
  // D(1e-12 m/s) differ from it by ~1e-12 m/s in the velocity, times the damping a = k h / m <= 1 of a kick
  // (and the rounding of either, ~1e-16 relative). Air and water, grains of 0.1-5 mm, speeds from rest to
  // 3 m/s, half kicks of 1e-6-1e-3 s; and the result is the exact solution v_t + (v - v_t) e^-a.
  using model::NewtonianStokes;
  const drag::DragCurve stokes_curve{drag::CurveId::stokes, {}};
  double worst = 0.0, worst_exact = 0.0;
  for (const NewtonianStokes::Params fluid : {NewtonianStokes::Params{1.2, 1.8e-5}, NewtonianStokes::Params{1000.0, 1e-3}}) {
    for (double d : {1e-4, 1e-3, 5e-3}) {
      const auto sphere = NewtonianStokes::sphere(fluid, stokes_curve, d, 0.0);
      auto magnitude = [&](double s) { return NewtonianStokes::magnitude(sphere, s); };
      const double k = NewtonianStokes::linear_slope(sphere), m = 2760.0 * kPi * d * d * d / 6.0;
      CHECK(k == doctest::Approx(3.0 * kPi * fluid.viscosity * d).epsilon(1e-15));
      CHECK(magnitude(0.37) == doctest::Approx(k * 0.37).epsilon(1e-13));
      const double d0 = magnitude(kRestSpeed);
      for (double h : {1e-6, 1e-5, 1e-4, 1e-3}) {
        const LinearKick c = linear_kick(k, m, h);
        for (double speed : {0.0, 1e-9, 1e-6, 1e-3, 0.1, 3.0}) {
          for (double f_rel : {0.0, 0.3, 1.0, 20.0}) {  // F in units of the weight m g
            const Vec v{0.6 * speed, -0.48 * speed, -0.64 * speed};
            const Vec F{0.1 * f_rel * m * g, 0.0, -f_rel * m * g};
            const Vec fast = apply(c, v, F);
            const Vec slow = drag_kick_implicit(magnitude, d0, d0, v, F, m, h);
            const double e = std::exp(-k * h / m);
            for (int i = 0; i < 3; ++i) {
              const double scale = std::abs(fast[i]);
              worst = std::max(worst, std::abs(fast[i] - slow[i]) / (1e-11 + 1e-13 * scale));
              const double exact = F[i] / k + (v[i] - F[i] / k) * e;  // v_t = F / k
              worst_exact = std::max(worst_exact, std::abs(fast[i] - exact) / (1e-15 + 1e-12 * (std::abs(v[i]) + std::abs(F[i] / k))));
            }
          }
        }
      }
    }
  }
  MESSAGE("linear kick vs iterated kernel: worst |dv| / (1e-11 m/s + 1e-13 |v|) = " << worst
          << "; vs exact solution: worst / (1e-15 + 1e-12 (|v| + |v_t|)) = " << worst_exact);
  CHECK(worst <= 1.0);
  CHECK(worst_exact <= 1.0);
}

TEST_CASE("fluid: the affine-branch kick of a Bingham sphere matches the iterated kernel within 1e-12 m/s + 1e-11 |v|") {
  // On the curve's viscous branch (Cd = 24/Re': the Stokes curve everywhere, the published curve for Re' < 1)
  // Dedegil's drag is D(0+) + k s with k = 3 pi eta_B d, and FluidField kicks it with affine_kick (the factors
  // kept per sphere) instead of drag_kick_implicit, whose slope is the difference quotient
  // (D(s) - D(1e-12 m/s)) / s (taken at 1e-9 m/s near rest: 0.1 % low there, on a velocity of ~1e-9 m/s).
  // Pastes of 0-400 Pa and 0.1-2 Pa.s, spheres of 1-20 mm, half kicks of 2.5e-6-1e-4 s, submerged fractions 1
  // and 0.37, held rest resistance 0.3-2.5 D(0+) (the collective rule's factors), speeds from rest to 0.9 s_max,
  // forces 0-3 times the weight in three directions. Above s_max affine_kick declines (the general kernel runs).
  double worst = 0.0;
  long fast_kicks = 0, declined = 0;
  for (const drag::DragCurve* curve : {&stokes, &published}) {
    for (const Fluid paste : {Fluid{1843.0, 0.0, 0.7}, Fluid{1843.0, 30.0, 0.1}, Fluid{1843.0, 138.0, 0.7},
                              Fluid{1500.0, 400.0, 2.0}}) {
      for (double d : {1e-3, 2.5e-3, 5e-3, 2e-2}) {
        const auto sphere = BinghamDedegil::sphere(paste, *curve, d, 0.0);
        auto magnitude = [&](double s) { return BinghamDedegil::magnitude(sphere, s); };
        const model::AffinePart part = BinghamDedegil::affine_part(sphere);
        CHECK(part.k == doctest::Approx(3.0 * kPi * paste.plastic_viscosity * d).epsilon(1e-14));
        const double d0 = magnitude(kRestSpeed);
        if (curve == &published) {
          // s_max is where Re' = 1: the branch's end.
          CHECK(drag::bingham_reynolds(paste.density, part.s_max, paste.yield_stress, paste.plastic_viscosity, d) ==
                doctest::Approx(1.0).epsilon(1e-12));
        } else {
          CHECK(part.s_max == INFINITY);
        }
        const double s_top = std::min(part.s_max, 3.0);
        for (double s : {1e-6, 1e-3, 0.5 * s_top, 0.99 * s_top})
          CHECK(magnitude(s) == doctest::Approx(d0 + part.k * (s - kRestSpeed)).epsilon(1e-12));
        const double m = 2760.0 * kPi * d * d * d / 6.0;
        const double lim = part.s_max * (1.0 - 1e-6);
        for (double h : {2.5e-6, 1e-5, 1e-4}) {
          for (double phi : {1.0, 0.37}) {
            const LinearKick c = linear_kick(part.k, m / phi, h);
            for (double factor : {1.0, 0.3, 2.5}) {
              const double held = d0 * factor;
              for (double speed : {0.0, 1e-9, 1e-6, 1e-3, 0.05, 0.9 * s_top, 1.1 * part.s_max}) {
                if (!(speed < 10.0)) continue;
                for (double f_rel : {0.0, 0.5, 1.0, 3.0}) {  // F in units of the weight m g
                  for (double dir : {0.0, 1.2, 2.8}) {
                    const Vec v{0.6 * speed, -0.48 * speed, -0.64 * speed};
                    const Vec F{f_rel * m * g * std::sin(dir), 0.1 * f_rel * m * g, -f_rel * m * g * std::cos(dir)};
                    Vec fast{};
                    if (!affine_kick(c, c.gain / phi, held, lim * lim, v, F, fast)) {
                      ++declined;
                      CHECK(speed > 0.5 * s_top);  // only near or above the branch's end
                      continue;
                    }
                    ++fast_kicks;
                    const Vec Fs{F[0] / phi, F[1] / phi, F[2] / phi};
                    const Vec slow = drag_kick_implicit(magnitude, d0, held, v, Fs, m / phi, h);
                    for (int i = 0; i < 3; ++i)
                      worst = std::max(worst, std::abs(fast[i] - slow[i]) / (1e-12 + 1e-11 * std::abs(slow[i])));
                  }
                }
              }
            }
          }
        }
      }
    }
  }
  MESSAGE("affine kick vs iterated kernel: " << fast_kicks << " kicks (" << declined
          << " declined near or above s_max); worst |dv| / (1e-12 m/s + 1e-11 |v|) = " << worst);
  CHECK(fast_kicks > 10000);
  CHECK(declined > 0);
  CHECK(worst <= 1.0);
}
