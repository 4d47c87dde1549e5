// SPDX-License-Identifier: MIT
#include "model/fluid/fluid_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "base/error.h"
#include "model/coupling/kernel.h"
#include "model/laws/registry.h"

namespace pastemix::model::fluid {

namespace {

constexpr double kMaxCellAspect = 1.2;  // -, largest over smallest cell side of a `cells = [nx, ny, nz]` grid

drag::CurveId curve_by_name(const Params& p, std::string_view key, const std::string& name) {
  auto id = drag::find_curve(name);
  if (!id) {
    std::string known;
    for (const auto& c : drag::kCurves) known += fmt::format("{}{}", known.empty() ? "" : ", ", c.name);
    p.fail(key, fmt::format("unknown drag curve '{}' (known: {})", name, known));
  }
  return *id;
}

drag::DragCurve read_curve(const Params& f, const std::string& scene_path, const std::string& fallback) {
  if (f.has("curve") && f.has("curve_from")) f.fail("curve_from", "give either curve or curve_from, not both");
  drag::DragCurve c;
  if (f.has("curve_from")) {
    std::filesystem::path file = f.string("curve_from");
    if (file.is_relative()) file = std::filesystem::path(scene_path).parent_path() / file;
    if (!std::filesystem::exists(file)) f.fail("curve_from", fmt::format("no such file: {}", file.string()));
    return read_chosen_curve(file.string());
  }
  const std::string name = f.string_or("curve", fallback);
  c.id = curve_by_name(f, "curve", name);
  const auto& info = c.info();
  if (info.n_coefficients > 0) {
    c.coefficients = f.numbers("coefficients");
    const auto why = drag::check_coefficients(c.id, c.coefficients);
    if (!why.empty())
      f.fail("coefficients", fmt::format("{} for curve {} ({} coefficients: {})", why, name, info.n_coefficients,
                                         info.formula));
  } else if (f.has("coefficients")) {
    f.fail("coefficients", fmt::format("curve {} takes no coefficients", name));
  }
  return c;
}

// The name of the drag law that takes a lab store's paste rheology (the one with from_store).
std::string store_law() {
  std::string name;
  for (const std::string& n : DragLaws::names())
    DragLaws::with(n, [&](auto law) {
      using Law = typename decltype(law)::type;
      if constexpr (requires { Law::from_store(1.0, 1.0, 1.0); }) name = Law::name;
    });
  return name;
}

// [[fluid]] rheology_from = STORE: tau_y, eta_B and the density at the region's solids content, read from the
// lab parameter store (never numbers typed into the scene), with the drag curve the store's eta_B belongs to.
void read_rheology_from(const Params& f, const std::string& scene_path, const std::string& law, FluidRegion& r) {
  if (law != store_law())
    f.fail("rheology_from", fmt::format("a store's paste rheology is {0}: set rheology = \"{0}\"", store_law()));
  for (const char* key : {"yield_stress", "plastic_viscosity", "density", "viscosity"})
    if (f.has(key)) f.fail(key, fmt::format("give either rheology_from or {}, not both", key));
  if (!f.has("solids_fraction")) f.fail("rheology_from", "needs solids_fraction (which of the store's pastes)");
  r.solids_fraction = f.number("solids_fraction", Range::fraction);
  std::filesystem::path file = f.string("rheology_from");
  if (file.is_relative()) file = std::filesystem::path(scene_path).parent_path() / file;
  if (!std::filesystem::exists(file))
    f.fail("rheology_from", fmt::format("no such parameter store: {} (run `pastemix lab reduce datasets/thesis --out "
                                        "out/lab` first)",
                                        file.string()));
  StoreRheology s;
  try {
    s = read_store_rheology(file.string(), r.solids_fraction,
                            f.choice_or("rheology_at", {"value", "minus_sd", "plus_sd"}, "value"));
  } catch (const InputError& e) {  // name the scene's key too: the fix may be in either file
    f.fail("rheology_from", e.what());
  }
  DragLaws::with(law, [&](auto l) {
    using Law = typename decltype(l)::type;
    if constexpr (requires { Law::from_store(1.0, 1.0, 1.0); })
      r.law = Law::from_store(s.density, s.yield_stress, s.plastic_viscosity);
  });
  if (!f.has("curve") && !f.has("curve_from")) f.fail("curve", fmt::format("name the drag curve (the store's eta_B belongs to {})", s.curve));
  r.curve = read_curve(f, scene_path, "");
  if (s.curve != r.curve.info().name)
    f.fail("curve", fmt::format("the store's eta_B ({}) belongs to drag curve {}, the scene uses {}", s.key,
                                s.curve, r.curve.info().name));
}

// The region's drag law (rheology = NAME of DragLaws), its values from its own keys, and its curve.
void read_drag_law(const Params& f, const std::string& scene_path, FluidRegion& r) {
  const std::string law = f.choice("rheology", DragLaws::names());
  if (f.has("rheology_at") && !f.has("rheology_from")) f.fail("rheology_at", "needs rheology_from");
  if (f.has("rheology_from")) return read_rheology_from(f, scene_path, law, r);
  DragLaws::with(law, [&](auto l) {
    using Law = typename decltype(l)::type;
    r.law = Law::from_params(f);
    const std::string fallback = Law::default_curve;
    if (fallback.empty() && !f.has("curve") && !f.has("curve_from"))
      f.fail("curve", fmt::format("a {} fluid needs curve = NAME (with coefficients) or curve_from = FILE", law));
    r.curve = read_curve(f, scene_path, fallback);
  });
}

constexpr const char* kFlowKeys[] = {"cell", "cells", "top", "kernel_width", "coupling_interval", "regularisation",
                                     "flow_time_step", "implicit_stick"};

void read_flow_numerics(const Params& f, FluidRegion& r, const Vec3& domain_max);

// [[fluid]] dynamics (fluid_scene.h): "at_rest" (the default) or "flow", whose numerics (grid, kernel, coupling
// interval, regularisation, sub-step, stick) are read from the region's table or from its [fluid.flow] sub-table,
// checked against the region and the domain and kept in r. A region at rest may carry the sub-table: the frozen
// numerics of its flow variant (the shipped mixing scenes use mixing_flow.overrides.toml instead), read and
// checked as for "flow" but not used; --set fluid.N.dynamics=flow then runs with them.
void read_dynamics(const Params& f, FluidRegion& r, const Vec3& domain_max) {
  const bool flow = f.choice_or("dynamics", {"at_rest", "flow"}, "at_rest") == "flow";
  const std::optional<Params> sub = f.optional_table("flow");
  for (const char* key : kFlowKeys)
    if (f.has(key)) {
      if (sub) f.fail(key, fmt::format("{} is set both here and in the region's [fluid.flow] table: keep one", key));
      if (!flow) f.fail(key, fmt::format("{} is a key of dynamics = \"flow\" (this region is at rest; a region at rest "
                                         "keeps its flow numerics in a [fluid.flow] sub-table)", key));
    }
  if (!flow) {
    if (sub) {
      FluidRegion unused = r;
      read_flow_numerics(*sub, unused, domain_max);
    }
    return;
  }
  if (r.collective)
    f.fail("collective", "the bearing-capacity rule is for dynamics = \"at_rest\" only: with \"flow\" the paste's "
                         "own stress carries a pile (set collective = \"none\")");
  read_flow_numerics(sub ? *sub : f, r, domain_max);
}

// The flow numerics of read_dynamics, from the table that holds them.
void read_flow_numerics(const Params& f, FluidRegion& r, const Vec3& domain_max) {
  if (f.has("cell") == f.has("cells"))
    f.fail(f.has("cell") ? "cells" : "dynamics",
           "dynamics = \"flow\" needs the flow grid, one of: cell = SIZE (m, cubic cells that tile the region) or "
           "cells = [nx, ny, nz] (the cells along x, y, z; nearly cubic)");
  const double top = f.number_or("top", domain_max.z, Range::any);
  if (top > domain_max.z)
    f.fail("top", fmt::format("top = {:g} m is above the [domain] box (z up to {:g} m): the flow box would reach "
                              "outside the domain",
                              top, domain_max.z));
  if (!(top > r.z_surface0))
    f.fail("top", fmt::format("top = {:g} m must lie above the surface ({:g} m): the flow box holds the air above "
                              "the paste",
                              top, r.z_surface0));
  const std::array<double, 3> extent{r.x_max - r.x_min, r.y_max - r.y_min, top - r.z_bottom};
  if (f.has("cell")) {
    const double cell = f.number("cell", Range::positive);
    // The grid must tile the region: a box that is not a whole number of cells would move its walls.
    const char* what[3] = {"x extent", "y extent", "height from bottom to top"};
    for (int d = 0; d < 3; ++d) {
      const double n = extent[d] / cell;
      if (std::abs(n - std::round(n)) > 1e-9 * n || std::round(n) < 1.0)
        f.fail(d == 2 && f.has("top") ? "top" : "cell",
               fmt::format("the region's {} ({:g} m) is not a whole number of {:g} m cells ({:.6g}); cells = [nx, "
                           "ny, nz] sets the cells per axis instead",
                           what[d], extent[d], cell, n));
      r.flow_cells[d] = static_cast<int>(std::lround(n));
    }
    r.flow_cell = cell;
  } else {
    const std::vector<double> n = f.numbers("cells", 3);
    std::array<double, 3> h{};
    for (int d = 0; d < 3; ++d) {
      if (!(n[d] >= 1.0) || n[d] != std::floor(n[d]) || n[d] > 1e5)
        f.fail("cells", fmt::format("cells = [nx, ny, nz] must be whole numbers >= 1 (axis {}: {:g})", d, n[d]));
      r.flow_cells[d] = static_cast<int>(n[d]);
      h[d] = extent[d] / n[d];
    }
    // Nearly cubic: the disturbance correction of the drag (model/coupling/drag.h) is tabulated for cubic cells
    // and takes their geometric mean size; 20 % apart at most (e.g. 1 cm x 1.03 cm for a 16.5 cm side).
    const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
    if (*hi > kMaxCellAspect * *lo)
      f.fail("cells", fmt::format("cells = [{}, {}, {}] gives cells of {:.4g} x {:.4g} x {:.4g} m: more than {:g} "
                                  "apart (the drag's disturbance correction assumes nearly cubic cells)",
                                  r.flow_cells[0], r.flow_cells[1], r.flow_cells[2], h[0], h[1], h[2], kMaxCellAspect));
    r.flow_cell = std::cbrt(h[0] * h[1] * h[2]);
  }
  const double c = f.number_or("kernel_width", coupling::kDefaultWidthFactor, Range::positive);
  if (c < coupling::kMinWidthFactor)
    f.fail("kernel_width", fmt::format("kernel_width = {:g} is below its minimum {} (model/coupling/kernel.h: a "
                                       "narrower kernel puts a single sphere's solid fraction above 1)",
                                       c, coupling::kMinWidthFactor));
  const long interval = f.integer_or("coupling_interval", 1);
  if (interval < 1) f.fail("coupling_interval", fmt::format("coupling_interval = {} must be >= 1 (DEM steps per flow interval)", interval));
  // A yield-stress paste in the flow solver is regularised (model/flow/bingham.h); m is part of every result,
  // so it is never defaulted.
  if (r.yield_stress() > 0.0) {
    if (!f.has("regularisation"))
      f.fail("dynamics", "a yield-stress paste with dynamics = \"flow\" needs regularisation = m (s, Papanastasiou's "
                         "parameter, model/flow/bingham.h)");
    r.regularisation = f.number("regularisation", Range::positive);
  } else if (f.has("regularisation")) {
    f.fail("regularisation", "regularisation is for a paste with a yield stress (this one has none)");
  }
  // The flow's sub-step inside a cycle: the time-step convergence of the lagged viscosity (model/flow/bingham.h)
  // is then separable from the coupling interval's.
  if (f.has("flow_time_step")) r.flow_time_step = f.number("flow_time_step", Range::positive);
  r.implicit_stick = f.boolean_or("implicit_stick", false);
  r.flow = true, r.flow_top = top, r.kernel_width = c, r.coupling_interval = interval;
}

}  // namespace

drag::DragCurve read_chosen_curve(const std::string& parameters_toml, const std::string& wanted) {
  const Params root = Params::parse_file(parameters_toml);
  const Params dc = root.table("drag_curve");
  const Params chosen = dc.table("chosen");
  const std::string name = wanted.empty() ? chosen.string("text") : wanted;
  drag::DragCurve c;
  c.id = curve_by_name(chosen, "text", name);
  const auto& info = c.info();
  if (info.n_coefficients > 0) {
    const Params t = dc.table(name);
    for (int i = 0; i < info.n_coefficients; ++i)
      c.coefficients.push_back(t.table(info.coefficient_names[static_cast<std::size_t>(i)]).number("value"));
    const auto why = drag::check_coefficients(c.id, c.coefficients);
    if (!why.empty()) t.fail(info.coefficient_names[0], std::string(why));
  }
  // Not finish()ed: the file holds every lab parameter; only the curve is read here.
  return c;
}

LabPaste read_lab_paste(const std::string& parameters_toml, const std::string& curve_name) {
  const Params root = Params::parse_file(parameters_toml);
  auto value = [&](const char* group, const char* key) -> std::optional<double> {
    const auto g = root.optional_table(group);
    if (!g) return std::nullopt;
    const auto t = g->optional_table(key);
    if (!t) return std::nullopt;
    return t->number("value", Range::positive);
  };
  auto required = [&](const char* group, const char* key) {
    const auto v = value(group, key);
    if (!v)
      throw InputError(parameters_toml, 0, fmt::format("{}.{}", group, key),
                       "missing (run `pastemix lab reduce DATASET --out DIR` to produce it, or pass the value)");
    return *v;
  };
  LabPaste p;
  p.tau_y = required("paste", "yield_stress");
  p.density = required("paste", "density");
  p.eta_B = value("paste", "plastic_viscosity");
  p.ball_restitution = value("steel_ball", "restitution");
  p.ball_friction = value("steel_ball", "static_friction");
  p.ball_density = value("steel_ball", "density");
  p.curve = read_chosen_curve(parameters_toml, curve_name);
  return p;
}

std::vector<FluidRegion> read_fluid_regions(const Params& root, const std::string& scene_path, const Vec3& domain_min,
                                            const Vec3& domain_max) {
  std::vector<FluidRegion> out;
  for (const Params& f : root.tables("fluid")) {
    FluidRegion r;
    r.name = f.string_or("name", fmt::format("fluid{}", out.size()));
    const auto x = f.numbers("x", 2), y = f.numbers("y", 2);
    if (!(x[1] > x[0])) f.fail("x", "x = [min, max] needs max > min");
    if (!(y[1] > y[0])) f.fail("y", "y = [min, max] needs max > min");
    r.x_min = x[0], r.x_max = x[1], r.y_min = y[0], r.y_max = y[1];
    r.z_bottom = f.number("bottom");
    r.z_surface0 = f.number("surface");
    if (!(r.z_surface0 > r.z_bottom)) f.fail("surface", "the free surface must lie above the bottom");
    // The region must lie in the domain: fluid where no sphere can be is a mistake of the scene (a unit, a
    // sign), and the surface rise would divide the displaced volume by the wrong area.
    auto within = [&](const char* key, double lo, double hi, double dlo, double dhi, const char* axis) {
      if (lo < dlo || hi > dhi)
        f.fail(key, fmt::format("{} = [{:g}, {:g}] m reaches outside the [domain] box ({} from {:g} to {:g} m)", key,
                                lo, hi, axis, dlo, dhi));
    };
    within("x", r.x_min, r.x_max, domain_min.x, domain_max.x, "x");
    within("y", r.y_min, r.y_max, domain_min.y, domain_max.y, "y");
    if (r.z_bottom < domain_min.z)
      f.fail("bottom", fmt::format("bottom = {:g} m is below the [domain] box (z from {:g} to {:g} m)", r.z_bottom,
                                   domain_min.z, domain_max.z));
    if (r.z_surface0 > domain_max.z)
      f.fail("surface", fmt::format("surface = {:g} m is above the [domain] box (z from {:g} to {:g} m)", r.z_surface0,
                                    domain_min.z, domain_max.z));
    read_drag_law(f, scene_path, r);
    if (!f.has("rheology_from")) r.solids_fraction = f.number_or("solids_fraction", 0.0, Range::fraction);
    r.buoyancy = f.boolean_or("buoyancy", true);
    r.yield_term = f.boolean_or("yield_term", true);
    r.partial_submergence = f.boolean_or("partial_submergence", true);
    r.surface_rise = f.boolean_or("surface_rise", true);
    r.collective = f.choice_or("collective", {"none", "bearing_capacity"}, "none") == "bearing_capacity";
    r.collective_interval = f.number_or("collective_interval", r.collective_interval, Range::positive);
    if (r.collective && r.yield_stress() <= 0.0)
      f.fail("collective", "the bearing-capacity rule needs a yield stress (a drag law with yield_stress > 0)");
    read_dynamics(f, r, domain_max);
    // One flow region and no other: the engine's flow pass owns the kick of every particle in its box, and
    // a second region (at rest or flowing) would claim the same particles.
    const bool any_flow = std::any_of(out.begin(), out.end(), [](const FluidRegion& q) { return q.flow; });
    if (!out.empty() && (r.flow || any_flow))
      f.fail("dynamics", "a scene with a dynamics = \"flow\" region has that one [[fluid]] region only");
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace pastemix::model::fluid
