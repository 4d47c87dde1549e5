// SPDX-License-Identifier: MIT
#include "model/flow/flow_config.h"

#include <cmath>

#include <fmt/format.h>

#include "base/error.h"
#include "model/flow/bingham.h"

namespace pastemix::flow {

namespace {

constexpr const char* kAxis[3] = {"x", "y", "z"};

BoundaryType boundary_type(const std::string& s) {
  if (s == "no_slip") return BoundaryType::no_slip;
  if (s == "free_slip") return BoundaryType::free_slip;
  if (s == "open") return BoundaryType::open;
  return BoundaryType::periodic;
}

void read_boundaries(const Params& flow, Grid& g) {
  const std::optional<Params> b = flow.optional_table("boundary");
  if (!b) return;
  const std::vector<std::string> kinds{"no_slip", "free_slip", "open", "periodic"};
  for (int d = 0; d < 3; ++d) {
    const std::string axis = kAxis[d];
    if (b->has(axis)) {
      const BoundaryType t = boundary_type(b->choice(axis, kinds));
      g.bc[2 * d].type = g.bc[2 * d + 1].type = t;
    }
    for (int hi = 0; hi < 2; ++hi) {
      const std::string key = axis + (hi ? "_hi" : "_lo");
      if (b->has(key)) {
        if (b->has(axis)) b->fail(key, fmt::format("given together with '{}' (one or the other)", axis));
        g.bc[2 * d + hi].type = boundary_type(b->choice(key, kinds));
      }
      if (const auto v = b->optional_numbers(key + "_velocity", 3)) {
        if (g.bc[2 * d + hi].type != BoundaryType::no_slip)
          b->fail(key + "_velocity", "a wall velocity needs a no_slip side");
        for (int c = 0; c < 3; ++c) g.bc[2 * d + hi].wall_velocity[c] = (*v)[c];
      }
    }
    if ((g.bc[2 * d].type == BoundaryType::periodic) != (g.bc[2 * d + 1].type == BoundaryType::periodic))
      b->fail(axis + "_lo", fmt::format("periodic on one {} side only: set both (or '{} = \"periodic\"')", axis, axis));
  }
}

void read_grid(const Params& flow, Grid& g) {
  const std::vector<double> box = flow.numbers("box", 3);
  if (const auto o = flow.optional_numbers("origin", 3))
    for (int d = 0; d < 3; ++d) g.origin[d] = (*o)[d];
  std::array<double, 3> cell{};
  if (flow.has("cells")) {
    if (flow.has("cell")) flow.fail("cells", "given together with 'cell' (one or the other)");
    const std::vector<double> n = flow.numbers("cells", 3);
    for (int d = 0; d < 3; ++d) {
      if (!(n[d] >= 1.0) || n[d] != std::floor(n[d]))
        flow.fail("cells", fmt::format("expected a whole number of cells >= 1 along {}, got {}", kAxis[d], n[d]));
      cell[d] = box[d] / n[d];
    }
  } else {
    cell.fill(flow.number("cell", Range::positive));
  }
  for (int d = 0; d < 3; ++d) {
    if (!(box[d] > 0.0)) flow.fail("box", fmt::format("the box's {} extent must be positive, got {}", kAxis[d], box[d]));
    const double cells = box[d] / cell[d];
    const double whole = std::round(cells);
    if (whole < 1.0 || std::abs(cells - whole) > 1e-9 * std::max(1.0, cells))
      flow.fail("cell", fmt::format("the grid does not fit the box: {} m along {} is {:.6g} cells of {} m, not a whole "
                                    "number (change the cell, or give cells = [nx, ny, nz])",
                                    box[d], kAxis[d], cells, cell[d]));
    g.n[d] = static_cast<int>(whole);
    g.h[d] = box[d] / whole;
  }
}

void read_phases(const Params& flow, Phases& ph) {
  const Params paste = flow.table("paste");
  ph.paste = read_paste_law(paste, ph.rho_paste);  // model/flow/bingham.h: newtonian, bingham, herschel_bulkley
  if (const auto air = flow.optional_table("air")) {
    ph.rho_air = air->number_or("density", ph.rho_air, Range::positive);
    ph.eta_air = air->number_or("viscosity", ph.eta_air, Range::positive);
  }
  if (!(ph.rho_paste > ph.rho_air)) paste.fail("density", "the paste must be denser than the air");
}

void read_settings(const Params& flow, FlowSettings& s) {
  s.cfl = flow.number_or("cfl", s.cfl, Range::positive);
  if (s.cfl > 0.5)
    flow.fail("cfl", fmt::format("CFL {} is above its bound 0.5 (the split VOF sweeps stay bounded only up to 1/2)", s.cfl));
  s.max_time_step = flow.number_or("max_time_step", s.max_time_step, Range::positive);
  if (const auto gv = flow.optional_numbers("gravity", 3))
    for (int d = 0; d < 3; ++d) s.gravity[d] = (*gv)[d];
  s.pressure_tolerance = flow.number_or("pressure_tolerance", s.pressure_tolerance, Range::positive);
  if (s.pressure_tolerance > 1e-10)
    flow.fail("pressure_tolerance", fmt::format("{} is above 1e-10: leftover divergence is lost paste", s.pressure_tolerance));
  s.viscous_tolerance = flow.number_or("viscous_tolerance", s.viscous_tolerance, Range::positive);
}

void read_initial(const Params& flow, const Grid& g, std::vector<PasteBox>& paste) {
  const std::optional<Params> init = flow.optional_table("initial");
  if (!init) return;
  std::array<double, 3> top{};
  for (int d = 0; d < 3; ++d) top[d] = g.origin[d] + g.n[d] * g.h[d];
  if (const auto z = init->optional_number("paste_below")) paste.push_back({g.origin, {top[0], top[1], *z}});
  for (const Params& b : init->tables("paste_box")) {
    const std::vector<double> lo = b.numbers("lo", 3), hi = b.numbers("hi", 3);
    PasteBox p;
    for (int d = 0; d < 3; ++d) {
      if (!(hi[d] > lo[d])) b.fail("hi", fmt::format("hi must exceed lo along {}", kAxis[d]));
      p.lo[d] = lo[d];
      p.hi[d] = hi[d];
    }
    paste.push_back(p);
  }
}

}  // namespace

FlowCase read_flow_case(const Params& flow) {
  FlowCase c;
  c.source = flow.path();
  c.name = flow.string_or("name", c.name);
  read_grid(flow, c.grid);
  read_boundaries(flow, c.grid);
  read_phases(flow, c.phases);
  read_settings(flow, c.settings);
  c.end_time = flow.number("end_time", Range::positive);
  c.output_interval = flow.number_or("output_interval", 0.0, Range::non_negative);
  read_initial(flow, c.grid, c.paste);
  return c;
}

FlowCase load_flow_case(const std::filesystem::path& path) {
  const Params file = Params::parse_file(path);
  const Params flow = file.table("flow");
  FlowCase c = read_flow_case(flow);
  file.finish();
  return c;
}

FlowSolver make_solver(const FlowCase& c) {
  FlowSolver s(c.grid, c.phases, c.settings);
  for (const PasteBox& b : c.paste) s.add_paste_box(b.lo, b.hi);
  return s;
}

}  // namespace pastemix::flow
