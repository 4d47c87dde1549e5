// SPDX-License-Identifier: MIT
#include "analysis/maps/result_file.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "base/error.h"
#include "base/h5.h"
#include "base/hash.h"

namespace pastemix::analysis {

namespace {

namespace fs = std::filesystem;

// A snapshot group name is six digits ("000042").
bool is_snapshot_name(const std::string& s) {
  return s.size() == 6 && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// N x 3 values (a dataset read flat) as N vectors; a non-finite component is an InputError naming the
// dataset and the particle.
std::vector<Vec3> vectors_of(const std::vector<double>& flat, const std::string& file, const std::string& dataset) {
  std::vector<Vec3> out(flat.size() / 3);
  for (std::size_t p = 0; p < out.size(); ++p) {
    out[p] = {flat[3 * p], flat[3 * p + 1], flat[3 * p + 2]};
    if (!std::isfinite(out[p].x) || !std::isfinite(out[p].y) || !std::isfinite(out[p].z))
      throw InputError(file, 0, fmt::format("dataset '{}'", dataset), fmt::format("particle {} is not finite", p));
  }
  return out;
}

// The paste property `attr`: the override if given, else the file's root attribute, else an InputError.
Sourced fluid_property(const H5Reader& h5, const std::string& file, const char* attr, std::optional<double> over,
                       const char* option, const char* unit, std::vector<std::string>& notes) {
  const bool in_file = h5.has_attribute("/", attr);
  if (over) {
    std::string note = fmt::format("{} = {:g} {} from the command line {}", attr, *over, unit, option);
    if (in_file) note += fmt::format(" (overrides the file's {:g})", h5.attribute_double("/", attr));
    else note += " (the file has no such attribute)";
    notes.push_back(note);
    return {*over, fmt::format("command line {}", option)};
  }
  if (!in_file)
    throw InputError(file, 0, fmt::format("attribute '{}' of '/'", attr),
                     fmt::format("missing from the file (a result without a fluid, or from an engine that does not "
                                 "write it yet); give it with {} ({})",
                                 option, unit));
  return {h5.attribute_double("/", attr), fmt::format("file attribute '{}'", attr)};
}

}  // namespace

std::string seedless_scene_key(const std::string& text) {
  // The scene's lines without a `seed = ...` line before the first [table] header, hashed like scene_hash.
  std::string kept;
  bool top = true;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line(text.data() + start, end - start);
    const std::size_t first = line.find_first_not_of(" \t");
    const std::string_view body = first == std::string_view::npos ? std::string_view{} : line.substr(first);
    if (body.starts_with('[')) top = false;
    const std::size_t eq = body.find_first_not_of(" \t", 4);
    const bool seed_line = top && body.starts_with("seed") && eq != std::string_view::npos && body[eq] == '=';
    if (!seed_line) kept.append(line).push_back('\n');
    start = end + 1;
  }
  return text_hash(kept);
}

int snapshot_index(const H5Reader& h5, const std::string& file, std::optional<int> chosen) {
  if (!h5.exists("/snapshots")) throw InputError(file, 0, "group '/snapshots'", "missing from the file");
  std::vector<int> snaps;
  for (const auto& name : h5.children("/snapshots"))
    if (is_snapshot_name(name)) snaps.push_back(std::stoi(name));
  std::sort(snaps.begin(), snaps.end());
  if (snaps.empty()) throw InputError(file, 0, "group '/snapshots'", "holds no snapshot (NNNNNN groups)");
  if (!chosen) return snaps.back();
  if (!std::binary_search(snaps.begin(), snaps.end(), *chosen))
    throw InputError(file, 0, "--snapshot",
                     fmt::format("snapshot {} not in the file (it has {} to {})", *chosen, snaps.front(), snaps.back()));
  return *chosen;
}

namespace {

void check_is_file(const fs::path& path) {
  if (!fs::exists(path)) throw InputError(path.string(), 0, "", "no such file");
  if (!fs::is_regular_file(path)) throw InputError(path.string(), 0, "", "not a regular file");
}

// A checkpoint (model/checkpoint.h) holds the snapshots so far of a run that did not finish: its last one is
// not the final state a map is about.
void check_not_checkpoint(const H5Reader& h5, const std::string& file) {
  if (h5.exists("/checkpoint"))
    throw InputError(file, 0, "", fmt::format("the checkpoint of an interrupted run (stopped at t = {:.6g} s), not a "
                                              "result: continue it with `{}`",
                                              h5.attribute_double("/checkpoint", "time_s"),
                                              h5.attribute_string("/checkpoint", "resume_with")));
}

// Positions, radii (> 0) and velocities of snapshot group g; returns the particles' material indices.
std::vector<std::int64_t> read_particles(const H5Reader& h5, const std::string& file, const std::string& g,
                                         ResultSnapshot& r) {
  const auto pos = h5.read_doubles(g + "/position");
  const auto pdims = h5.dims(g + "/position");
  r.radius = h5.read_doubles(g + "/radius");
  std::vector<std::int64_t> mat = h5.read_ints(g + "/material");
  const std::size_t n = r.radius.size();
  if (pdims.size() != 2 || pdims[1] != 3 || pdims[0] != n)
    throw InputError(file, 0, fmt::format("dataset '{}/position'", g),
                     fmt::format("expected N x 3 with N = {} (the radius count)", n));
  if (mat.size() != n)
    throw InputError(file, 0, fmt::format("dataset '{}/material'", g), fmt::format("expected {} values", n));
  r.position = vectors_of(pos, file, g + "/position");
  for (std::size_t p = 0; p < n; ++p) {
    if (!(r.radius[p] > 0.0) || !std::isfinite(r.radius[p]))
      throw InputError(file, 0, fmt::format("dataset '{}/radius'", g),
                       fmt::format("particle {}: radius must be positive, got {}", p, r.radius[p]));
  }
  if (h5.exists(g + "/velocity")) {
    const auto vel = h5.read_doubles(g + "/velocity");
    if (vel.size() != 3 * n)
      throw InputError(file, 0, fmt::format("dataset '{}/velocity'", g), fmt::format("expected {} x 3 values", n));
    r.velocity = vectors_of(vel, file, g + "/velocity");
  }
  if (h5.exists(g + "/mean_speed")) {
    r.mean_speed = h5.read_doubles(g + "/mean_speed");
    if (r.mean_speed.size() != n)
      throw InputError(file, 0, fmt::format("dataset '{}/mean_speed'", g), fmt::format("expected {} values", n));
    for (std::size_t p = 0; p < n; ++p)
      if (!(r.mean_speed[p] >= 0.0))  // +inf is allowed: a particle the rule had no earlier position of
        throw InputError(file, 0, fmt::format("dataset '{}/mean_speed'", g),
                         fmt::format("particle {}: a speed must be >= 0, got {}", p, r.mean_speed[p]));
  }
  return mat;
}

// Every material's density (kg/m3, > 0) from /material_density; empty with --rock-density.
std::vector<double> material_densities(const H5Reader& h5, const std::string& file, const ResultOverrides& over,
                                       ResultSnapshot& r) {
  const auto names = h5.exists("/materials") ? h5.read_strings("/materials") : std::vector<std::string>{};
  std::vector<double> rho;
  if (over.rock_density) {
    r.density_source = fmt::format("command line --rock-density ({:g} kg/m3 for every particle)", *over.rock_density);
    r.notes.push_back(r.density_source + (h5.exists("/material_density") ? ", overriding /material_density" : ""));
    return rho;
  }
  if (!h5.exists("/material_density"))
    throw InputError(file, 0, "dataset '/material_density'",
                     "missing from the file (an engine that does not write it yet); give --rock-density (kg/m3)");
  rho = h5.read_doubles("/material_density");
  if (!names.empty() && rho.size() != names.size())
    throw InputError(file, 0, "dataset '/material_density'",
                     fmt::format("has {} values for {} materials in /materials", rho.size(), names.size()));
  for (std::size_t m = 0; m < rho.size(); ++m)
    if (!(rho[m] > 0.0) || !std::isfinite(rho[m]))
      throw InputError(file, 0, "dataset '/material_density'",
                       fmt::format("material {}: density must be positive, got {}", m, rho[m]));
  r.density_source = "file dataset '/material_density'";
  return rho;
}

// Each particle's density (kg/m3) from its material, or --rock-density for all.
void particle_densities(const std::string& file, const std::string& g, const std::vector<std::int64_t>& mat,
                        const std::vector<double>& rho, const ResultOverrides& over, ResultSnapshot& r) {
  const std::size_t n = r.radius.size();
  r.density.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    if (over.rock_density) {
      r.density[p] = *over.rock_density;
      continue;
    }
    if (mat[p] < 0 || static_cast<std::size_t>(mat[p]) >= rho.size())
      throw InputError(file, 0, fmt::format("dataset '{}/material'", g),
                       fmt::format("particle {}: material {} is not in /material_density ({} entries)", p, mat[p],
                                   rho.size()));
    r.density[p] = rho[static_cast<std::size_t>(mat[p])];
  }
}

// Outflow: rock removed at the domain boundary up to the snapshot (removed at time <= the snapshot's).
void read_escaped(const H5Reader& h5, const std::string& file, ResultSnapshot& r) {
  if (!h5.exists("/escaped/mass")) return;
  const auto em = h5.read_doubles("/escaped/mass");
  const auto et = h5.read_doubles("/escaped/time");
  if (et.size() != em.size())
    throw InputError(file, 0, "dataset '/escaped/time'",
                     fmt::format("has {} values for {} in /escaped/mass", et.size(), em.size()));
  for (std::size_t e = 0; e < em.size(); ++e) {
    if (!(em[e] > 0.0) || !std::isfinite(em[e]) || !std::isfinite(et[e]))
      throw InputError(file, 0, "dataset '/escaped/mass'",
                       fmt::format("entry {}: mass must be positive and finite, got {} (time {})", e, em[e], et[e]));
    if (std::isnan(r.time_s) || et[e] <= r.time_s) {
      r.escaped_mass += em[e];
      ++r.escaped_count;
    }
  }
}

// The paste's surface height (m), density (kg/m3) and solids fraction: file attributes or overrides, checked.
void read_paste(const H5Reader& h5, const std::string& file, const ResultOverrides& over, ResultSnapshot& r) {
  if (has_paste_field(h5)) r.paste_field = read_paste_field(h5, file, std::isnan(r.time_s) ? 0.0 : r.time_s);
  if (r.paste_field && !over.surface_z && !h5.has_attribute("/", "fluid_surface_z"))
    r.surface_z = {std::nan(""), "the paste field " + r.paste_field->source};
  else
    r.surface_z = fluid_property(h5, file, "fluid_surface_z", over.surface_z, "--surface-z", "m", r.notes);
  r.paste_density = fluid_property(h5, file, "fluid_density", over.paste_density, "--paste-density", "kg/m3", r.notes);
  r.solids_fraction =
      fluid_property(h5, file, "fluid_solids_fraction", over.solids_fraction, "--solids", "fraction", r.notes);
  if (!std::isfinite(r.surface_z.value) && !r.paste_field)
    throw InputError(file, 0, r.surface_z.source, "fluid surface height is not finite");
  if (!(r.paste_density.value > 0.0) || !std::isfinite(r.paste_density.value))
    throw InputError(file, 0, r.paste_density.source,
                     fmt::format("paste density must be positive (kg/m3), got {}", r.paste_density.value));
  if (!(r.solids_fraction.value > 0.0 && r.solids_fraction.value <= 1.0))
    throw InputError(file, 0, r.solids_fraction.source,
                     fmt::format("solids fraction must be in (0, 1] (e.g. 0.75), got {}", r.solids_fraction.value));
}

}  // namespace

