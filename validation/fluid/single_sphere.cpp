// SPDX-License-Identifier: MIT
#include "validation/fluid/single_sphere.h"

#include <cmath>

#include <fmt/format.h>

#include "model/scene.h"

namespace pastemix::validation {

using namespace model;          // the engine these harnesses drive
using namespace model::fluid;

std::string single_sphere_scene(const SphereRun& r, double end_time) {
  const double rad = 0.5 * r.d;
  const double half = r.box_half > 0.0 ? r.box_half : 10.0 * r.depth;
  const double z0 = r.drop >= 0.0 ? r.depth + r.drop + rad : r.depth + r.drop - rad;
  const double top = std::max(z0, r.depth) + 0.1 + 2.0 * r.d;
  const double dom = std::max(half, r.mould_radius);  // m, the domain encloses the fluid box and the mould
  std::string s = fmt::format(
      "seed = 1\ntime_step = {:.17g}\nend_time = {:.17g}\n"
      "[domain]\nmin = [{h:.17g}, {h:.17g}, -0.01]\nmax = [{H:.17g}, {H:.17g}, {top:.17g}]\n"
      "[physics]\nrotation = false\n[contact]\nlaw = \"hertz_mindlin\"\n"
      "[[material]]\nname = \"sphere\"\ndensity = {rho:.17g}\nyoungs_modulus = {E:.17g}\npoisson_ratio = 0.3\n"
      "[[material]]\nname = \"wall\"\ndensity = 7800\nyoungs_modulus = {E:.17g}\npoisson_ratio = 0.3\n"
      "[[interaction]]\nmaterials = \"sphere/sphere\"\nrestitution = 0.5\nfriction = 0.0\n"
      "[[interaction]]\nmaterials = \"sphere/wall\"\nrestitution = 0.5\nfriction = 0.0\n"
      "[[interaction]]\nmaterials = \"wall/wall\"\nrestitution = 0.5\nfriction = 0.0\n"
      "[[particle]]\nmaterial = \"sphere\"\nradius = {rad:.17g}\nposition = [{x0:.17g}, 0, {z0:.17g}]\n"
      "velocity = [0, 0, {vz:.17g}]\n",
      r.dt, end_time, fmt::arg("h", -dom - r.d), fmt::arg("H", dom + r.d), fmt::arg("x0", r.x0), fmt::arg("top", top),
      fmt::arg("rho", r.rho_p), fmt::arg("rad", rad), fmt::arg("z0", z0), fmt::arg("vz", r.vz0), fmt::arg("E", r.youngs_modulus));
  if (r.floor)
    s += "[[wall]]\nname = \"floor\"\ntype = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n";
  if (r.mould_radius > 0.0)
    s += fmt::format("[[wall]]\nname = \"mould\"\ntype = \"cylinder\"\nmaterial = \"wall\"\ncenter = [0, 0]\n"
                     "radius = {:.17g}\nz_min = 0\nz_max = {:.17g}\n",
                     r.mould_radius, r.depth);  // the mould's rim: the paste fills it
  s += fmt::format("[[fluid]]\nx = [{:.17g}, {:.17g}]\ny = [{:.17g}, {:.17g}]\nbottom = 0\nsurface = {:.17g}\n"
                   "density = {:.17g}\n",
                   -half, half, -half, half, r.depth, r.rho_f);
  const auto& info = r.curve.info();
  if (r.tau_y > 0.0 || r.curve.id != drag::CurveId::stokes)
    s += fmt::format("rheology = \"bingham\"\nyield_stress = {:.17g}\nplastic_viscosity = {:.17g}\n", r.tau_y, r.eta);
  else
    s += fmt::format("rheology = \"newtonian\"\nviscosity = {:.17g}\n", r.eta);
  s += fmt::format("curve = \"{}\"\n", info.name);
  if (info.n_coefficients > 0) {
    s += "coefficients = [";
    for (std::size_t k = 0; k < r.curve.coefficients.size(); ++k)
      s += fmt::format("{}{:.17g}", k ? ", " : "", r.curve.coefficients[k]);
    s += "]\n";
  }
  s += fmt::format("buoyancy = {}\nyield_term = {}\npartial_submergence = {}\nsurface_rise = {}\n", r.buoyancy,
                   r.yield_term, r.partial_submergence, r.surface_rise);
  return s;
}

SphereTrace run_single_sphere(const SphereRun& r, double end_time, long rest_steps) {
  const Scene scene = parse_scene(single_sphere_scene(r, end_time), "single_sphere.toml");
  World w = make_world(scene);
  SphereTrace tr;
  tr.surface0 = r.depth;
  const long steps = std::lround(end_time / r.dt);
  auto record = [&] {
    tr.t.push_back(w.time());
    tr.z.push_back(w.particles().x[0].z);
    tr.vz.push_back(w.particles().v[0].z);
  };
  record();
  long at_rest = 0;
  const double rad = 0.5 * r.d;
  for (long s = 0; s < steps; ++s) {
    w.step();
    record();
    const auto& p = w.particles();
    if (p.x[0].z < rad + 1e-3) {
      tr.reached_bottom = true;
      break;
    }
    const bool rest = norm2(p.v[0]) == 0.0 && w.fluid()->inside(0);
    at_rest = rest ? at_rest + 1 : 0;
    if (rest_steps > 0 && at_rest >= rest_steps) break;
  }
  w.check();
  tr.stopped = at_rest > 0;
  tr.surface = w.fluid()->surface_z(0);
  return tr;
}

double settling_distance(const SphereRun& r, const SphereTrace& tr) {
  return tr.surface0 - (tr.z.back() - 0.5 * r.d);
}

}  // namespace pastemix::validation
