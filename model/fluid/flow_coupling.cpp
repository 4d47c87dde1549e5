// SPDX-License-Identifier: MIT
#include "model/fluid/flow_coupling.h"

#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "base/error.h"
#include "base/units.h"
#include "model/coupling/coupled_flow.h"
#include "model/flow/bingham.h"
#include "model/flow/solver.h"
#include "model/state_bytes.h"

namespace pastemix::model::fluid {

namespace {

using Vec = std::array<double, 3>;

// The region's box as the flow's grid: its cells (fluid_scene.h: cubic, or nearly), no-slip walls on five sides, the top open (p = 0: the air
// above the paste may leave and enter).
flow::Grid region_grid(const FluidRegion& r) {
  flow::Grid g;
  g.n = r.flow_cells;
  g.h = {(r.x_max - r.x_min) / g.n[0], (r.y_max - r.y_min) / g.n[1], (r.flow_top - r.z_bottom) / g.n[2]};
  g.origin = {r.x_min, r.y_min, r.z_bottom};
  g.bc[5].type = flow::BoundaryType::open;
  return g;
}

// The paste's law in the flow solver, from the region's drag law values (the same fluid both ways).
flow::Phases region_phases(const FluidRegion& r) {
  flow::Phases ph;
  ph.rho_paste = r.density();
  std::visit(
      [&](const auto& prm) {
        using P = std::decay_t<decltype(prm)>;
        if constexpr (requires { prm.plastic_viscosity; })
          ph.paste = std::make_shared<flow::Bingham>(prm.yield_stress, prm.plastic_viscosity, r.regularisation);
        else if constexpr (requires { prm.consistency; })
          ph.paste = std::make_shared<flow::HerschelBulkley>(prm.yield_stress, prm.consistency, prm.flow_index,
                                                              r.regularisation);
        else
          ph.paste = std::make_shared<flow::Newtonian>(prm.viscosity);
        static_assert(std::is_same_v<typename P::Law::Params, P>);
      },
      r.law);
  return ph;
}

// Particle a's drag law in the region's paste, split as the exchange wants it (coupling/drag.h): D(s) of the
// registry law with the region's curve and the particle's yield number, its Reynolds number, D(0+).
coupling::SphereDrag sphere_drag(const FluidRegion& r, double mass, double radius, const Vec3& g) {
  const double d = 2.0 * radius;
  const double rho_p = mass / (4.0 / 3.0 * units::pi * radius * radius * radius), gmag = norm(g);
  const double y = r.yield_stress() <= 0.0 ? 0.0
                   : (rho_p > r.density() && gmag > 0.0) ? r.yield_stress() / (gmag * d * (rho_p - r.density()))
                                                         : std::numeric_limits<double>::infinity();
  return std::visit(
      [&](const auto& prm) {
        using Law = typename std::decay_t<decltype(prm)>::Law;
        const auto sphere = Law::sphere(prm, r.curve, d, y);  // holds &r.curve: r outlives it (State)
        const double off = r.yield_term ? 0.0 : Law::yield_term(sphere);
        coupling::SphereDrag s;
        s.magnitude = [sphere, off](double v) { return Law::magnitude(sphere, v) - off; };
        if constexpr (requires { Law::reynolds(sphere, 1.0); })
          s.reynolds = [sphere](double v) { return Law::reynolds(sphere, v); };
        else if constexpr (requires { prm.plastic_viscosity; })
          s.reynolds = [prm, d](double v) { return drag::bingham_reynolds(prm.density, v, prm.yield_stress, prm.plastic_viscosity, d); };
        else
          s.reynolds = [prm, d](double v) { return drag::bingham_reynolds(prm.density, v, 0.0, prm.viscosity, d); };
        s.rest = s.magnitude(kRestSpeed);
        s.rest_speed = kRestSpeed;
        return s;
      },
      r.law);
}

bool in_box(const FluidRegion& r, const Vec3& x) {
  return x.x >= r.x_min && x.x <= r.x_max && x.y >= r.y_min && x.y <= r.y_max && x.z >= r.z_bottom && x.z <= r.flow_top;
}

template <class T>
void remap(std::vector<T>& v, const std::vector<std::uint32_t>& map, std::size_t count) {
  if (v.empty()) return;
  std::vector<T> out(count);
  for (std::size_t a = 0; a < map.size() && a < v.size(); ++a)
    if (map[a] != Particles::kGone) out[map[a]] = std::move(v[a]);
  v = std::move(out);
}

}  // namespace

struct FlowCoupling::State {
  FluidRegion region;
  double dt = 0.0;  // s, the World's
  Vec3 gravity;
  flow::FlowSolver solver;
  coupling::CoupledFlow coupled;
  coupling::CoupledParticles p;  // every World particle, by dense index
  coupling::CoupledFlow::Start start;
  std::vector<Vec> impulse;  // N s per particle: the cycle's summed drag impulses (J_sub)
  coupling::CycleStats last;
  // Per particle, what its kicks read in this cycle (fixed from the cycle's start to its end): the drag's record
  // and the pending pressure impulse over the interval (N). Rebuilt wherever start, the pending impulses or the
  // numbering change (begin_cycle, renumber, restore); never saved (it follows from what is).
  std::vector<coupling::CoupledFlow::StepRecord> record;
  std::vector<Vec> pressure;
  void gather() {
    const std::size_t n = p.m.size();
    const auto& pending = coupled.pending_impulse();
    const double T = interval();
    record.resize(n), pressure.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      record[i] = coupled.step_record(p, i, start);
      pressure[i] = {pending[i][0] / T, pending[i][1] / T, pending[i][2] / T};
    }
  }

