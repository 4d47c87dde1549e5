// SPDX-License-Identifier: MIT
// Collective yield resistance: touching spheres share the paste's resistance (shadowing, footing capacity).
//
// Why. The per-sphere drag (laws/bingham_dedegil.h, kicked by drag_kick.h) gives every submerged sphere its own rest resistance
// D0 = N_ball tau_y pi d^2 / 4 with N_ball ~ 15 (the full-flow factor of a ball pushed through a plastic
// medium: Dedegil's yield term plus the 24/Re' branch of Cd). That is right for an isolated sphere, but a
// pile of touching spheres then resists with the SUM over its submerged spheres: one layer of spheres
// already gives ~12 tau_y per unit of footprint and every deeper layer adds as much, so a pile can never
// push into the paste. A continuum paste under a loaded area fails at its bearing capacity instead,
// q_u = N_c tau_y with N_c = 5.14 (strip, Prandtl) to 6 (circle, square), whatever the number of layers:
// the yielded zone is shared by the whole cluster. The lab's crater under the rock cone (C = 100 % down to
// 3 cm in chapter-3 case 3) is such a failure.
//
// The rule (per fluid region with collective = "bearing_capacity"), two parts, both from the paste's plastic
// failure around bodies, neither fitted. A cluster is a connected set of submerged spheres (V_sub > 0) that
// touch (gap < kTouchGap times the smaller radius).
//  1. Shadowing. A sphere resting on a lower touching sphere does not push its own way through the paste
//     where their horizontal projections overlap: there the paste is already displaced by the lower one
//     (two spheres in line in a yield-stress fluid move inside one yielded envelope and resist little more
//     than one; Jossic & Magnin, Merkak et al.). Its rest resistance D0_a is scaled by its exposed fraction
//     e_a = 1 - (sum of the lens areas of its projection with those of the lower touching members) / (pi r_a^2),
//     clamped to [0, 1]. So only the cluster's underside resists, however many layers sit on it.
//  2. Footing. With A the cluster's footprint (area of the union of its spheres' wetted horizontal sections),
//     B the diameter of the circle of area A and D its embedment (surface minus its lowest point, >= 0),
//     the cluster moves as one body when that is the cheaper mechanism:
//       end  = min(sum_a e_a D0_a, N_c tau_y A)   N_c = 6 (1 + 0.2 D / B), at most 9 (Skempton 1951, circle or
//                                                 square footing): the underside pushes through, at most at
//                                                 the bearing capacity of a footing of that size
//       side = tau_y pi B D                       the paste sheared at tau_y along the embedded side
//                                                 (adhesion factor 1: the paste is a fluid, not a clay)
//       R_cluster = max(max_a e_a D0_a, min(sum_a D0_a, end + side))
//     The unshadowed sum is a bound because every sphere pushing its own way is always a possible mechanism.
//     Each member's rest resistance becomes e_a D0_a R_cluster / sum_b e_b D0_b (the cluster's resistance
//     carried by its exposed underside; it may exceed the sphere's own D0 when the side shear is large).
//     So a cluster never resists more than the weaker mechanism, nor less than its most exposed sphere
//     alone (a body that contains a sphere needs at least that sphere's force to move).
// An isolated sphere keeps its own law exactly. The velocity-dependent part of the drag stays per sphere.
//
// Cost: the clusters change on the time scale of the rock's motion, not of a contact, so they are computed
// every `interval` seconds of simulated time (from the pair list: one union-find pass over the pairs, and
// a scan-line union of the footprint discs), not every step. Between two updates a sphere that just entered
// the paste keeps factor 1 (its own law).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "model/particles.h"

