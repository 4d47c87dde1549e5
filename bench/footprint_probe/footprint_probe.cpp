// SPDX-License-Identifier: MIT
// The footprint probe (issue 19, bench/README.md session 36): what one footprint of the collective rule costs
// (model/fluid/collective.h: disc_union_area, the strips' covered lengths of a cluster's wetted sections), on a
// pile like case 3's at rest on the paste: n discs of radius uniform in [r_min, 2 r_min], centres uniform in a
// 0.2 x 0.11 m rectangle (12,108 discs of 1.25-2.5 mm covering ~0.022 m2 about six deep, as case 3's pile at
// t = 1.5 s seen from above: 12,108 spheres over 0.0221 m2 of its 0.2 x 0.165 m box), strips r_min / 16 wide
// as the rule draws them. Prints the area to 17 digits (two builds that give the same bits print the same
// number) and the best time of each trial.
//
// Usage: pastemix_footprint_probe [--n N] [--reps R] [--trials T]   (defaults 12108 discs, 20 footprints, 3)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "model/fluid/collective.h"

int main(int argc, char** argv) {
  long n = 12108, reps = 20, trials = 3;
  if (argc % 2 == 0) {  // an option without its value
    std::fprintf(stderr, "usage: pastemix_footprint_probe [--n N] [--reps R] [--trials T]\n");
    return 2;
  }
  for (int a = 1; a + 1 < argc; a += 2) {
    const long v = std::atol(argv[a + 1]);
    if (std::strcmp(argv[a], "--n") == 0) n = v;
    else if (std::strcmp(argv[a], "--reps") == 0) reps = v;
    else if (std::strcmp(argv[a], "--trials") == 0) trials = v;
    else {
      std::fprintf(stderr, "footprint_probe: unknown option %s\n", argv[a]);
      return 2;
    }
  }
  if (n < 1 || reps < 1 || trials < 1) {
    std::fprintf(stderr, "footprint_probe: --n, --reps and --trials take positive integers\n");
    return 2;
  }
  const double r_min = 1.25e-3;  // m
  std::mt19937_64 g(20261207);
  std::uniform_real_distribution<double> ux(0.0, 0.2), uy(0.0, 0.11), ur(r_min, 2.0 * r_min);
  std::vector<double> cx(static_cast<std::size_t>(n)), cy(cx.size()), r(cx.size());
  for (std::size_t k = 0; k < cx.size(); ++k) cx[k] = ux(g), cy[k] = uy(g), r[k] = ur(g);
  double area = 0.0;
  for (long t = 0; t < trials; ++t) {
    double best = 1e300;
    for (long q = 0; q < reps; ++q) {
      const auto t0 = std::chrono::steady_clock::now();
      area = pastemix::model::fluid::disc_union_area(cx, cy, r, r_min / 16.0);
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::printf("discs %ld  area %.17g m2  best of %ld: %.3f ms per footprint\n", n, area, reps, best * 1e3);
  }
  return 0;
}