  State(FluidRegion r, double step, const Vec3& g)
      : region(std::move(r)), dt(step), gravity(g),
        solver(region_grid(region), region_phases(region), settings(region, g)),
        coupled(solver, coupling_settings(region, g)) {
    solver.add_paste_box({region.x_min, region.y_min, region.z_bottom}, {region.x_max, region.y_max, region.z_surface0});
  }
  static flow::FlowSettings settings(const FluidRegion& r, const Vec3& g) {
    flow::FlowSettings s;
    s.gravity = {g.x, g.y, g.z};
    if (r.flow_time_step > 0.0) s.max_time_step = r.flow_time_step;
    return s;
  }
  static coupling::CouplingSettings coupling_settings(const FluidRegion& r, const Vec3& g) {
    coupling::CouplingSettings s;
    s.width_factor = r.kernel_width;
    s.implicit_stick = r.implicit_stick;
    s.gravity = {g.x, g.y, g.z};
    return s;
  }
  double interval() const { return static_cast<double>(region.coupling_interval) * dt; }  // s, T
};

FlowCoupling::FlowCoupling(FluidRegion region, double dt, const Vec3& gravity)
    : s_(std::make_unique<State>(std::move(region), dt, gravity)) {}

FlowCoupling::~FlowCoupling() = default;

const FluidRegion& FlowCoupling::region() const { return s_->region; }
const flow::FlowSolver& FlowCoupling::solver() const { return s_->solver; }
double FlowCoupling::paste_volume() const { return s_->solver.paste_volume(); }
long FlowCoupling::flow_steps() const { return s_->solver.totals().steps; }
long FlowCoupling::pressure_iterations() const { return s_->solver.totals().pressure_iterations; }
long FlowCoupling::viscous_iterations() const { return s_->solver.totals().viscous_iterations; }
double FlowCoupling::solver_seconds() const { return s_->solver.totals().seconds; }
double FlowCoupling::solver_time() const { return s_->solver.time(); }

void FlowCoupling::start(const Particles& p) {
  auto& cp = s_->p;
  const std::size_t n = p.size();
  cp.x.resize(n), cp.v.resize(n), cp.d.resize(n), cp.m.resize(n), cp.drag.clear();
  for (std::size_t a = 0; a < n; ++a) {
    cp.x[a] = {p.x[a].x, p.x[a].y, p.x[a].z};
    cp.d[a] = 2.0 * p.radius[a], cp.m[a] = p.mass[a];
    cp.drag.push_back(sphere_drag(s_->region, p.mass[a], p.radius[a], s_->gravity));
  }
  s_->coupled.start(cp);
  started_ = true;
}

