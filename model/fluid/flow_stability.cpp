// SPDX-License-Identifier: MIT
#include "model/fluid/flow_stability.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "base/error.h"
#include "base/units.h"
#include "model/flow/solver.h"
#include "model/fluid/flow_coupling.h"
#include "model/scene.h"

namespace pastemix::model::fluid {

namespace {

constexpr double kRho = 2760.0, kPaste = 1800.0;  // kg/m3
constexpr double kRayleighShare = 0.2;           // the DEM step over the spheres' Rayleigh time

// The box (a whole number of cells around the bed or the stream), the paste and the spheres.
std::string stability_scene(const StabilitySettings& s, double dt, double eta, long& spheres) {
  const double d = s.diameter, c = s.cell;
  const bool bed = s.name == "bed";
  const double side = std::ceil(s.layers * d * 1.0001 / c) * c;  // m, the box's horizontal side
  const double height = bed ? std::ceil(3.0 * s.layers * d / c) * c : std::ceil(8.0 * s.layers * d / c) * c;
  const double surface = bed ? 1.5 * s.layers * d : 0.3 * height;
  std::string text = fmt::format(
      "seed = 5\ntime_step = {}\nend_time = {}\n[domain]\nmin = [-0.01, -0.01, -0.01]\nmax = [{}, {}, {}]\n"
      "[physics]\nrotation = true\n[contact]\nlaw = \"hertz_mindlin\"\n[[material]]\nname = \"rock\"\n"
      "density = {}\nyoungs_modulus = 4.68e7\npoisson_ratio = 0.19\n[[interaction]]\nmaterials = \"rock/rock\"\n"
      "restitution = 0.5\nfriction = 0.5\n[[wall]]\nname = \"box\"\ntype = \"box\"\nmaterial = \"rock\"\n"
      "min = [0, 0, 0]\nmax = [{}, {}, {}]\n"
      "[[fluid]]\nname = \"paste\"\nx = [0.0, {}]\ny = [0.0, {}]\nbottom = 0.0\nsurface = {}\ndensity = {}\n"
      "rheology = \"newtonian\"\nviscosity = {}\ncurve = \"stokes\"\ndynamics = \"flow\"\ncell = {}\ntop = {}\n"
      "coupling_interval = {}\n",
      dt, s.time, side + 0.01, side + 0.01, height + 0.01, kRho, side, side, height, side, side, surface, kPaste, eta,
      c, height, s.interval);
  const double pitch = d * (1.0 + 1e-6);  // touching within 5 nm: the scene refuses an overlap
  if (bed) {
    // Simple cubic from the floor, centred in the box: eps_s = pi / 6 inside the lattice.
    const double x0 = 0.5 * (side - (s.layers - 1) * pitch);
    for (int k = 0; k < s.layers; ++k)
      for (int j = 0; j < s.layers; ++j)
        for (int i = 0; i < s.layers; ++i)
          text += fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = {}\nposition = [{}, {}, {}]\n", 0.5 * d,
                              x0 + i * pitch, x0 + j * pitch, 0.5 * pitch + k * pitch);
    spheres = static_cast<long>(s.layers) * s.layers * s.layers;
    return text;
  }
  // The stream: a random fill of a column in the air above the paste, falling at 1 m/s.
  const double mass = 10.0 * s.layers * kRho * units::pi * d * d * d / 6.0;
  text += fmt::format("[[factory]]\nmaterial = \"rock\"\nmass = {}\nshape = \"box\"\nmin = [{}, {}, {}]\n"
                      "max = [{}, {}, {}]\nvelocity = [0, 0, -1.0]\n[[factory.psd]]\nd_min = {}\nd_max = {}\nfraction = 1.0\n",
                      mass, 0.2 * side, 0.2 * side, surface + 2.0 * d, 0.8 * side, 0.8 * side,
                      std::min(height - d, surface + 2.0 * d + 3.0 * s.layers * d), d, d * 1.0001);
  spheres = -1;
  return text;
}

// J: kinetic energy of the fluid (the faces' masses eps_f rho V and velocities).
double fluid_kinetic(const flow::FlowSolver& f) {
  const flow::Faces m = f.fluid_mass();
  double k = 0.0;
  for (int c = 0; c < 3; ++c)
    for (std::size_t q = 0; q < m[c].size(); ++q) k += 0.5 * m[c][q] * f.velocity()[c][q] * f.velocity()[c][q];
  return k;
}

}  // namespace

StabilityResult run_stability(const StabilitySettings& s) {
  if (s.name != "bed" && s.name != "stream")
    throw InputError("validate coupling", 0, "case", fmt::format("unknown stability case '{}' (bed, stream)", s.name));
  const OneThread one;  // a validation case of one thread (flow_coupling.h)
  const auto t0 = std::chrono::steady_clock::now();
  StabilityResult r;
  // The step: 20 % of the Rayleigh time pi r sqrt(rho / G) / (0.8766 + 0.163 nu) (G = E / (2 (1 + nu))); the
  // paste's viscosity then makes tau = m / (3 pi eta d) the step over `relaxations`.
  const double radius = 0.5 * s.diameter, G = 4.68e7 / (2.0 * 1.19);
  r.dt = kRayleighShare * units::pi * radius * std::sqrt(kRho / G) / (0.8766 + 0.163 * 0.19);
  r.tau = r.dt / s.relaxations;
  const double m = kRho * units::pi * s.diameter * s.diameter * s.diameter / 6.0;
  r.viscosity = m / (3.0 * units::pi * s.diameter * r.tau);
  const Scene scene = parse_scene(stability_scene(s, r.dt, r.viscosity, r.spheres), fmt::format("{} (model/fluid/flow_stability.cpp)", s.name));
  World w = make_world(scene);
  r.spheres = static_cast<long>(w.particles().size());
  const long steps = std::lround(s.time / r.dt);
  const Energies e0 = w.energies();
  const double pe0 = e0.potential;
  double v0 = 0.0;  // m3: the paste's volume once the particles are in the grid (the first step's start)
  const double k0 = e0.kinetic + e0.rotational + fluid_kinetic(w.flow()->solver());
  const long every = steps / 50 + 1;  // ~50 samples
  r.growth = -INFINITY;
  for (long n = 0; n < steps; n += every) {
    w.advance(std::min(every, steps - n));
    w.check();
    if (n == 0) v0 = w.flow()->paste_volume();
    const Energies e = w.energies();
    const double k = e.kinetic + e.rotational + fluid_kinetic(w.flow()->solver());
    const double released = pe0 - e.potential;
    r.growth = std::max(r.growth, k - k0 - released);
    r.budget = std::max(r.budget, k0 + released);
    for (const Vec3& v : w.particles().v) r.max_speed = std::max(r.max_speed, norm(v));
    r.kinetic_end = k, r.released_end = released;
    ++r.samples;
  }
  r.steps = w.steps(), r.cycles = w.flow()->cycles();
  r.paste_volume_error = std::abs(w.flow()->paste_volume() - v0) / v0;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace pastemix::model::fluid
