// SPDX-License-Identifier: MIT
// The rolling law of Ai et al. (2011) type A with the rolling radius R*: its torque on a rolling sphere
// against tau = mu_r F_n R*, on a floor (R* = R) and between two equal spheres (R* = R/2), and the stop
// distance of a sphere rolling on a floor against the analytic (5/7) mu_r g deceleration.
#include "model/laws/constant_torque_rstar.h"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>

#include "model/world.h"
#include "tests/model/scene_text.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

constexpr double kR = 0.005, kMuR = 0.15;  // m, -

std::string scene(const std::string& gravity, const std::string& body) {
  return fmt::format(
             "seed = 3\ntime_step = 2e-6\nend_time = 1.0\n[domain]\nmin = [-0.5, -0.5, -0.05]\nmax = [0.5, 0.5, 1.0]\n"
             "[physics]\ngravity = {}\n[contact]\nlaw = \"hertz_mindlin\"\nrolling = \"constant_torque_rstar\"\n",
             gravity) +
         model::test::material("rock", 2760, 4.68e7, 0.19) + model::test::interaction("rock/rock", 0.5, 0.466, kMuR) +
         body;
}

const std::string kFloor =
    "[[wall]]\nname = \"floor\"\ntype = \"plane\"\nmaterial = \"rock\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n";

std::string sphere(double x, double z, double vx, double wy) {
  return fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = {}\nposition = [{}, 0, {}]\nvelocity = [{}, 0, 0]\n"
                     "angular_velocity = [0, {}, 0]\n",
                     kR, x, z, vx, wy);
}

}  // namespace

TEST_CASE("constant_torque_rstar: the rolling torque on a rolling sphere is mu_r F_n R* (floor: R* = R)") {
  const double v0 = 0.1;
  World w = make_world(model::test::scene_from(scene("[0, 0, -9.81]", kFloor + sphere(0, kR, v0, v0 / kR))));
  const Particles& p = w.particles();
  while (w.time() < 0.01) w.step();  // the first bounce damped out (e = 0.5), still rolling
  REQUIRE(norm(p.omega[0]) > 0.0);
  const double fn = p.f[0].z;  // N: the floor's normal force (its tangential force is horizontal)
  const double overlap = kR - p.x[0].z;
  MESSAGE(fmt::format("floor: capacity {:.9e} N.m, mu_r F_n R {:.9e}, F_n / (m g) {:.6f}, overlap {:.3e} m",
                      p.rolling_capacity[0], kMuR * fn * kR, fn / (p.mass[0] * 9.81), overlap));
  CHECK(p.rolling_capacity[0] == doctest::Approx(kMuR * fn * kR).epsilon(1e-12));
  // The standard law's arm R_i = R - overlap would give a torque smaller by overlap / R.
  CHECK(std::abs(p.rolling_capacity[0] - kMuR * fn * (kR - overlap)) > 0.5 * kMuR * fn * overlap);
  CHECK(fn == doctest::Approx(p.mass[0] * 9.81).epsilon(0.01));
}

TEST_CASE("constant_torque_rstar: between two equal spheres the torque is mu_r F_n R/2") {
  // Head-on at 0.05 m/s each, no gravity, one spinning: during the contact each sphere's friction capacity
  // is mu_r F_n R* with R* = R R / (R + R) = R/2 (the standard law would give mu_r F_n (R - overlap/2)).
  World w = make_world(model::test::scene_from(
      scene("[0, 0, 0]", sphere(-kR - 1e-5, 0.1, 0.05, 3.0) + sphere(kR + 1e-5, 0.1, -0.05, 0.0))));
  const Particles& p = w.particles();
  int checked = 0;
  for (int k = 0; k < 2000; ++k) {
    w.step();
    // N: the normal force on sphere 0, F_n = -f_0 . n (the friction is perpendicular to n, the unit vector from
    // sphere 0 to sphere 1 at the positions the forces were computed at).
    const Vec3 n = (p.x[1] - p.x[0]) * (1.0 / norm(p.x[1] - p.x[0]));
    const double fn = -dot(p.f[0], n);
    if (fn <= 0.0) continue;
    CHECK(p.rolling_capacity[0] == doctest::Approx(kMuR * fn * 0.5 * kR).epsilon(1e-9));
    CHECK(p.rolling_capacity[1] == doctest::Approx(kMuR * fn * 0.5 * kR).epsilon(1e-9));
    ++checked;
  }
  MESSAGE("steps in contact checked: " << checked);
  CHECK(checked > 10);
}

TEST_CASE("constant_torque_rstar: a sphere rolling on a floor stops at v0^2 / (2 (5/7) mu_r g) and stays") {
  // On a floor R* = R: tau = mu_r m g R, rolling without slip (I + m R^2) dw/dt = -tau -> a = 5/7 mu_r g.
  const double v0 = 0.1;
  World w = make_world(model::test::scene_from(scene("[0, 0, -9.81]", kFloor + sphere(0, kR, v0, v0 / kR))));
  const Particles& p = w.particles();
  const double a = 5.0 / 7.0 * kMuR * 9.81, t_stop = v0 / a, d_theory = v0 * v0 / (2 * a);
  while (w.time() < t_stop + 0.1) w.step();
  const double d = p.x[0].x;
  MESSAGE(fmt::format("stop distance {:.5e} m vs theory {:.5e} m ({:+.3f} %)", d, d_theory, 100 * (d / d_theory - 1)));
  CHECK(d == doctest::Approx(d_theory).epsilon(0.02));
  CHECK(norm(p.omega[0]) < 1e-9);
}
