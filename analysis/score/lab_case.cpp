// SPDX-License-Identifier: MIT
#include "analysis/score/lab_case.h"

#include <algorithm>

#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "base/error.h"
#include "base/h5.h"

namespace pastemix::analysis {

namespace {

template <class T, std::size_t N>
void read_grid(const H5Reader& h5, const std::string& file, const std::string& path, std::array<T, N>& out) {
  const auto dims = h5.dims(path);
  if (dims != std::vector<std::uint64_t>{lab::kBlocksI, lab::kBlocksJ, lab::kLayers})
    throw InputError(file, 0, fmt::format("dataset '{}'", path), "expected a 4 x 3 x 3 grid");
  if constexpr (std::is_floating_point_v<T>) {
    const auto v = h5.read_doubles(path);
    for (std::size_t b = 0; b < N; ++b) out[b] = v[b];
  } else {
    const auto v = h5.read_ints(path);
    for (std::size_t b = 0; b < N; ++b) out[b] = static_cast<T>(v[b]);
  }
}

std::vector<int> known_cases(const H5Reader& h5) {
  std::vector<int> cases;
  if (!h5.exists("/psd")) return cases;
  for (const auto& name : h5.children("/psd"))
    if (name.rfind("mixing_case_", 0) == 0) cases.push_back(std::stoi(name.substr(12)));
  return cases;
}

}  // namespace

LabCase read_lab_case(const std::filesystem::path& lab_h5, int case_id, bool need_grid) {
  const std::string file = lab_h5.string();
  if (!std::filesystem::exists(lab_h5))
    throw InputError(file, 0, "", "no such file (make it with `pastemix lab reduce datasets/thesis --out out/lab`)");
  H5Reader h5(lab_h5);
  LabCase c;
  c.lab_path = file;
  c.case_id = case_id;
  const std::string prefix = fmt::format("/parameters/mixing.case_{}.", case_id);
  const std::string grid = fmt::format("/block_cut/case_{}", case_id);
  const bool known = h5.exists(prefix + "paste_solids_fraction") || h5.exists(grid);
  if (!known) {
    const auto cases = known_cases(h5);
    throw InputError(file, 0, "--lab",
                     fmt::format("case {} is not a mixing case in this lab.h5 (it has cases {})", case_id,
                                 cases.empty() ? std::string("none") : fmt::format("{}", fmt::join(cases, ", "))));
  }
  if (h5.exists(prefix + "paste_solids_fraction"))
    c.solids_fraction = h5.attribute_double(prefix + "paste_solids_fraction", "value");
  if (h5.exists(prefix + "falling_height")) c.falling_height = h5.attribute_double(prefix + "falling_height", "value");
  const std::string psd = fmt::format("/psd/mixing_case_{}", case_id);
  if (h5.exists(psd + "/d_min") && h5.exists(psd + "/d_max")) {
    const auto lo = h5.read_doubles(psd + "/d_min"), hi = h5.read_doubles(psd + "/d_max");
    if (!lo.empty() && !hi.empty()) {
      c.d_min = *std::min_element(lo.begin(), lo.end());
      c.d_max = *std::max_element(hi.begin(), hi.end());
    }
  }
  const std::string kparam = fmt::format("/parameters/block_cut.case_{}.K", case_id);
  c.has_grid = h5.exists(grid);
  if (c.has_grid) {
    c.K = h5.attribute_double(grid, "K");
    c.K_source = fmt::format("{} {} attribute K ({})", file, grid, h5.attribute_string(grid, "K_source"));
  } else if (h5.exists(kparam)) {
    c.K = h5.attribute_double(kparam, "value");
    c.K_source = fmt::format("{} parameter block_cut.case_{}.K", file, case_id);
  }
  if (!c.has_grid) {
    if (need_grid)
      throw InputError(file, 0, fmt::format("group '{}'", grid),
                       fmt::format("case {} has no lab block grid: its measured C and S are not in the dataset "
                                   "(the thesis's grids of cases 6 and 7 are reserved for blind validation), so "
                                   "there is nothing to score against; `pastemix maps` still maps the result",
                                   case_id));
    return c;
  }
  lab::BlockGrid& g = c.grid;
  g.case_id = case_id;
  g.K = c.K;
  g.K_source = c.K_source;
  read_grid(h5, file, grid + "/C", g.C);
  read_grid(h5, file, grid + "/S", g.S);
  read_grid(h5, file, grid + "/S_raw", g.S_raw);
  read_grid(h5, file, grid + "/flag", g.flag);
  read_grid(h5, file, grid + "/M_wr", g.M_wr);
  read_grid(h5, file, grid + "/M_paste_dried", g.M_paste);
  return c;
}

}  // namespace pastemix::analysis
