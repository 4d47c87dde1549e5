// SPDX-License-Identifier: MIT
#include "model/flow/validations_bingham.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "base/units.h"
#include "model/flow/bingham.h"
#include "model/flow/validation_run.h"

namespace pastemix::flow {

namespace {

constexpr double kG = 9.81;  // m/s2
constexpr double kPi = units::pi;

// A 1-D column of cells along z, periodic along x and y (one cell each, width `width` so that the CFL bound
// along the flow never binds), walls at both z ends.
Grid column(int nz, double hz, double width) {
  Grid g;
  g.n = {1, 1, nz};
  g.h = {width, width, hz};
  for (int d = 0; d < 2; ++d) g.bc[2 * d].type = g.bc[2 * d + 1].type = BoundaryType::periodic;
  return g;
}

// u along x at the centre of each cell of the column.
std::vector<double> column_u(const FlowSolver& s) {
  std::vector<double> u(s.grid().n[2]);
  for (int k = 0; k < s.grid().n[2]; ++k) u[k] = s.velocity()[0][s.grid().face(0, {0, 0, k})];
  return u;
}

double poiseuille_exact(double z, double H, double G, const BinghamPaste& p) {
  const double zeta = std::abs(z - 0.5 * H), y0 = p.tau_y / G, half = 0.5 * H;
  if (zeta < y0) return G / (2 * p.eta_B) * (half - y0) * (half - y0);
  return G / (2 * p.eta_B) * (half * half - zeta * zeta) - p.tau_y / p.eta_B * (half - zeta);
}

// Where the apparent stress eta(gd) gd of the edge strain rates crosses tau_y, from the wall inwards (m).
double yield_surface(const std::vector<double>& u, double h, const Bingham& law, bool from_top) {
  const int n = static_cast<int>(u.size());
  auto stress = [&](int e) {  // edge e between cells e-1 and e; e = 0 and n are the walls (u = 0)
    const double ua = e == 0 ? 0.0 : u[e - 1], ub = e == n ? 0.0 : u[e];
    const double dz = (e == 0 || e == n) ? 0.5 * h : h;
    const double gd = std::abs(ub - ua) / dz;
    return law.viscosity(gd) * gd;
  };
  auto z_of = [&](int e) { return e * h; };
  for (int step = 1; step <= n; ++step) {
    const int e = from_top ? n - step : step, prev = from_top ? e + 1 : e - 1;
    const double s1 = stress(e), s0 = stress(prev);
    if (s1 < law.yield_stress()) {
      const double t = (s0 - law.yield_stress()) / (s0 - s1);
      return z_of(prev) + t * (z_of(e) - z_of(prev));
    }
  }
  return 0.5 * n * h;
}

}  // namespace

PoiseuilleResult bingham_poiseuille(int cells, double m, const BinghamPaste& p) {
  PoiseuilleResult r;
  r.cells = cells;
  r.m = m;
  r.H = 0.02;  // m
  const double G = p.tau_y / (0.25 * r.H);  // Pa/m: plug half-width H/4
  const double h = r.H / cells;
  Grid g = column(cells, h, 10.0);  // 10 m wide: the CFL bound along the flow never binds
  Phases ph;
  ph.rho_paste = ph.rho_air = p.rho;
  auto law = std::make_shared<Bingham>(p.tau_y, p.eta_B, m);
  ph.paste = law;
  ph.eta_air = p.eta_B;
  FlowSettings fs;
  fs.gravity = {G / p.rho, 0.0, 0.0};
  FlowSolver s(g, ph, fs);
  s.add_paste_box({0, 0, 0}, {10.0, 10.0, r.H});
  const double v0 = s.paste_volume();
  r.plug_speed_exact = poiseuille_exact(0.5 * r.H, r.H, G, p);
  // Backward Euler to the steady state: steps of a tenth of the viscous time rho H^2 / eta_B (0.105 s);
  // the lagged viscosity makes this a damped Picard iteration on the steady problem.
  const double dt = 0.1 * p.rho * r.H * r.H / p.eta_B;
  std::vector<double> prev = column_u(s);
  r.last_change = 1.0;
  for (int it = 0; it < 4000 && r.last_change > 1e-9; ++it) {  // 1e-9: ten times the solves' tolerance
    s.step(dt);
    r.max_divergence = std::max(r.max_divergence, relative_divergence(s.last()));
    const std::vector<double> u = column_u(s);
    r.last_change = 0.0;
    for (int k = 0; k < cells; ++k) r.last_change = std::max(r.last_change, std::abs(u[k] - prev[k]) / r.plug_speed_exact);
    prev = u;
  }
  r.u = prev;
  double num = 0.0, den = 0.0;
  for (int k = 0; k < cells; ++k) {
    const double z = (k + 0.5) * h, ue = poiseuille_exact(z, r.H, G, p);
    r.z.push_back(z);
    r.u_exact.push_back(ue);
    num += (r.u[k] - ue) * (r.u[k] - ue);
    den += ue * ue;
    r.max_error = std::max(r.max_error, std::abs(r.u[k] - ue) / r.plug_speed_exact);
  }
  r.l2_error = std::sqrt(num / den);
  r.plug_width_exact = 2.0 * p.tau_y / G;
  r.plug_width = yield_surface(r.u, h, *law, true) - yield_surface(r.u, h, *law, false);
  r.plug_speed = *std::max_element(r.u.begin(), r.u.end());
  return finished(r, s, v0);
}

InclineResult bingham_incline(double depth_over_hc, int cells, double m, double theta_deg, const BinghamPaste& p) {
  InclineResult r;
  r.depth_over_hc = depth_over_hc;
  r.cells = cells;
  r.m = m;
  r.theta_deg = theta_deg;
  const double th = theta_deg * kPi / 180.0, gs = kG * std::sin(th);
  r.h_c = p.tau_y / (p.rho * gs);
  r.h = depth_over_hc * r.h_c;
  const double hz = r.h / cells;
  const int air = std::max(4, cells / 3);  // cells of air under the lid
  Grid g = column(cells + air, hz, r.h);
  g.bc[5].type = BoundaryType::no_slip;  // the lid: keeps the air, driven by its own weight along x, slow
  Phases ph;
  ph.rho_paste = p.rho;
  ph.paste = std::make_shared<Bingham>(p.tau_y, p.eta_B, m);
  FlowSettings fs;
  fs.gravity = {gs, 0.0, -kG * std::cos(th)};
  FlowSolver s(g, ph, fs);
  s.add_paste_box({0, 0, 0}, {r.h, r.h, r.h});
  const double v0 = s.paste_volume();
  r.surface_speed_exact = depth_over_hc > 1 ? p.rho * gs * (r.h - r.h_c) * (r.h - r.h_c) / (2 * p.eta_B) : 0.0;
  // To steady: chunks of 0.25 s until the surface speed changes by < 1e-5 relative over one (at most 20 s).
  // The slowest time of the film is its viscous time rho h^2 / eta_B (~1.4 s at 1.5 h_c).
  auto surface = [&] { return s.velocity()[0][g.face(0, {0, 0, cells - 1})]; };
  double prev = 0.0;
  r.last_change = 1.0;
  while (s.time() < 20.0 - 1e-9 && !(s.time() >= 2.0 && r.last_change < 1e-5)) {
    const double t_end = s.time() + 0.25;
    while (s.time() < t_end * (1 - 1e-14)) {
      s.step(std::min(s.next_time_step(), t_end - s.time()));
      r.max_divergence = std::max(r.max_divergence, relative_divergence(s.last()));
    }
    const double now = surface();
    r.last_change = std::abs(now - prev) / std::max(std::abs(now), 1e-30);
    prev = now;
  }
  r.time = s.time();
  r.surface_speed = surface();
  return finished(r, s, v0);
}

namespace {

// Where the floor row crosses alpha = 1/2, from x = 0 outwards (m).
double floor_front(const FlowSolver& s) {
  const Grid& g = s.grid();
  for (int i = 1; i < g.n[0]; ++i) {
    const double a = s.alpha()[g.cell(i, 0, 0)];
    if (a < 0.5) {
      const double b = s.alpha()[g.cell(i - 1, 0, 0)];
      return (i - 0.5 + (b - 0.5) / (b - a)) * g.h[0];
    }
  }
  return g.n[0] * g.h[0];
}

// The paste's height in the column at x = 0: the sum of alpha h (m).
double top_height(const FlowSolver& s) {
  const Grid& g = s.grid();
  double z = 0.0;
  for (int k = 0; k < g.n[2]; ++k) z += s.alpha()[g.cell(0, 0, k)] * g.h[2];
  return z;
}

}  // namespace

CliffResult bingham_cliff(double height_over_scale, int cells, double m, double time, const BinghamPaste& p) {
  CliffResult r;
  r.height_over_scale = height_over_scale;
  r.cells = cells;
  r.m = m;
  r.H = height_over_scale * p.tau_y / (p.rho * kG);
  r.h = r.H / cells;
  Grid g;
  g.n = {5 * cells, 1, (3 * cells) / 2};  // 2 H of paste behind the face, 3 H in front; 1.5 H high
  g.h = {r.h, r.h, r.h};
  g.bc[0].type = g.bc[1].type = BoundaryType::free_slip;  // x = 0: the symmetry plane
  g.bc[2].type = g.bc[3].type = BoundaryType::periodic;
  g.bc[5].type = BoundaryType::open;
  Phases ph;
  ph.rho_paste = p.rho;
  ph.paste = std::make_shared<Bingham>(p.tau_y, p.eta_B, m);
  FlowSettings fs;
  FlowSolver s(g, ph, fs);
  s.add_paste_box({0, 0, 0}, {2 * r.H, r.h, r.H});
  const double v0 = s.paste_volume(), front0 = floor_front(s), top0 = top_height(s);
  while (s.time() < time * (1 - 1e-14)) {
    const double dt = std::min(s.next_time_step(), time - s.time());
    s.step(dt);
    r.displacement += paste_speed(s) * dt;
    r.max_divergence = std::max(r.max_divergence, relative_divergence(s.last()));
  }
  r.time = s.time();
  r.front_advance = floor_front(s) - front0;
  r.top_drop = top0 - top_height(s);
  return finished(r, s, v0);
}

}  // namespace pastemix::flow