ResultSnapshot read_result(const fs::path& path, const ResultOverrides& over) {
  const std::string file = path.string();
  check_is_file(path);
  H5Reader h5(path);
  check_not_checkpoint(h5, file);
  ResultSnapshot r;
  r.path = file;
  r.seed = h5.has_attribute("/", "seed") ? h5.attribute_int("/", "seed") : -1;
  r.scene_hash = h5.has_attribute("/", "scene_hash") ? h5.attribute_string("/", "scene_hash") : "";
  r.ensemble_key = h5.has_attribute("/", "scene_text") ? seedless_scene_key(h5.attribute_string("/", "scene_text"))
                                                       : r.scene_hash;
  r.snapshot = snapshot_index(h5, file, over.snapshot);
  const std::string g = fmt::format("/snapshots/{:06d}", r.snapshot);
  r.time_s = h5.has_attribute(g, "time_s") ? h5.attribute_double(g, "time_s") : std::nan("");
  const std::vector<std::int64_t> mat = read_particles(h5, file, g, r);
  const std::vector<double> rho = material_densities(h5, file, over, r);
  particle_densities(file, g, mat, rho, over, r);
  read_escaped(h5, file, r);
  read_paste(h5, file, over, r);
  return r;
}

}  // namespace pastemix::analysis