namespace pastemix::model::fluid {

// Spheres closer than this fraction of the smaller radius share the paste between them (m/m).
inline constexpr double kTouchGap = 0.02;

// Area (m2) shared by two discs of radii r1, r2 (m) whose centres are c (m) apart.
double lens_area(double r1, double r2, double c);

// Skempton's N_c for a circular or square footing of breadth B (m) at embedment D (m).
double skempton_nc(double breadth, double embedment);

// Area (m2) of the union of horizontal discs (centres cx, cy, radii r; m), by strips of width <= h (at most
// 4000 strips): per strip each disc is the interval of its mean chord there, and the merged intervals' length
// times the width is the strip's area. Exact for one disc or discs in separate strips; discs sharing a strip
// to O(h / r) of the shared area (tested: 0.2 % for a raft of touching discs at h = r / 16).
double disc_union_area(const std::vector<double>& cx, const std::vector<double>& cy, const std::vector<double>& r,
                       double h);

struct CollectiveInput {
  const Particles* particles = nullptr;
  const std::vector<long>* members = nullptr;        // submerged particles of this region, ascending
  const std::vector<double>* rest_drag = nullptr;    // per member: D0_a, submerged fraction applied (N)
  const std::vector<std::uint32_t>* pair_i = nullptr;  // candidate pairs (dense indices; any superset of
  const std::vector<std::uint32_t>* pair_j = nullptr;  // the touching pairs)
  double surface = 0.0;                               // m, free surface of the region
  double yield_stress = 0.0;                          // Pa
};

struct ClusterStats {
  long clusters = 0;        // of two or more spheres
  long largest = 0;         // spheres in the largest cluster
  double min_factor = 1.0;  // smallest factor applied (0: a wholly shadowed sphere)
};

// factor[k] for members[k] (resized); scratch vectors kept by the caller between calls.
class CollectiveYield {
 public:
  static constexpr int kMaxParts = 64;
  ClusterStats factors(const CollectiveInput& in, std::vector<double>& factor);
  // The same in three parts, so that threads share the footprints (the costly part: strips of r_min / 16):
  // begin(in, parts) on one thread; then footprints(t) for t = 0 .. parts - 1, each on any thread (part t
  // takes the t-th share of every cluster's strips); then finish(in, factor) on one thread. The footprints'
  // lengths are summed in strip order whatever the parts, so every parts count gives the same bits.
  void begin(const CollectiveInput& in, int parts);
  void footprints(int part);
  ClusterStats finish(const CollectiveInput& in, std::vector<double>& factor);
  // After begin(): per cluster to be measured, the parts' first strips and its strip count (parts + 1 rows,
  // ascending; part t measures [cut[t], cut[t + 1])), cut at equal shares of the disc-strip crossings.
  const std::vector<long>& part_cuts() const { return cut_; }

 private:
  std::vector<long> parent_, slot_;  // union-find over members; slot_[a]: member index of particle a or -1
  std::vector<long> order_, start_;  // members grouped by cluster root
  std::vector<double> cx_, cy_, cr_;  // the wetted discs of the clusters in pending_, one run per cluster
  std::vector<double> cover_;  // per member: area shadowed by lower touching members (m2), then the exposed fraction
  // A cluster whose footprint is to be measured: its members order_[b, e), the sums of begin() (N, m) and its
  // discs [disc0, disc1) with their strips (disc_union_area's layout).
  struct Pending {
    long b = 0, e = 0;
    double sum = 0.0, sum_all = 0.0, strongest = 0.0, lowest = INFINITY, r_min = INFINITY;
    std::size_t disc0 = 0, disc1 = 0;
    double y_lo = 0.0, step = 0.0;
    long rows = 0;
  };
  std::vector<Pending> pending_;
  ClusterStats stats_;
  int parts_ = 1;
  std::array<std::vector<double>, kMaxParts> seg_;  // per part: the covered length of each strip's segments (m)
  std::vector<std::vector<std::size_t>> seg_start_;  // per part: where each pending cluster's lengths start
  std::vector<long> cut_;         // per pending cluster: the parts' first strips, parts_ + 1 rows (cut_rows)
  std::vector<long> row_scratch_;  // crossings per strip of the cluster being cut
  void cut_rows(const Pending& c);
  long find(long k);
};

}  // namespace pastemix::model::fluid
