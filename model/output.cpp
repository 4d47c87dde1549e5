// SPDX-License-Identifier: MIT
#include "model/output.h"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "base/h5.h"
#include "base/hash.h"
#include "model/flow/solver.h"
#include "model/fluid/flow_coupling.h"
#include "model/scene.h"

namespace pastemix::model {

std::string scene_hash(const std::string& text) { return text_hash(text); }

namespace {

std::vector<double> flat(const std::vector<Vec3>& v) {
  std::vector<double> out(3 * v.size());
  for (std::size_t k = 0; k < v.size(); ++k) {
    out[3 * k] = v[k].x;
    out[3 * k + 1] = v[k].y;
    out[3 * k + 2] = v[k].z;
  }
  return out;
}

std::string group(std::size_t k) { return fmt::format("/snapshots/{:06d}", k); }

// One XDMF attribute of 8-byte values read from the HDF5 dataset `where` (FILE:/path).
std::string xdmf_attribute(const char* name, const char* type, const char* center, const std::string& dims,
                           const char* number_type, const std::string& where) {
  return fmt::format("    <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"{}\">\n"
                     "     <DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"8\" Format=\"HDF\">{}</DataItem>\n"
                     "    </Attribute>\n",
                     name, type, center, dims, number_type, where);
}

}  // namespace

RunOutput::RunOutput(const std::filesystem::path& h5_path, std::string h5_final_name, const Scene& scene)
    : h5_(std::make_unique<H5Writer>(h5_path)), h5_name_(std::move(h5_final_name)),
      rotation_(scene.plan.rotation) {
  h5_->attribute("/", "scene_path", scene.path);
  h5_->attribute("/", "scene_text", scene.text);
  h5_->attribute("/", "scene_hash", scene_hash(scene.text));
  h5_->attribute("/", "seed", static_cast<std::int64_t>(scene.seed));
  h5_->attribute("/", "law", scene.plan.law);
  h5_->attribute("/", "rolling", scene.plan.rolling);
  h5_->attribute("/", "time_step_s", scene.config.dt);
  h5_->attribute("/", "end_time_s", scene.end_time);
  h5_->attribute("/", "particle_count", static_cast<std::int64_t>(scene.particles.size()));
  // The resolved Plan and defaults (what the scene text leaves implicit).
  h5_->attribute("/", "skin_m", scene.config.skin);
  h5_->attribute("/", "rotation", static_cast<std::int64_t>(scene.plan.rotation));
  h5_->attribute("/", "history_width", static_cast<std::int64_t>(scene.plan.history_width));
  h5_->attribute("/", "output_interval_s", scene.output_interval);
  h5_->attribute("/", "energy_interval_s", scene.energy_interval);
  std::vector<std::string> names;
  for (const auto& m : scene.materials) names.push_back(m.name);
  h5_->write_strings("/materials", names);
  std::vector<double> densities;
  for (const auto& m : scene.materials) densities.push_back(m.density);
  h5_->write("/material_density", densities);
  // Fluid (only with [[fluid]]): the first region's fluid for the analysis layer.
  if (!scene.fluid.empty()) {
    const auto& f = scene.fluid.front();
    h5_->attribute("/", "fluid_density", f.density());
    h5_->attribute("/", "fluid_solids_fraction", f.solids_fraction);
    h5_->attribute("/", "fluid_region_count", static_cast<std::int64_t>(scene.fluid.size()));
    if (f.flow) {
      h5_->create_group("/flow");
      h5_->attribute("/flow", "dynamics", "flow");
      h5_->attribute("/flow", "cell_m", f.flow_cell);
      h5_->attribute("/flow", "top_m", f.flow_top);
      h5_->attribute("/flow", "kernel_width", f.kernel_width);
      h5_->attribute("/flow", "coupling_interval", static_cast<std::int64_t>(f.coupling_interval));
      h5_->attribute("/flow", "regularisation_s", f.regularisation);
      if (f.flow_time_step > 0.0) h5_->attribute("/flow", "flow_time_step_s", f.flow_time_step);
      if (f.implicit_stick) h5_->attribute("/flow", "implicit_stick", static_cast<std::int64_t>(1));
    }
  }
}

// The flow's cell fields at this snapshot (model/output.h), under the snapshot's own number.
void RunOutput::flow_snapshot(const fluid::FlowCoupling& c, std::size_t k) {
  const fluid::FlowFields f = c.fields();
  if (k == 0) {
    const char* axis[] = {"x", "y", "z"};
    for (int d = 0; d < 3; ++d) {
      h5_->attribute("/flow", fmt::format("n{}", axis[d]), static_cast<std::int64_t>(f.n[d]));
      h5_->attribute("/flow", fmt::format("h{}", axis[d]), f.h[d]);
      h5_->attribute("/flow", fmt::format("origin_{}", axis[d]), f.origin[d]);
    }
  }
  const std::string g = fmt::format("/flow/snapshots/{:06d}", k);
  const std::vector<std::uint64_t> dims{static_cast<std::uint64_t>(f.n[2]), static_cast<std::uint64_t>(f.n[1]),
                                        static_cast<std::uint64_t>(f.n[0])};
  h5_->write(g + "/paste_fraction", f.paste_fraction, dims);
  h5_->write(g + "/fluid_fraction", f.fluid_fraction, dims);
  h5_->write(g + "/pressure", f.pressure, dims);
  h5_->write(g + "/velocity", f.velocity, {dims[0], dims[1], dims[2], 3});
  h5_->attribute(g, "time_s", c.solver_time());
}

RunOutput::~RunOutput() = default;

void RunOutput::write_escaped(const World& w) {
  const std::vector<Escape>& esc = w.escaped();
  const std::uint64_t n = esc.size();
  std::vector<std::int64_t> id;
  std::vector<std::int32_t> mat;
  std::vector<double> time, mass, radius;
  std::vector<Vec3> x, v;
  for (const Escape& e : esc) {
    id.push_back(e.id);
    mat.push_back(e.material);
    time.push_back(e.time);
    mass.push_back(e.mass);
    radius.push_back(e.radius);
    x.push_back(e.x);
    v.push_back(e.v);
  }
  h5_->write("/escaped/id", id, {n});
  h5_->write("/escaped/time", time, {n});
  h5_->write("/escaped/mass", mass, {n});
  h5_->write("/escaped/radius", radius, {n});
  h5_->write("/escaped/material", mat, {n});
  h5_->write("/escaped/position", flat(x), {n, 3});
  h5_->write("/escaped/velocity", flat(v), {n, 3});
  const bool remove = w.config().on_exit == ExitRule::remove;
  h5_->attribute("/", "on_exit", remove ? "remove" : "stop");
  if (remove) h5_->attribute("/", "max_escaped_fraction", w.config().max_escaped_fraction);
  h5_->attribute("/", "escaped_count", static_cast<std::int64_t>(n));
  h5_->attribute("/", "escaped_mass", w.escaped_mass());
}

namespace {

// The particles by ascending id: the engine's dense order is spatial once it sorts the store
// ([neighbor] sort_every), and the files keep the layout they have without the sort.
std::vector<std::size_t> id_order(const Particles& p) {
  std::vector<std::size_t> by_id(p.size());
  std::iota(by_id.begin(), by_id.end(), std::size_t{0});
  if (!std::is_sorted(p.id.begin(), p.id.end()))
    std::sort(by_id.begin(), by_id.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
  return by_id;
}

}  // namespace

void RunOutput::snapshot(const World& w) {
  const Particles& p = w.particles();
  const std::string g = group(snap_times_.size());
  const std::uint64_t n = p.size();
  const std::vector<std::size_t> by_id = id_order(p);
  auto in_id_order = [&](const auto& v) {
    std::vector<std::decay_t<decltype(v[0])>> out(n);
    for (std::size_t k = 0; k < n; ++k) out[k] = v[by_id[k]];
    return out;
  };
  h5_->write(g + "/position", flat(in_id_order(p.x)), {n, 3});
  h5_->write(g + "/velocity", flat(in_id_order(p.v)), {n, 3});
  h5_->write(g + "/radius", in_id_order(p.radius), {n});
  h5_->write(g + "/id", in_id_order(p.id), {n});
  const std::vector<int> mat_sorted = in_id_order(p.material);
  std::vector<std::int32_t> mat(mat_sorted.begin(), mat_sorted.end());
  h5_->write(g + "/material", mat, {n});
  if (rotation_) h5_->write(g + "/angular_velocity", flat(in_id_order(p.omega)), {n, 3});
  h5_->attribute(g, "time_s", w.time());
  if (const auto* c = w.flow()) flow_snapshot(*c, snap_times_.size());
  snap_times_.push_back(w.time());
  snap_counts_.push_back(p.size());
}

void RunOutput::mean_speed(const World& w, const std::vector<double>& speeds) {
  const Particles& p = w.particles();
  if (snap_times_.empty() || speeds.size() != p.size() || p.size() != snap_counts_.back())
    throw std::logic_error("mean_speed: no last snapshot of the same particles");
  const std::vector<std::size_t> by_id = id_order(p);
  std::vector<double> out(speeds.size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = speeds[by_id[k]];
  h5_->write(group(snap_times_.size() - 1) + "/mean_speed", out, {out.size()});
}

void RunOutput::sample(const World& w) {
  const Energies e = w.energies();
  t_.push_back(w.time());
  ke_.push_back(e.kinetic);
  rot_.push_back(e.rotational);
  pot_.push_back(e.potential);
  el_.push_back(e.elastic);
  npair_.push_back(e.pair_contacts);
  nwall_.push_back(e.wall_contacts);
  if (const auto* f = w.fluid()) surface_.insert(surface_.end(), f->surfaces().begin(), f->surfaces().end());
  if (const auto* c = w.flow()) paste_volume_.push_back(c->paste_volume());
}

void RunOutput::stop_outcome(const StopOutcome& o, const StopRule& rule) {
  h5_->attribute("/", "stop_rule", rule.at_rest ? "at_rest" : "end_time");
  h5_->attribute("/", "stop_fired", static_cast<std::int64_t>(o.fired));
  h5_->attribute("/", "stop_time_s", o.time);
  h5_->attribute("/", "stop_speed_m_s", rule.speed);
  h5_->attribute("/", "stop_paste_speed_m_s", rule.paste_speed);
  h5_->attribute("/", "stop_moving_mass_limit_kg", rule.moving_mass);
  h5_->attribute("/", "stop_measure", rule.measure == RestMeasure::displacement ? "displacement" : "velocity");
  h5_->attribute("/", "moving_mass_kg", o.last.moving_mass);
  h5_->attribute("/", "in_flight_mass_kg", o.last.in_flight_mass);
  h5_->attribute("/", "moving_count", static_cast<std::int64_t>(o.last.moving_count));
  h5_->attribute("/", "max_speed_m_s", o.last.max_speed);
}

std::string RunOutput::finish(const World& w, double wall_seconds, int threads) {
  h5_->write("/snapshots/time", snap_times_);
  h5_->write("/timeseries/time", t_);
  h5_->write("/timeseries/kinetic", ke_);
  h5_->write("/timeseries/rotational", rot_);
  h5_->write("/timeseries/potential", pot_);
  h5_->write("/timeseries/elastic", el_);
  h5_->write("/timeseries/pair_contacts", npair_);
  h5_->write("/timeseries/wall_contacts", nwall_);
  write_escaped(w);
  if (const auto* f = w.fluid()) {
    const std::uint64_t r = f->regions().size();
    h5_->write("/timeseries/fluid_surface_z", surface_, {t_.size(), r});
    h5_->attribute("/", "fluid_surface_z", f->surface_z(0));
  }
  if (const auto* c = w.flow()) {
    h5_->write("/flow/timeseries/paste_volume", paste_volume_);
    h5_->attribute("/flow", "cycles", static_cast<std::int64_t>(c->cycles()));
    h5_->attribute("/flow", "flow_steps", static_cast<std::int64_t>(c->flow_steps()));
    // The flow's cost, for a user sizing a run: its linear solves' iterations and its wall time (s).
    const auto& cost = c->solver().totals();
    h5_->attribute("/flow", "pressure_iterations", static_cast<std::int64_t>(cost.pressure_iterations));
    h5_->attribute("/flow", "viscous_iterations", static_cast<std::int64_t>(cost.viscous_iterations));
    h5_->attribute("/flow", "solver_seconds", cost.seconds);
  }
  const Profile& prof = w.profile();
  std::vector<std::string> names(Profile::names.begin(), Profile::names.end());
  std::vector<double> secs(prof.seconds.begin(), prof.seconds.end());
  h5_->write_strings("/profile/stage", names);
  h5_->write("/profile/seconds", secs);
  h5_->attribute("/profile", "steps", static_cast<std::int64_t>(w.steps()));
  h5_->attribute("/profile", "rebuilds", static_cast<std::int64_t>(prof.rebuilds));
  h5_->attribute("/profile", "sorts", static_cast<std::int64_t>(prof.sorts));
  h5_->attribute("/profile", "wall_seconds", wall_seconds);
  h5_->attribute("/profile", "steps_per_second", wall_seconds > 0 ? static_cast<double>(w.steps()) / wall_seconds : 0.0);
  h5_->attribute("/profile", "threads", static_cast<std::int64_t>(threads));
  h5_->close();  // throws (path, cause) if the data did not reach the disk
  h5_.reset();

  std::string x = "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n";
  x += "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < snap_times_.size(); ++k) {
    const std::string g = group(k);
    const std::size_t n = snap_counts_[k];
    x += fmt::format("   <Grid Name=\"step{:06d}\" GridType=\"Uniform\">\n", k);
    x += fmt::format("    <Time Value=\"{:.9g}\"/>\n", snap_times_[k]);
    x += fmt::format("    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" NodesPerElement=\"1\"/>\n", n);
    x += "    <Geometry GeometryType=\"XYZ\">\n";
    x += fmt::format("     <DataItem Dimensions=\"{} 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">{}:{}/position</DataItem>\n",
                     n, h5_name_, g);
    x += "    </Geometry>\n";
    auto attr = [&](const char* name, const char* type, const std::string& dims, const char* num) {
      x += xdmf_attribute(name, type, "Node", dims, num, h5_name_ + ":" + g + "/" + name);
    };
    attr("radius", "Scalar", fmt::format("{}", n), "Float");
    attr("id", "Scalar", fmt::format("{}", n), "Int");
    attr("velocity", "Vector", fmt::format("{} 3", n), "Float");
    if (rotation_) attr("angular_velocity", "Vector", fmt::format("{} 3", n), "Float");
    x += "   </Grid>\n";
  }
  x += "  </Grid>\n";
  if (const auto* c = w.flow()) x += flow_xdmf(c->fields());
  x += " </Domain>\n</Xdmf>\n";
  return x;
}

// The flow's cell fields as a second temporal collection ("paste"): one 3DCoRectMesh per snapshot, nodes at the
// cell corners (origin + i h), the fields cell-centred, so ParaView shows the paste fraction as cells and
// "Contour" at paste_fraction = 0.5 draws the free surface. XDMF orders Origin, DxDyDz and Dimensions z, y, x,
// slowest first, as the datasets are stored (model/output.h).
std::string RunOutput::flow_xdmf(const fluid::FlowFields& f) const {
  const std::string cells = fmt::format("{} {} {}", f.n[2], f.n[1], f.n[0]);
  const std::string nodes = fmt::format("{} {} {}", f.n[2] + 1, f.n[1] + 1, f.n[0] + 1);
  std::string x = "  <Grid Name=\"paste\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < snap_times_.size(); ++k) {
    const std::string g = fmt::format("/flow/snapshots/{:06d}", k);
    x += fmt::format("   <Grid Name=\"flow{:06d}\" GridType=\"Uniform\">\n", k);
    x += fmt::format("    <Time Value=\"{:.9g}\"/>\n", snap_times_[k]);
    x += fmt::format("    <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"{}\"/>\n", nodes);
    x += "    <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n";
    x += fmt::format("     <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">{:.17g} {:.17g} {:.17g}"
                     "</DataItem>\n", f.origin[2], f.origin[1], f.origin[0]);
    x += fmt::format("     <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">{:.17g} {:.17g} {:.17g}"
                     "</DataItem>\n", f.h[2], f.h[1], f.h[0]);
    x += "    </Geometry>\n";
    auto attr = [&](const char* name, const char* type, const std::string& dims) {
      x += xdmf_attribute(name, type, "Cell", dims, "Float", h5_name_ + ":" + g + "/" + name);
    };
    attr("paste_fraction", "Scalar", cells);
    attr("fluid_fraction", "Scalar", cells);
    attr("pressure", "Scalar", cells);
    attr("velocity", "Vector", cells + " 3");
    x += "   </Grid>\n";
  }
  return x + "  </Grid>\n";
}

}  // namespace pastemix::model
