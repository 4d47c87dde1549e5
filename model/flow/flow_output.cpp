// SPDX-License-Identifier: MIT
#include "model/flow/flow_output.h"

#include <fmt/format.h>

namespace pastemix::flow {

namespace {
std::string group(std::size_t k) { return fmt::format("/flow/snapshots/{:06d}", k); }
}  // namespace

FlowWriter::FlowWriter(const std::filesystem::path& h5_path, std::string h5_name, const FlowSolver& s,
                       const std::string& source)
    : h5_(std::make_unique<H5Writer>(h5_path)), h5_name_(std::move(h5_name)), grid_(s.grid()) {
  const Grid& g = grid_;
  h5_->create_group("/flow/snapshots");
  const char* axis[3] = {"x", "y", "z"};
  for (int d = 0; d < 3; ++d) {
    h5_->attribute("/flow", fmt::format("n{}", axis[d]), static_cast<std::int64_t>(g.n[d]));
    h5_->attribute("/flow", fmt::format("h{}", axis[d]), g.h[d]);
    h5_->attribute("/flow", fmt::format("origin_{}", axis[d]), g.origin[d]);
  }
  std::string bc;
  for (int i = 0; i < 6; ++i) {
    if (i) bc += ' ';
    bc += boundary_name(g.bc[i].type);
  }
  h5_->attribute("/flow", "boundary", bc);
  h5_->attribute("/flow", "rho_paste", s.phases().rho_paste);
  h5_->attribute("/flow", "rho_air", s.phases().rho_air);
  h5_->attribute("/flow", "eta_air", s.phases().eta_air);
  h5_->attribute("/flow", "rheology", s.phases().paste->describe());
  h5_->attribute("/flow", "cfl", s.settings().cfl);
  h5_->attribute("/flow", "source", source);
}

FlowWriter::~FlowWriter() = default;

void FlowWriter::snapshot(const FlowSolver& s) {
  const Grid& g = grid_;
  const std::string grp = group(times_.size());
  const std::vector<std::uint64_t> dims{static_cast<std::uint64_t>(g.n[2]), static_cast<std::uint64_t>(g.n[1]),
                                        static_cast<std::uint64_t>(g.n[0])};
  const std::vector<double> vel = s.cell_velocity();
  h5_->write(grp + "/velocity", vel, {dims[0], dims[1], dims[2], 3});
  h5_->write(grp + "/pressure", s.pressure(), dims);
  h5_->write(grp + "/paste_fraction", s.alpha(), dims);
  h5_->write(grp + "/viscosity", s.viscosity(), dims);
  h5_->attribute(grp, "time_s", s.time());
  times_.push_back(s.time());
}

void FlowWriter::record_step(const FlowSolver& s) {
  const StepStats& st = s.last();
  ts_time_.push_back(s.time());
  ts_dt_.push_back(st.dt);
  ts_volume_.push_back(s.paste_volume());
  ts_speed_.push_back(s.max_speed());
  ts_piter_.push_back(st.projection.solve.iterations);
  ts_viter_.push_back(st.viscous.iterations);
  const auto& p = st.projection;
  ts_div_.push_back(p.divergence_before > 0 ? p.divergence_after / p.divergence_before : 0.0);
}

std::string FlowWriter::finish(const FlowSolver& s, int threads) {
  h5_->write("/flow/snapshots/time", times_);
  h5_->write("/flow/timeseries/time", ts_time_);
  h5_->write("/flow/timeseries/dt", ts_dt_);
  h5_->write("/flow/timeseries/paste_volume", ts_volume_);
  h5_->write("/flow/timeseries/max_speed", ts_speed_);
  h5_->write("/flow/timeseries/relative_divergence", ts_div_);
  h5_->write("/flow/timeseries/pressure_iterations", ts_piter_);
  h5_->write("/flow/timeseries/viscous_iterations", ts_viter_);
  h5_->create_group("/flow/cost");
  const CostTotals& t = s.totals();
  h5_->attribute("/flow/cost", "steps", static_cast<std::int64_t>(t.steps));
  h5_->attribute("/flow/cost", "cells", static_cast<std::int64_t>(grid_.cell_count()));
  h5_->attribute("/flow/cost", "wall_seconds", t.seconds);
  h5_->attribute("/flow/cost", "cell_steps_per_second",
                 t.seconds > 0 ? static_cast<double>(grid_.cell_count()) * static_cast<double>(t.steps) / t.seconds : 0.0);
  h5_->attribute("/flow/cost", "threads", static_cast<std::int64_t>(threads));
  h5_->flush();
  h5_.reset();

  const Grid& g = grid_;
  // 3DCoRectMesh: Dimensions are node counts, z slowest; Origin and Spacing in the same (z, y, x) order.
  const std::string nodes = fmt::format("{} {} {}", g.n[2] + 1, g.n[1] + 1, g.n[0] + 1);
  const std::string cells = fmt::format("{} {} {}", g.n[2], g.n[1], g.n[0]);
  std::string x = "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n";
  x += "  <Grid Name=\"flow\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < times_.size(); ++k) {
    const std::string grp = group(k);
    x += fmt::format("   <Grid Name=\"flow{:06d}\" GridType=\"Uniform\">\n", k);
    x += fmt::format("    <Time Value=\"{:.9g}\"/>\n", times_[k]);
    x += fmt::format("    <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"{}\"/>\n", nodes);
    x += "    <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n";
    x += fmt::format("     <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">{:.9g} {:.9g} {:.9g}</DataItem>\n",
                     g.origin[2], g.origin[1], g.origin[0]);
    x += fmt::format("     <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">{:.9g} {:.9g} {:.9g}</DataItem>\n",
                     g.h[2], g.h[1], g.h[0]);
    x += "    </Geometry>\n";
    auto attr = [&](const char* name, const char* type, const char* ds, const std::string& dims) {
      x += fmt::format("    <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Cell\">\n", name, type);
      x += fmt::format("     <DataItem Dimensions=\"{}\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">{}:{}/{}</DataItem>\n",
                       dims, h5_name_, grp, ds);
      x += "    </Attribute>\n";
    };
    attr("velocity", "Vector", "velocity", cells + " 3");
    attr("pressure", "Scalar", "pressure", cells);
    attr("paste_fraction", "Scalar", "paste_fraction", cells);
    attr("viscosity", "Scalar", "viscosity", cells);
    x += "   </Grid>\n";
  }
  x += "  </Grid>\n </Domain>\n</Xdmf>\n";
  return x;
}

}  // namespace pastemix::flow
