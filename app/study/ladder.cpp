// SPDX-License-Identifier: MIT
#include "app/study/ladder.h"

#include <cmath>

#include <fmt/format.h>

namespace pastemix::app::study {
namespace {

double standard_error(const LadderPoint& a) { return a.seeds > 1 ? a.qoi_sd / std::sqrt(a.seeds) : 0.0; }

}  // namespace

Reference reference_of(const std::vector<LadderPoint>& pts, double ratio) {
  Reference ref;
  if (pts.empty()) return ref;
  const LadderPoint& f = pts.back();
  ref.qoi = f.qoi;
  if (ratio <= 1.0) {
    ref.method = "finest run (ladder is not a geometric refinement)";
    return ref;
  }
  if (pts.size() < 3) {
    ref.method = "finest run (fewer than 3 points)";
    return ref;
  }
  const LadderPoint &q1 = pts[pts.size() - 1], &q2 = pts[pts.size() - 2], &q3 = pts[pts.size() - 3];
  const double d21 = q2.qoi - q1.qoi, d32 = q3.qoi - q2.qoi;
  const double se21 = std::hypot(standard_error(q1), standard_error(q2));
  const double se32 = std::hypot(standard_error(q2), standard_error(q3));
  if (std::abs(d21) <= 2 * se21 || std::abs(d32) <= 2 * se32 || d21 == 0.0) {
    ref.method = "finest run (differences within the seed spread or zero)";
    return ref;
  }
  if (d21 * d32 <= 0.0 || std::abs(d32) <= std::abs(d21)) {
    ref.method = "finest run (not monotonically converging)";
    return ref;
  }
  const double p = std::log(std::abs(d32) / std::abs(d21)) / std::log(ratio);
  if (!(p >= 0.5 && p <= 8.0)) {
    ref.method = fmt::format("finest run (observed order {:.2f} out of [0.5, 8])", p);
    return ref;
  }
  ref.order = p;
  ref.qoi = q1.qoi - d21 / (std::pow(ratio, p) - 1.0);
  ref.method = fmt::format("Richardson (p = {:.2f}, r = {:g})", p, ratio);
  return ref;
}

Choice choose(const std::vector<LadderPoint>& pts, const Reference& ref, double tol) {
  Choice c;
  bool by_work = true;
  for (const auto& p : pts) by_work = by_work && p.work > 0;
  auto cost = [&](std::size_t k) { return by_work ? pts[k].work : pts[k].wall_s; };
  const double scale = std::abs(ref.qoi) > 0 ? std::abs(ref.qoi) : 1.0;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const double d = std::abs(pts[k].qoi - ref.qoi);
    c.rel_error.push_back(d / scale);
    c.significant.push_back(pts[k].seeds <= 1 || d > 2 * standard_error(pts[k]));
    if (d / scale <= tol && (c.index < 0 || cost(k) < cost(static_cast<std::size_t>(c.index))))
      c.index = static_cast<int>(k);
  }
  return c;
}

}  // namespace pastemix::app::study