void FlowCoupling::begin_cycle(const Particles& p) {
  auto& cp = s_->p;
  const std::size_t n = p.size();
  for (std::size_t a = 0; a < n; ++a) cp.x[a] = {p.x[a].x, p.x[a].y, p.x[a].z}, cp.v[a] = {p.v[a].x, p.v[a].y, p.v[a].z};
  s_->start = s_->coupled.begin(cp);
  s_->impulse.assign(n, Vec{0.0, 0.0, 0.0});
  s_->gather();
  member_.assign(n, 0);
  members_.clear();
  for (std::size_t a = 0; a < n; ++a)
    if (in_box(s_->region, p.x[a])) member_[a] = 1, members_.push_back(static_cast<long>(a));
  ++membership_;
  step_in_cycle_ = 0;
}

const std::vector<long>& FlowCoupling::prepare(Particles& p) {
  changed_.clear();
  if (failure_) return changed_;
  const OneThread one;  // (flow_coupling.h)
  try {
    cycle(p);
  } catch (...) {
    failure_ = std::current_exception();
    changed_.clear();
  }
  return changed_;
}

void FlowCoupling::cycle(Particles& p) {
  if (!started_) {
    start(p);
    begin_cycle(p);
    return;
  }
  if (++step_in_cycle_ < s_->region.coupling_interval) return;
  // The cycle ends: its flow interval with the positions the DEM reached, then the exchange's change of the
  // particles' velocities (the fluid's own change, implicit in both phases) into the World.
  auto& cp = s_->p;
  for (std::size_t a = 0; a < p.size(); ++a) cp.x[a] = {p.x[a].x, p.x[a].y, p.x[a].z}, cp.v[a] = {p.v[a].x, p.v[a].y, p.v[a].z};
  s_->last = coupling::CycleStats{};
  s_->coupled.finish(cp, s_->interval(), s_->start, s_->impulse, s_->last);
  for (std::size_t a = 0; a < p.size(); ++a) {
    const Vec3 v{cp.v[a][0], cp.v[a][1], cp.v[a][2]};
    if (v.x == p.v[a].x && v.y == p.v[a].y && v.z == p.v[a].z) continue;
    p.v[a] = v;
    changed_.push_back(static_cast<long>(a));
  }
  ++cycles_;
  begin_cycle(p);
}

Vec3 FlowCoupling::kick(long a, const Vec3& v, const Vec3& F, double, double h) const {
  const std::size_t i = static_cast<std::size_t>(a);
  const Vec& pressure = s_->pressure[i];  // the pending impulse over the cycle, N
  const Vec force{F.x + pressure[0], F.y + pressure[1], F.z + pressure[2]};
  Vec out{v.x, v.y, v.z};
  const bool stuck = coupling::CoupledFlow::drag_update(s_->record[i], out, force, h, s_->impulse[i]);
  s_->start.stuck[i] = stuck ? 1 : 0;  // its own entry: written by the particle's owner thread only
  return {out[0], out[1], out[2]};
}

Vec3 FlowCoupling::pressure_force(long a) const {
  const std::size_t i = static_cast<std::size_t>(a);
  if (!started_ || i >= member_.size() || !member_[i]) return {0.0, 0.0, 0.0};
  const Vec& f = s_->pressure[i];
  return {f[0], f[1], f[2]};
}

void FlowCoupling::renumber(const std::vector<std::uint32_t>& map, std::size_t count) {
  if (!started_) return;
  auto& cp = s_->p;
  remap(cp.x, map, count), remap(cp.v, map, count), remap(cp.d, map, count), remap(cp.m, map, count);
  remap(cp.drag, map, count);
  auto& st = s_->start;
  remap(st.u, map, count), remap(st.share, map, count), remap(st.beta, map, count), remap(st.shift, map, count);
  remap(st.x, map, count), remap(st.stuck, map, count);
  remap(s_->impulse, map, count), remap(member_, map, count);
  coupling::CoupledFlow::State c = s_->coupled.state();
  remap(c.x_flow, map, count), remap(c.pending, map, count), remap(c.drag, map, count);
  s_->coupled.restore(std::move(c));
  members_.clear();
  for (std::size_t a = 0; a < member_.size(); ++a)
    if (member_[a]) members_.push_back(static_cast<long>(a));
  ++membership_;
  s_->gather();
}