namespace pastemix::flow {

double pashias_boger_slump(double tau_y, double rho, double H) {
  const double t = tau_y / (rho * kG * H);  // tau'
  return H * (1.0 - 2.0 * t * (1.0 - std::log(2.0 * t)));
}

double roussel_coussot_radius(double tau_y, double rho, double volume) {
  return std::pow(225.0 * rho * kG * volume * volume / (128.0 * kPi * kPi * tau_y), 0.2);
}

namespace {

constexpr double kMouldH = 0.152, kMouldR = 0.076;  // m: the lab's mould (H = D = 152 mm)

// The quarter cylinder's share of each cell: 16 x 16 points across x-y, the z overlap exact.
std::vector<double> quarter_cylinder(const Grid& g) {
  std::vector<double> a(g.cell_count(), 0.0);
  const int sub = 16;
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i) {
      int inside = 0;
      for (int sj = 0; sj < sub; ++sj)
        for (int si = 0; si < sub; ++si) {
          const double x = (i + (si + 0.5) / sub) * g.h[0], y = (j + (sj + 0.5) / sub) * g.h[1];
          inside += x * x + y * y <= kMouldR * kMouldR;
        }
      const double share = static_cast<double>(inside) / (sub * sub);
      for (int k = 0; k < g.n[2]; ++k) {
        const double zf = std::clamp((kMouldH - k * g.h[2]) / g.h[2], 0.0, 1.0);
        a[g.cell(i, j, k)] = share * zf;
      }
    }
  return a;
}

// The paste inside the mould's staircase (LiftedMould::inside) up to the mould's height, the z overlap exact.
std::vector<double> quarter_staircase(const Grid& g, const LiftedMould& mould) {
  std::vector<double> a(g.cell_count(), 0.0);
  for (int k = 0; k < g.n[2]; ++k) {
    const double zf = std::clamp((mould.height - k * g.h[2]) / g.h[2], 0.0, 1.0);
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        if (mould.inside(g, i, j)) a[g.cell(i, j, k)] = zf;
  }
  return a;
}

// The highest paste column, m: the paste height sum alpha h_z of the tallest column.
double highest_column(const FlowSolver& s) {
  const Grid& g = s.grid();
  double top = 0.0;
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i) {
      double h = 0.0;
      for (int k = 0; k < g.n[2]; ++k) h += s.alpha()[g.cell(i, j, k)] * g.h[2];
      top = std::max(top, h);
    }
  return top;
}

