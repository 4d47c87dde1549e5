// SPDX-License-Identifier: MIT
#include "analysis/score/realization_check.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "base/error.h"

namespace pastemix::analysis {

namespace {

std::string canonical(const std::string& path) {
  std::error_code ec;
  const auto p = std::filesystem::weakly_canonical(path, ec);
  return ec ? path : p.string();
}

double median_diameter(const ResultSnapshot& r) {
  std::vector<double> d(r.radius);
  if (d.empty()) return std::nan("");
  std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
  return 2.0 * d[d.size() / 2];
}

void check_distinct(const std::vector<ResultSnapshot>& results) {
  for (std::size_t a = 0; a < results.size(); ++a)
    for (std::size_t b = 0; b < a; ++b) {
      const auto &x = results[a], &y = results[b];
      if (canonical(x.path) == canonical(y.path))
        throw InputError(x.path, 0, "", fmt::format("given twice (as result {} and {}): one realization would count "
                                                    "as two",
                                                    b + 1, a + 1));
      if (!x.ensemble_key.empty() && x.ensemble_key == y.ensemble_key && x.seed >= 0 && x.seed == y.seed)
        throw InputError(x.path, 0, "attribute 'seed' of '/'",
                         fmt::format("seed {} of scene {} is also the seed of {}: the same realization twice (a "
                                     "copied file?); give distinct seeds",
                                     x.seed, x.scene_hash, y.path));
    }
  // Seeded realizations differ in their top-level seed (so in scene_hash): compare the scenes without it.
  for (const auto& r : results)
    if (r.ensemble_key != results.front().ensemble_key)
      throw InputError(r.path, 0, "attribute 'scene_hash' of '/'",
                       fmt::format("scene {} differs from {}'s scene {}: an ensemble must be realizations of one "
                                   "scene (score them separately)",
                                   r.scene_hash.empty() ? "(none)" : r.scene_hash, results.front().path,
                                   results.front().scene_hash.empty() ? "(none)" : results.front().scene_hash));
}

void check_case(const LabCase& lab, const ResultSnapshot& r) {
  const bool solids_from_file = r.solids_fraction.source.rfind("command line", 0) != 0;
  if (solids_from_file && std::isfinite(lab.solids_fraction) &&
      std::abs(r.solids_fraction.value - lab.solids_fraction) > kSolidsTolerance)
    throw InputError(r.path, 0, r.solids_fraction.source,
                     fmt::format("paste of {:.1f} % solids, but lab case {} had {:.1f} % (in {}): is --lab {} the "
                                 "case this result simulates?",
                                 100 * r.solids_fraction.value, lab.case_id, 100 * lab.solids_fraction, lab.lab_path,
                                 lab.case_id));
  const double d = median_diameter(r);
  if (std::isfinite(lab.d_min) && std::isfinite(lab.d_max) && std::isfinite(d) &&
      (d < lab.d_min * (1 - kDiameterMargin) || d > lab.d_max * (1 + kDiameterMargin)))
    throw InputError(r.path, 0, "particle radii",
                     fmt::format("median rock diameter {:.3g} mm is outside lab case {}'s sizes {:g}-{:g} mm (in {}): "
                                 "is --lab {} the case this result simulates?",
                                 d * 1e3, lab.case_id, lab.d_min * 1e3, lab.d_max * 1e3, lab.lab_path, lab.case_id));
}

}  // namespace

void check_realizations(const LabCase& lab, const std::vector<ResultSnapshot>& results) {
  check_distinct(results);
  for (const auto& r : results) check_case(lab, r);
}

}  // namespace pastemix::analysis