namespace {

// What the state holds besides the members (the drag laws are remade from the particles, not stored).
struct Saved {
  coupling::CoupledParticles p;
  coupling::CoupledFlow::Start start;
  std::vector<Vec> impulse;
  coupling::CycleStats last;
  flow::FlowSolver::State flow;
};

// Both directions in one order: io.put(x) writes or reads x.
template <class IO, class S, class C>
void pack_state(IO& io, S& st, C& coupled, std::vector<char>& member, std::vector<long>& list, long& step, long& cycles) {
  auto faces = [&](auto& f) {
    for (auto& c : f) io(c);
  };
  io(member), io(list), io(step), io(cycles);
  io(st.p.x), io(st.p.v), io(st.start.u), io(st.start.share), io(st.start.beta), io(st.start.shift), io(st.impulse);
  io(st.start.x), faces(st.start.mask), faces(st.start.mass), io(st.start.stuck);
  io(st.last), io(coupled.x_flow), io(coupled.pending), io(coupled.drag), io(coupled.interval);
  auto& f = st.flow;
  faces(f.u), faces(f.continuity_impulse), faces(f.pressure_impulse);
  io(f.p), io(f.alpha), io(f.mu), io(f.eps), io(f.eps_next), io(f.with_rate), io(f.pressure_ready), io(f.t);
  io(f.last), io(f.totals);
}

// The raw-byte structs of the flow state, by size: a checkpoint of another build (a field added to the cycle's
// stats, say) is then named as such instead of reading as damaged bytes.
std::string flow_sizes_tag() {
  // "stuck": the layout with the start's stuck flags (the implicit stick, coupled_flow.h), "mass" with its
  // faces' fluid mass (the reaction's share, exchange.h); a state without them is another version's.
  return fmt::format("flow state: CycleStats {} StepStats {} Totals {} stuck mass", sizeof(coupling::CycleStats),
                     sizeof(flow::FlowSolver::State::last), sizeof(flow::FlowSolver::State::totals));
}

}  // namespace

std::vector<char> FlowCoupling::save() const {
  StateBytes b;
  auto io = [&](auto& v) { b.put(v); };
  const std::string t = flow_sizes_tag();
  std::vector<char> tag(t.begin(), t.end());
  io(tag);
  bool started = started_;
  io(started);
  if (!started_) return b.data();
  Saved st{s_->p, s_->start, s_->impulse, s_->last, s_->solver.state()};
  coupling::CoupledFlow::State c = s_->coupled.state();
  std::vector<char> member = member_;
  std::vector<long> list = members_;
  long step = step_in_cycle_, cycles = cycles_;
  pack_state(io, st, c, member, list, step, cycles);
  return b.data();
}

void FlowCoupling::restore(const std::vector<char>& bytes, const Particles& p) {
  StateReader rd({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, "checkpoint (flow state)");
  auto io = [&](auto& v) { rd.get(v); };
  std::vector<char> tag;
  io(tag);
  if (std::string(tag.begin(), tag.end()) != flow_sizes_tag())
    throw InputError("checkpoint", 0, "/checkpoint/state",
                     fmt::format("flow state written by another version of pastemix ({}; this one: {}): start the run again",
                                 std::string(tag.begin(), tag.end()), flow_sizes_tag()));
  io(started_);
  ++membership_;  // whatever the bytes hold, the members are theirs now
  if (!started_) return;
  start(p);  // the per-particle constants (diameters, masses, drag laws) of the restored particles
  Saved st;
  coupling::CoupledFlow::State c;
  pack_state(io, st, c, member_, members_, step_in_cycle_, cycles_);
  if (!rd.done()) rd.damaged("bytes left over in the flow state");
  s_->p.x = std::move(st.p.x), s_->p.v = std::move(st.p.v);
  s_->start = std::move(st.start), s_->impulse = std::move(st.impulse), s_->last = st.last;
  s_->coupled.restore(std::move(c));
  s_->solver.restore(std::move(st.flow));
  s_->gather();
}

FlowFields FlowCoupling::fields() const {
  const flow::FlowSolver& f = s_->solver;
  const flow::Grid& g = f.grid();
  FlowFields out;
  out.n = g.n, out.h = g.h, out.origin = g.origin;
  out.paste_fraction = f.alpha();
  out.fluid_fraction = f.fluid_fraction().empty() ? std::vector<double>(g.cell_count(), 1.0) : f.fluid_fraction();
  out.pressure = f.pressure();
  out.velocity = f.cell_velocity();
  return out;
}

}  // namespace pastemix::model::fluid