// Lifts the mould: sets the solver's blocked faces whenever a layer of them opens (or the mould leaves the box).
class MouldLift {
 public:
  MouldLift(const LiftedMould& mould, const Grid& g) : mould_(mould), g_(g) {}
  void update(FlowSolver& s) {
    if (mould_.instant()) return;
    const int open = mould_.open_layers(g_, s.time());  // layers the lower edge has passed
    if (open == open_) return;
    open_ = open;
    s.set_blocked_faces(mould_.faces(g_, s.time()));
  }
  // The step dt from time t shortened to land on the next opening time (no sliver left before it), so the lift
  // keeps its schedule; unchanged when no layer is left to open (and for the instantaneous release).
  double landed(double t, double dt) const {
    if (mould_.instant() || open_ >= g_.n[2]) return dt;
    const double t_open = mould_.opening_time(g_, open_), left = t_open - t;
    if (t + dt >= t_open) return left;
    return t + 1.5 * dt > t_open ? 0.5 * left : dt;
  }

 private:
  LiftedMould mould_;
  Grid g_;
  int open_ = -1;
};

}  // namespace

LiftedMould slump_mould(double speed) {
  LiftedMould m;
  m.radius = kMouldR;
  m.height = kMouldH;
  m.speed = speed;
  return m;
}

