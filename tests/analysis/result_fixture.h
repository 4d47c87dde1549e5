// SPDX-License-Identifier: MIT
// Synthetic model result files (the schema of model/output.h plus the maps' /material_density and fluid
// attributes), and a synthetic lab.h5 case, written by the tests themselves.
#pragma once

#include <unistd.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "base/h5.h"

namespace pastemix::test {

struct Sphere {
  std::array<double, 3> c;  // m
  double r;                 // m
  int material = 0;
};

struct ResultSpec {
  std::vector<Sphere> final;           // last snapshot
  std::vector<double> densities{2760};  // kg/m3 per material
  std::int64_t seed = 7;
  bool material_density = true, surface = true, paste = true;
  double surface_z = 0.10, paste_density = 1843.0, solids = 0.75;
  std::string scene_hash = "00000000deadbeef";
  std::string scene_text = "# synthetic scene for the analysis tests\n";
  // Spheres removed at the domain boundary (model/output.h /escaped): removal time (s) and mass (kg).
  std::vector<std::array<double, 2>> escaped;
  // Final-snapshot velocities (m/s) per sphere; empty: all at rest. `velocities = false` writes none.
  std::vector<std::array<double, 3>> velocity;
  bool velocities = true;
  // The last snapshot's mean_speed (m/s per sphere: a [stop] displacement-measure run); empty: none written.
  std::vector<double> mean_speed;
  // A flow result's paste field (/flow, model/flow/flow_output.h schema) at t = 0.5 s when flow_n[0] > 0:
  // cells, size (m), low corner (m), alpha [k][j][i].
  std::array<std::int64_t, 3> flow_n{0, 0, 0};
  std::array<double, 3> flow_h{0.01, 0.01, 0.01}, flow_origin{0.0, 0.0, 0.0};
  std::vector<double> flow_alpha;
  std::int64_t flow_nz_attribute = 0;  // > 0: the nz attribute written instead of flow_n[2] (a bad file)
  // The engine's layout (model/output.h): a group per particle snapshot with its time_s, the field under the
  // same number (000000 at t = 0 all air, 000001 at t = 0.5 s), and no /flow/snapshots/time.
  bool flow_engine_layout = false;
};

inline void write_flow(H5Writer& h5, const ResultSpec& s) {
  h5.create_group("/flow");
  h5.create_group("/flow/snapshots");
  const char* axis[3] = {"x", "y", "z"};
  for (int d = 0; d < 3; ++d) {
    h5.attribute("/flow", fmt::format("n{}", axis[d]), d == 2 && s.flow_nz_attribute > 0 ? s.flow_nz_attribute : s.flow_n[d]);
    h5.attribute("/flow", fmt::format("h{}", axis[d]), s.flow_h[d]);
    h5.attribute("/flow", fmt::format("origin_{}", axis[d]), s.flow_origin[d]);
  }
  const std::vector<std::uint64_t> dims{std::uint64_t(s.flow_n[2]), std::uint64_t(s.flow_n[1]),
                                        std::uint64_t(s.flow_n[0])};
  if (s.flow_engine_layout) {
    h5.create_group("/flow/snapshots/000000");
    h5.write("/flow/snapshots/000000/paste_fraction", std::vector<double>(s.flow_alpha.size(), 0.0), dims);
    h5.attribute("/flow/snapshots/000000", "time_s", 0.0);
    h5.create_group("/flow/snapshots/000001");
    h5.write("/flow/snapshots/000001/paste_fraction", s.flow_alpha, dims);
    h5.attribute("/flow/snapshots/000001", "time_s", 0.5);
    return;
  }
  h5.write("/flow/snapshots/time", std::vector<double>{0.5});
  h5.create_group("/flow/snapshots/000000");
  h5.write("/flow/snapshots/000000/paste_fraction", s.flow_alpha, dims);
}

inline void write_result(const std::filesystem::path& path, const ResultSpec& s) {
  H5Writer h5(path);
  const std::string scene = s.scene_text;
  h5.attribute("/", "scene_path", "synthetic.toml");
  h5.attribute("/", "scene_text", scene);
  h5.attribute("/", "scene_hash", s.scene_hash);
  h5.attribute("/", "seed", s.seed);
  std::vector<std::string> names;
  for (std::size_t m = 0; m < s.densities.size(); ++m) names.push_back(fmt::format("rock{}", m));
  h5.write_strings("/materials", names);
  if (s.material_density) h5.write("/material_density", s.densities);
  if (s.surface) h5.attribute("/", "fluid_surface_z", s.surface_z);
  if (s.paste) {
    h5.attribute("/", "fluid_density", s.paste_density);
    h5.attribute("/", "fluid_solids_fraction", s.solids);
  }
  // Snapshot 0: the same spheres lifted 1 m (still falling); snapshot 1: the final state.
  for (int snap = 0; snap < 2; ++snap) {
    std::vector<double> pos, r;
    std::vector<std::int64_t> id;
    std::vector<std::int32_t> mat;
    for (std::size_t p = 0; p < s.final.size(); ++p) {
      const auto& q = s.final[p];
      pos.insert(pos.end(), {q.c[0], q.c[1], q.c[2] + (snap == 0 ? 1.0 : 0.0)});
      r.push_back(q.r);
      id.push_back(static_cast<std::int64_t>(p));
      mat.push_back(q.material);
    }
    const std::string g = fmt::format("/snapshots/{:06d}", snap);
    const std::uint64_t n = s.final.size();
    h5.write(g + "/position", pos, {n, 3});
    h5.write(g + "/radius", r, {n});
    h5.write(g + "/id", id, {n});
    h5.write(g + "/material", mat, {n});
    if (s.velocities) {
      std::vector<double> v(3 * n, 0.0);
      for (std::size_t p = 0; p < s.velocity.size() && p < n; ++p)
        for (int c = 0; c < 3; ++c) v[3 * p + static_cast<std::size_t>(c)] = snap == 0 ? -1.0 : s.velocity[p][static_cast<std::size_t>(c)];
      if (snap == 0)
        for (std::size_t p = 0; p < n; ++p) v[3 * p + 2] = -1.0;  // snapshot 0 is still falling
      h5.write(g + "/velocity", v, {n, 3});
    }
    if (snap == 1 && !s.mean_speed.empty()) h5.write(g + "/mean_speed", s.mean_speed, {s.mean_speed.size()});
    h5.attribute(g, "time_s", 0.5 * snap);
  }
  h5.write("/snapshots/time", std::vector<double>{0.0, 0.5});
  if (!s.escaped.empty()) {
    std::vector<double> t, m;
    for (const auto& e : s.escaped) t.push_back(e[0]), m.push_back(e[1]);
    h5.write("/escaped/time", t);
    h5.write("/escaped/mass", m);
  }
  if (s.flow_n[0] > 0) write_flow(h5, s);
  h5.flush();
}

// A scratch folder removed when the test ends.
struct ScratchDir {
  std::filesystem::path dir;
  explicit ScratchDir(const std::string& name) {
    dir = std::filesystem::temp_directory_path() / fmt::format("pastemix_an_{}_{}", name, static_cast<long>(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~ScratchDir() { std::filesystem::remove_all(dir); }
  std::filesystem::path operator/(const std::string& n) const { return dir / n; }
};

}  // namespace pastemix::test

namespace pastemix::test {

// A lab.h5 with the layout of lab/lab_h5.h for one case with a grid (C, flag, masses given per block in
// lab order) and, optionally, one case known from the mixing programme but without a grid (as cases 6, 7).
struct LabSpec {
  int case_id = 3;
  double K = 3570;
  std::vector<double> C, S, M_wr, M_paste;  // 36 each
  std::vector<std::int32_t> flag;           // 36
  int case_without_grid = 6;                // 0: none
};

inline void write_lab(const std::filesystem::path& path, const LabSpec& s) {
  H5Writer h5(path);
  const std::vector<std::uint64_t> dims{4, 3, 3};
  for (int c : {s.case_id, s.case_without_grid}) {
    if (c == 0) continue;
    const std::string p = fmt::format("/parameters/mixing.case_{}.paste_solids_fraction", c);
    h5.create_group(p);
    h5.attribute(p, "value", 0.75);
    h5.write(fmt::format("/psd/mixing_case_{}/d_min", c), std::vector<double>{0.0025});
  }
  const std::string g = fmt::format("/block_cut/case_{}", s.case_id);
  h5.write(g + "/C", s.C, dims);
  h5.write(g + "/S", s.S, dims);
  h5.write(g + "/S_raw", s.S, dims);
  h5.write(g + "/flag", s.flag, dims);
  h5.write(g + "/M_wr", s.M_wr, dims);
  h5.write(g + "/M_paste_dried", s.M_paste, dims);
  h5.attribute(g, "K", s.K);
  h5.attribute(g, "K_source", "synthetic");
  h5.flush();
}

}  // namespace pastemix::test
