// SPDX-License-Identifier: MIT
#include "lab/lab_h5.h"

#include <fmt/format.h>

#include "base/h5.h"

namespace pastemix::lab {

namespace {

constexpr const char* kLayout =
    "[i][j][k] row-major, dims 4x3x3: i = 1..4 along the 20 cm side (5 cm blocks), j = 1..3 along the 16.5 cm "
    "side (5.5 cm), k = layer 1..3 from the top (3 cm); C and S are fractions, NaN = undefined";

template <class T, std::size_t N>
void grid(H5Writer& h5, const std::string& path, const std::array<T, N>& a) {
  h5.write(path, std::span<const T>(a.data(), a.size()), {kBlocksI, kBlocksJ, kLayers});
}

void write_psd(H5Writer& h5, const std::string& g, const Psd& psd) {
  std::vector<double> lo, hi, f;
  for (const auto& iv : psd.intervals) {
    lo.push_back(iv.d_min);
    hi.push_back(iv.d_max);
    f.push_back(iv.mass_fraction);
  }
  h5.write(g + "/d_min", lo);
  h5.write(g + "/d_max", hi);
  h5.write(g + "/mass_fraction", f);
}

// C, S, S_raw and flag of a case's grid (as read, or corrected) under group p.
template <class Grids>
void mixing_grids(H5Writer& h5, const std::string& p, const Grids& g) {
  grid(h5, p + "/C", g.C);
  grid(h5, p + "/S", g.S);
  grid(h5, p + "/S_raw", g.S_raw);
  grid(h5, p + "/flag", g.flag);
}

void write_block_cut(H5Writer& h5, const BlockCutResult& bc) {
  for (const auto& g : bc.cases) {
    const std::string p = fmt::format("/block_cut/case_{}", g.case_id);
    mixing_grids(h5, p, g);
    grid(h5, p + "/M_wr", g.M_wr);
    grid(h5, p + "/M_paste_dried", g.M_paste);
    grid(h5, p + "/C_printed", g.C_printed);
    grid(h5, p + "/S_printed", g.S_printed);
    std::array<std::int32_t, kBlocks> line{};
    for (int b = 0; b < kBlocks; ++b) line[b] = g.line[b];
    grid(h5, p + "/line", line);
    h5.attribute(p, "K", g.K);
    h5.attribute(p, "K_source", g.K_source);
  }
  for (const auto& g : bc.corrected) {
    const std::string p = fmt::format("/block_cut/case_{}/corrected", g.case_id);
    mixing_grids(h5, p, g);
    grid(h5, p + "/M_paste_dried", g.M_paste);
    grid(h5, p + "/applied", g.corrected);
  }
  h5.attribute("/block_cut", "grid_layout", kLayout);
  h5.attribute("/block_cut", "flag_legend", "0 value, 1 capped at 1 (eq. 3.8 > 1), 2 no rock (S undefined), 3 K unknown");
  h5.attribute("/block_cut", "printed_C_blocks", static_cast<std::int64_t>(bc.printed.n_C));
  h5.attribute("/block_cut", "printed_C_max_error_pp", bc.printed.max_C_error_pp);
  h5.attribute("/block_cut", "printed_S_values_compared", static_cast<std::int64_t>(bc.printed.n_S));
  h5.attribute("/block_cut", "printed_S_max_relative_error", bc.printed.max_S_rel_error);
  h5.attribute("/block_cut", "capped_blocks", static_cast<std::int64_t>(bc.printed.n_capped));
}

}  // namespace

void write_lab_h5(const std::filesystem::path& path, const ReduceResult& r, const RunInfo& info) {
  H5Writer h5(path);
  h5.attribute("/", "software", info.software);
  h5.attribute("/", "command", info.command);
  h5.attribute("/", "created", info.created);
  h5.attribute("/", "dataset", r.dataset_dir);
  h5.attribute("/", "manifest", r.manifest);
  h5.attribute("/", "grid_layout", kLayout);
  for (const auto& p : r.parameters) {
    const std::string g = "/parameters/" + p.key;
    h5.create_group(g);
    h5.attribute(g, "value", p.value);
    h5.attribute(g, "sd", p.sd);
    h5.attribute(g, "n", static_cast<std::int64_t>(p.n));
    h5.attribute(g, "unit", p.unit);
    h5.attribute(g, "provenance", to_string(p.provenance));
    h5.attribute(g, "method", p.method);
    h5.attribute(g, "source", p.source);
    if (!p.text.empty()) h5.attribute(g, "text", p.text);
    if (!p.note.empty()) h5.attribute(g, "note", p.note);  // e.g. the "at-rest effective" label of paste_rheology.*
    if (!p.trials.empty()) h5.write(g + "/trials", p.trials);
  }
  if (r.block_cut) write_block_cut(h5, *r.block_cut);
  for (const auto& c : r.mixing_cases) {
    const std::string g = fmt::format("/psd/mixing_case_{}", c.case_id);
    write_psd(h5, g, c.psd);
    h5.attribute(g, "source", r.mixing_source);
  }
  for (const auto& s : r.sieves) {
    const std::string g = "/sieve/" + s.name;
    write_psd(h5, g, s.result.psd);
    h5.write(g + "/sieves", s.result.sieves);
    h5.write(g + "/passing", s.result.passing);
    h5.attribute(g, "source", s.source);
    h5.attribute(g, "provenance", to_string(s.provenance));
    h5.attribute(g, "pan_fraction", s.result.pan_fraction);
    h5.attribute(g, "cut_m", s.result.cut);
  }
  std::vector<std::string> warnings;
  for (const auto& w : r.warnings) warnings.push_back(w.where + ": " + w.message);
  if (warnings.empty()) warnings.push_back("(none)");
  h5.write_strings("/warnings", warnings);
  h5.write_strings("/inputs", r.inputs);
  h5.close();
}

}  // namespace pastemix::lab