SlumpShape slump_shape(const FlowSolver& s) {
  const Grid& g = s.grid();
  double column = 0.0, floor = 0.0;
  for (int k = 0; k < g.n[2]; ++k) column += s.alpha()[g.cell(0, 0, k)] * g.h[2];
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i) floor += s.alpha()[g.cell(i, j, 0)] * g.h[0] * g.h[1];
  return {kMouldH - column, 2.0 * std::sqrt(4.0 * floor / kPi)};
}

SlumpResult bingham_slump(double cell, double m, double tau_y, double rho, double eta_B, double max_time,
                          const FlowProgress& progress, double lift_speed) {
  if (!(lift_speed > 0.0)) throw std::invalid_argument("slump: the lift speed must be positive (infinity: at once)");
  SlumpResult r;
  r.cell = cell;
  r.m = m;
  r.lift_speed = lift_speed;
  r.tau_y = tau_y;
  r.rho = rho;
  Grid g;
  const int nxy = static_cast<int>(std::ceil(0.26 / cell)), nz = static_cast<int>(std::ceil(0.16 / cell));
  g.n = {nxy, nxy, nz};
  g.h = {cell, cell, cell};
  for (int s = 0; s < 4; ++s) g.bc[s].type = BoundaryType::free_slip;  // x = 0, y = 0: symmetry; far sides
  g.bc[5].type = BoundaryType::open;
  Phases ph;
  ph.rho_paste = rho;
  ph.paste = std::make_shared<Bingham>(tau_y, eta_B, m);
  FlowSolver s(g, ph, FlowSettings{});
  const LiftedMould mould = slump_mould(lift_speed);
  s.set_alpha(mould.instant() ? quarter_cylinder(g) : quarter_staircase(g, mould));
  MouldLift lift(mould, g);
  lift.update(s);
  const double v0 = s.paste_volume();
  r.slump_pashias = pashias_boger_slump(tau_y, rho, kMouldH);
  r.spread_roussel = 2.0 * roussel_coussot_radius(tau_y, rho, 4.0 * v0);  // the whole sample's volume
  // At rest once the paste's RMS speed is below kRestSpeed (bingham.h) and stays so for kSlumpRestHold, after
  // the first 0.1 s (it starts at rest) and once the mould has let go of it.
  double rest_since = -1.0;  // s, the start of the current spell at rest
  bool released = mould.instant();
  while (s.time() < max_time) {
    s.step(lift.landed(s.time(), s.next_time_step()));
    lift.update(s);  // the mask for the next step, from its start time
    r.max_divergence = std::max(r.max_divergence, relative_divergence(s.last()));
    if (progress) progress(s);
    if (!released && mould.lower_edge(s.time()) > highest_column(s)) {
      released = true;
      r.released = s.time();
    }
    if (s.time() <= 0.1 || !released || !at_rest(s)) {
      rest_since = -1.0;
      continue;
    }
    if (rest_since < 0.0) rest_since = s.time();
    if (s.time() - rest_since >= kSlumpRestHold) {
      r.at_rest = true;
      break;
    }
  }
  r.time = r.at_rest ? rest_since : s.time();
  r.end_time = s.time();
  r.final_speed = paste_rms_speed(s);
  r.final_max_speed = paste_speed(s);
  r.final_air_speed = s.max_speed();
  const SlumpShape shape = slump_shape(s);
  r.slump = shape.slump;
  r.spread = shape.spread;
  return finished(r, s, v0);
}

}  // namespace pastemix::flow
