// SPDX-License-Identifier: MIT
// Fluid regions in the engine: buoyancy with partial submergence, the region's drag law (laws/drag_law.h,
// registered in laws/registry.h) through the stable kick of drag_kick.h, and the free surface rising with the
// submerged rock volume.
//
// A region is a box (x/y extent, bottom z) of fluid at rest below a free surface. Each step the World calls
// update() once, with the positions at the end of the drift, and uses kick() instead of its plain half kick
// for the particles update() found inside a region (submerged volume > 0); every other particle takes the
// plain kick and pays nothing else. Without [[fluid]] in the scene no FluidField exists at all.
//
// Forces on a particle in region k (SI):
//   buoyancy  -rho_f V_sub g               (V_sub: spherical cap below the surface minus the part below the
//                                           bottom; with partial_submergence = false the thesis's rule: the
//                                           full volume once the centre is below the surface, else none)
//   drag      phi D(|v|) opposing v        (D: the region's drag law with its curve; phi = V_sub / V scales
//                                           the whole drag, yield term included, by the submerged fraction)
// The drag enters through drag_kick_implicit (drag_kick.h, the one kernel) with F = contacts + m g + buoyancy: m dv/dt = F - phi D is
// solved as (m/phi) dv/dt = F/phi - D, the same kernel with a scaled mass and force. The half kick of the
// Verlet step is thus stable for any dt, and the yield term cannot reverse the velocity (stick, no chatter).
// A linear law without a rest part (laws' linear_slope: Newtonian with the Stokes curve) takes that kernel's
// closed form instead (drag_kick.h linear_kick: what its iterations converge to, ~1e-13 m/s from them), with
// its two factors kept per sphere, so its kick is three multiply-adds per component (issue 19).
// A law with an affine branch (laws' affine_part: Bingham on the Stokes or the published curve, whose
// Cd = 24/Re' makes D = D(0+) + 3 pi eta_B d s below the speed where Re' = 1) takes the closed form of that
// kernel there (drag_kick.h affine_kick: its factors kept per sphere, no iteration, no exp), and the
// iterations above it; the two agree within 1e-12 m/s + 1e-11 |v| (tests/model/fluid/drag_kick_test.cpp).
// No fluid torque is applied (the spin is untouched by the fluid: a stated simplification).
// With collective = "bearing_capacity" the rest part D(0+) of a sphere in a cluster of touching submerged
// spheres is multiplied by its cluster factor (collective.h: shadowing, footing capacity), recomputed every
// collective_interval of simulated time in update(); the speed-dependent part stays the sphere's own.
//
// Cost outside the regions: with a candidate margin (World sets twice its Verlet skin), update() visits only
// the candidates: particles whose sphere came within the margin of a region's box (bottom to surface) at the
// last refresh. The World marks the list stale at each pair-list rebuild, i.e. before any particle has moved
// more than half the margin, and update() refreshes it itself when a surface has risen by more than half the margin,
// so no particle can enter a region unseen. A particle far from every region then costs one flag read per
// step (in the kick). Margin 0 (the default, for direct users of FluidField): every particle every step.
//
// Surface rise: z_s = z_s0 + (sum of V_sub of the particles in the region) / (box area), recomputed every
// step from the V_sub of that step, which itself used the previous step's surface (a one-step lag: the
// surface moves by far less than a radius per step). z_s0 is the height of the fluid without any rock.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "base/drag_curves.h"
#include "model/fluid/buoyancy.h"
#include "model/fluid/collective.h"
#include "model/fluid/drag_kick.h"
#include "model/laws/registry.h"
#include "model/particles.h"
#include "model/simd_avx2.h"
#include "model/simd_vec3.h"

namespace pastemix::model {
struct CheckpointAccess;
}

namespace pastemix::model::fluid {

struct FluidRegion {
  std::string name;
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;  // m, horizontal extent of the box
  double z_bottom = 0;                                // m, bottom of the box
  double z_surface0 = 0;                              // m, free surface without rock
  DragParams law;                                     // the drag law (its scene name: rheology) and values
  drag::DragCurve curve;                              // Cd(Re') by name
  double solids_fraction = 0.0;                       // -, mass fraction of solids (for the analysis maps)
  bool buoyancy = true, yield_term = true, partial_submergence = true, surface_rise = true;
  // Collective yield resistance of touching spheres (collective.h): off unless the scene asks for it.
  bool collective = false;
  double collective_interval = 5e-4;  // s of simulated time between two cluster updates
  // dynamics = "flow" (fluid_scene.h): the paste solved by the flow solver, coupled both ways with the
  // particles (fluid/flow_coupling.h); the keys below are read only then. The FluidField never sees such a
  // region.
  bool flow = false;
  double flow_cell = 0.0;         // m, the cells' size: `cell`, or the geometric mean of the sizes from `cells`
  std::array<int, 3> flow_cells{};  // cells along x, y, z tiling the region from bottom to flow_top
  double flow_top = 0.0;          // m, top of the flow box (air above the surface; an open side)
  double kernel_width = 2.0;      // -, c of the particles' kernels (model/coupling/kernel.h)
  long coupling_interval = 1;     // DEM steps per coupling cycle (one flow interval)
  double regularisation = 0.0;    // s, Papanastasiou's m of a yield-stress paste in the flow (model/flow/bingham.h)
  double flow_time_step = 0.0;    // s, the flow's largest sub-step within a cycle (0: the solver's default)
  bool implicit_stick = false;    // a yield-held particle follows the paste in the flow step (coupled_flow.h)

  double area() const { return (x_max - x_min) * (y_max - y_min); }
  double density() const { return std::visit([](const auto& p) { return p.density; }, law); }  // kg/m3
  double yield_stress() const { return std::visit([](const auto& p) { return p.yield_stress; }, law); }  // Pa
  std::string law_name() const {
    return std::visit([](const auto& p) { return std::string(std::decay_t<decltype(p)>::Law::name); }, law);
  }
  bool contains_xy(double x, double y) const { return x >= x_min && x <= x_max && y >= y_min && y <= y_max; }
};

class FluidField {
 public:
  explicit FluidField(std::vector<FluidRegion> regions);

  // Region membership and submerged volumes at the current positions; then the surfaces rise. With a
  // collective region, also its clusters every collective_interval: they need the candidate pairs (dense
  // indices, any superset of the touching pairs: the World's pair list). One call is one whole step.
  void update(const Particles& p, const std::vector<std::uint32_t>* pair_i = nullptr,
              const std::vector<std::uint32_t>* pair_j = nullptr);
  // The same step shared by a team of `threads` (the World's fluid pass, forces/fluid_forces.h), each thread
  // over its own particles, with no serial part on most steps:
  //   begin_batch(p, threads, partition)  one thread, before the team runs (partition: a stamp that changes
  //                                       whenever the particles' owners may have: PairList::partitions);
  //   update_part(p, t, own)              each step, every thread t: own = its particles, ascending (null: all);
  //   if cluster_due(t): a barrier, then one thread step_clusters(p, pair_i, pair_j, threads); if that left
  //                      clusters_pending(): every thread footprints(t), a barrier, one thread finish_clusters(p);
  //   end_batch()                         one thread, after the team.
  // Each thread keeps its own candidates, members and copy of the surfaces (Lane). A step's surface rise is
  // summed over every thread's members in ascending particle order, the one-thread order, by each thread at
  // the start of its next update_part (or by step_clusters / end_batch), from double-buffered lists: so the
  // bits are those of update() for any thread count, and a step needs no barrier of its own.
  void begin_batch(const Particles& p, int threads, long partition);
  void update_part(const Particles& p, int thread, const std::vector<std::uint32_t>* own);
  bool cluster_due(int thread) const { return lanes_[static_cast<std::size_t>(thread)].cluster_due; }
  void step_clusters(const Particles& p, const std::vector<std::uint32_t>* pair_i,
                     const std::vector<std::uint32_t>* pair_j, int threads);
  void end_batch();
  bool clusters_pending() const { return pending_region_ >= 0; }
  void footprints(int thread) { collective_.footprints(thread); }
  void finish_clusters(const Particles& p);
  // The step (s) and gravity (m/s2) of the World: set before the first update() when a region is collective.
  void set_step(double dt, const Vec3& g) {
    if (dt != dt_ || g.x != g_.x || g.y != g_.y || g.z != g_.z) rest_region_.assign(rest_region_.size(), -1);  // kept for the old ones
    dt_ = dt, g_ = g;
  }
  // Candidate list (see above): margin in m (the Verlet skin); stale at every pair-list rebuild.
  void set_candidate_margin(double margin) { margin_ = margin, stale_ = true, lanes_.clear(), partition_ = kNoLanes; }
  // The pair list was rebuilt (World): also invalidates the clusters kept while nothing moved.
  void mark_stale() {
    stale_ = true, ++pairs_version_;
    for (Lane& lane : lanes_) lane.stale = true;
  }
  // Particles were removed (World, on_exit = "remove"): every per-particle flag and list is anew at the
  // next update() (region_of_ no longer matches the particle count), the candidates refreshed.
  void particles_removed() {
    region_of_.clear(), v_sub_.clear(), members_.clear(), candidates_.clear(), stale_ = true;
    lanes_.clear(), partition_ = kNoLanes;
    factor_.clear(), factored_.clear();  // indices changed: the clusters are recomputed at the next update
    phi_.clear(), y_.clear(), d0_.clear(), rest_region_.clear(), clustered_members_.clear();
    lin_k_.clear(), lin_decay_.clear(), lin_gain_.clear();
    aff_k_.clear(), aff_limit2_.clear(), aff_decay_.clear(), aff_gain_.clear(), aff_fgain_.clear();
  }
  // A checkpoint was restored (model/checkpoint.cpp keeps what the kick needs but not the affine factors,
  // which follow from it): they are made anew for the particles inside a region, the same values.
  void restored(const Particles& p);
  // The World permuted the particles (its spatial sort at a pair-list rebuild; map: old -> new dense index, a
  // permutation): every per-particle array moves with its particle and the index lists are renamed and kept
  // ascending, so each particle keeps its region, its constants and its cluster factor (the same kicks as
  // without the sort; only sums over particles, such as the surface rise, see another order).
  void particles_moved(const std::vector<std::uint32_t>& map);
  std::size_t candidate_count() const {
    if (!(margin_ > 0.0)) return region_of_.size();
    std::size_t c = 0;
    for (const Lane& lane : lanes_) c += lane.candidates.size();
    return c;
  }
  // New velocity after a kick of length h (s) of particle a under the non-drag force F (N, gravity
  // included, buoyancy not: added here); g is the gravity vector (m/s2). mass and radius are particle a's
  // (those of the Particles update() saw: the per-sphere constants were kept for them).
  Vec3 kick(long a, const Vec3& v, const Vec3& F, double mass, double radius, double h, const Vec3& g) const {
    const std::size_t i = static_cast<std::size_t>(a);
    // A linear law at the World's half step and gravity (the usual case): its kept factors, inline here
    // (buoyancy as kick_general writes it); anything else the general kick.
    if (lin_k_[i] > 0.0 && h == 0.5 * dt_ && g.x == g_.x && g.y == g_.y && g.z == g_.z) {
      const double rho_b = buoyant_density_[static_cast<std::size_t>(region_of_[i])];  // 0: buoyancy off
      const Vec3 force = rho_b > 0.0 ? F - g * (rho_b * v_sub_[i]) : F;
      return v * lin_decay_[i] + force * lin_gain_[i];
    }
    // A law on its affine branch (Bingham on the Stokes / published curve's Cd = 24/Re'), the usual case in a
    // paste: its kept factors (drag_kick.h affine_kick), the general kick where the speed leaves the branch.
    if (aff_k_[i] > 0.0 && h == 0.5 * dt_ && g.x == g_.x && g.y == g_.y && g.z == g_.z) {
      const double rho_b = buoyant_density_[static_cast<std::size_t>(region_of_[i])];
      const Vec3 force = rho_b > 0.0 ? F - g * (rho_b * v_sub_[i]) : F;
      const LinearKick c{aff_decay_[i], aff_gain_[i]};
      Vec out;
      if (affine_kick(c, aff_fgain_[i], d0_[i] * yield_factor(a), aff_limit2_[i], Vec{v.x, v.y, v.z},
                      Vec{force.x, force.y, force.z}, out))
        return {out[0], out[1], out[2]};
    }
    return kick_general(a, v, F, mass, radius, h, g);
  }

  // The checks before a kick of W lanes (kick8_* / kick4_*): the step's half kick and gravity, every lane
  // inside and on the linear (affine = false) or the affine branch; then per lane rho_b V_sub, the buoyant
  // lanes and (affine) the rest resistance held. False: a lane is not for this form.
  template <int W>
  bool lanes_ready(std::size_t i0, const Vec3& g, double h, bool affine, double* rho_vsub, double* held,
                   unsigned& buoyant) const {
    if (!(h == 0.5 * dt_ && g.x == g_.x && g.y == g_.y && g.z == g_.z)) return false;
    buoyant = 0;
    for (std::size_t l = 0; l < W; ++l) {
      const std::size_t i = i0 + l;
      const bool mine = affine ? !(lin_k_[i] > 0.0) && aff_k_[i] > 0.0 : lin_k_[i] > 0.0;
      if (!(region_of_[i] >= 0 && mine)) return false;
      const double rho_b = buoyant_density_[static_cast<std::size_t>(region_of_[i])];  // 0: buoyancy off
      rho_vsub[l] = rho_b * v_sub_[i];
      if (rho_b > 0.0) buoyant |= 1u << l;
      if (affine) held[l] = d0_[i] * yield_factor(static_cast<long>(i));
    }
    return true;
  }

#if defined(__AVX512F__)
  // Particles a0 .. a0 + 7's two half kicks (the closing one of a step and the opening one of the next, the
  // same force) where all eight are inside and on the inline linear branch of kick(): v += (v decay + force
  // gain) twice, eight at a time (the blocked kick, model/kick_block.h), the bits kick() gives each. False,
  // nothing changed, otherwise.
  bool kick8_linear(long a0, Particles& p, const Vec3& g, double h) const {
    const std::size_t i0 = static_cast<std::size_t>(a0);
    alignas(64) double rho_vsub[8];
    unsigned buoyant = 0;  // lanes with buoyancy on
    if (!lanes_ready<8>(i0, g, h, false, rho_vsub, nullptr, buoyant)) return false;
    using namespace simd;
    const Aos8 force = total_force8(p, a0, g, rho_vsub, buoyant);
    const Aos8 decay = spread(_mm512_loadu_pd(&lin_decay_[i0])), gain = spread(_mm512_loadu_pd(&lin_gain_[i0]));
    const auto once = [](__m512d v, __m512d d, __m512d fo, __m512d ga) {
      return _mm512_add_pd(_mm512_mul_pd(v, d), _mm512_mul_pd(fo, ga));
    };
    Aos8 v = load_aos8(&p.v[a0]);
    for (int k = 0; k < 2; ++k)
      v = {once(v.f0, decay.f0, force.f0, gain.f0), once(v.f1, decay.f1, force.f1, gain.f1),
           once(v.f2, decay.f2, force.f2, gain.f2)};
    store_aos8(&p.v[a0], v);
    return true;
  }
#endif

#if defined(__AVX512F__)
  // The same for eight particles inside and on the affine branch (a Bingham paste on its viscous branch,
  // drag_kick.h affine_kick, the usual case in a paste): both half kicks, each v decay + F f_gain then the rest
  // resistance removed along the motion, in lanes; false, nothing changed, where a lane is on another branch
  // or leaves the affine one (its speed reaches s_max): kick() then takes it one particle at a time.
  bool kick8_affine(long a0, Particles& p, const Vec3& g, double h) const {
    const std::size_t i0 = static_cast<std::size_t>(a0);
    alignas(64) double rho_vsub[8], held[8];
    unsigned buoyant = 0;
    if (!lanes_ready<8>(i0, g, h, true, rho_vsub, held, buoyant)) return false;
    using namespace simd;
    const Soa8 F = to_soa(total_force8(p, a0, g, rho_vsub, buoyant));
    const __m512d decay = _mm512_loadu_pd(&aff_decay_[i0]), fgain = _mm512_loadu_pd(&aff_fgain_[i0]);
    const __m512d limit2 = _mm512_loadu_pd(&aff_limit2_[i0]);
    const __m512d removable = _mm512_mul_pd(_mm512_load_pd(held), _mm512_loadu_pd(&aff_gain_[i0]));
    const auto norm2 = [](__m512d x, __m512d y, __m512d z) {
      return _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(x, x), _mm512_mul_pd(y, y)), _mm512_mul_pd(z, z));
    };
    Soa8 v = to_soa(load_aos8(&p.v[a0]));
    for (int k = 0; k < 2; ++k) {
      if (_mm512_cmp_pd_mask(norm2(v.x, v.y, v.z), limit2, _CMP_LT_OQ) != 0xff) return false;
      const Soa8 o{_mm512_add_pd(_mm512_mul_pd(v.x, decay), _mm512_mul_pd(F.x, fgain)),
                   _mm512_add_pd(_mm512_mul_pd(v.y, decay), _mm512_mul_pd(F.y, fgain)),
                   _mm512_add_pd(_mm512_mul_pd(v.z, decay), _mm512_mul_pd(F.z, fgain))};
      const __m512d speed2 = norm2(o.x, o.y, o.z);
      if (_mm512_cmp_pd_mask(speed2, limit2, _CMP_LT_OQ) != 0xff) return false;
      // remove_rest: stop where speed <= removable, else scale by (speed - removable) / speed.
      const __m512d speed = _mm512_maskz_sqrt_pd(0xff, speed2);  // (the masked form: GCC 12 warns of the plain one)
      const __mmask8 moving = _mm512_cmp_pd_mask(speed, removable, _CMP_NLE_UQ);
      const __m512d scale = _mm512_div_pd(_mm512_sub_pd(speed, removable), speed);
      v = {_mm512_maskz_mul_pd(moving, o.x, scale), _mm512_maskz_mul_pd(moving, o.y, scale),
           _mm512_maskz_mul_pd(moving, o.z, scale)};
    }
    store_aos8(&p.v[a0], to_aos(v));
    return true;
  }
#elif defined(PASTEMIX_AVX2_LANES)
  // kick8_linear and kick8_affine with four lanes (AVX2 alone, model/simd_avx2.h): the same operations.
  bool kick4_linear(long a0, Particles& p, const Vec3& g, double h) const {
    const std::size_t i0 = static_cast<std::size_t>(a0);
    alignas(32) double rho_vsub[4];
    unsigned buoyant = 0;
    if (!lanes_ready<4>(i0, g, h, false, rho_vsub, nullptr, buoyant)) return false;
    using namespace avx2;
    const Aos4 force = total_force4(p, a0, g, rho_vsub, buoyant);
    const Aos4 decay = spread(_mm256_loadu_pd(&lin_decay_[i0])), gain = spread(_mm256_loadu_pd(&lin_gain_[i0]));
    const auto once = [](__m256d v, __m256d d, __m256d fo, __m256d ga) {
      return _mm256_add_pd(_mm256_mul_pd(v, d), _mm256_mul_pd(fo, ga));
    };
    Aos4 v = load_aos4(&p.v[a0].x);
    for (int k = 0; k < 2; ++k)
      v = {once(v.f0, decay.f0, force.f0, gain.f0), once(v.f1, decay.f1, force.f1, gain.f1),
           once(v.f2, decay.f2, force.f2, gain.f2)};
    store_aos4(&p.v[a0].x, v);
    return true;
  }
  bool kick4_affine(long a0, Particles& p, const Vec3& g, double h) const {
    const std::size_t i0 = static_cast<std::size_t>(a0);
    alignas(32) double rho_vsub[4], held[4];
    unsigned buoyant = 0;
    if (!lanes_ready<4>(i0, g, h, true, rho_vsub, held, buoyant)) return false;
    using namespace avx2;
    const Soa4 F = to_soa(total_force4(p, a0, g, rho_vsub, buoyant));
    const __m256d decay = _mm256_loadu_pd(&aff_decay_[i0]), fgain = _mm256_loadu_pd(&aff_fgain_[i0]);
    const __m256d limit2 = _mm256_loadu_pd(&aff_limit2_[i0]);
    const __m256d removable = _mm256_mul_pd(_mm256_load_pd(held), _mm256_loadu_pd(&aff_gain_[i0]));
    const auto below = [&](__m256d s2) { return _mm256_movemask_pd(_mm256_cmp_pd(s2, limit2, _CMP_LT_OQ)) == 0xf; };
    Soa4 v = to_soa(load_aos4(&p.v[a0].x));
    for (int k = 0; k < 2; ++k) {
      if (!below(avx2::norm2(v.x, v.y, v.z))) return false;
      const Soa4 o{_mm256_add_pd(_mm256_mul_pd(v.x, decay), _mm256_mul_pd(F.x, fgain)),
                   _mm256_add_pd(_mm256_mul_pd(v.y, decay), _mm256_mul_pd(F.y, fgain)),
                   _mm256_add_pd(_mm256_mul_pd(v.z, decay), _mm256_mul_pd(F.z, fgain))};
      const __m256d speed2 = avx2::norm2(o.x, o.y, o.z);
      if (!below(speed2)) return false;
      // remove_rest: +0 where speed <= removable, else scaled by (speed - removable) / speed.
      const __m256d speed = _mm256_sqrt_pd(speed2);
      const __m256d moving = _mm256_cmp_pd(speed, removable, _CMP_NLE_UQ);
      const __m256d scale = _mm256_div_pd(_mm256_sub_pd(speed, removable), speed);
      v = {_mm256_and_pd(moving, _mm256_mul_pd(o.x, scale)), _mm256_and_pd(moving, _mm256_mul_pd(o.y, scale)),
           _mm256_and_pd(moving, _mm256_mul_pd(o.z, scale))};
    }
    store_aos4(&p.v[a0].x, to_aos(v));
    return true;
  }
#endif

  bool inside(long a) const { return region_of_[a] >= 0; }
  // inside(a), false where the field has no flags for a yet (before the first update, after a removal).
  bool known_inside(long a) const {
    return static_cast<std::size_t>(a) < region_of_.size() && region_of_[static_cast<std::size_t>(a)] >= 0;
  }
  // The particles inside a region at the last update() or end_batch(), ascending.
  const std::vector<long>& members() const { return members_; }
  // Thread t's particles inside a region at its last update_part, ascending (the World's fluid pass).
  const std::vector<long>& members(int thread) const {
    const Lane& lane = lanes_[static_cast<std::size_t>(thread)];
    return lane.members[static_cast<std::size_t>(lane.par)];
  }
  int region_of(long a) const { return region_of_[a]; }
  double submerged_volume(long a) const { return v_sub_[a]; }
  const std::vector<FluidRegion>& regions() const { return regions_; }
  double surface_z(std::size_t k) const { return surface_[k]; }
  const std::vector<double>& surfaces() const { return surface_; }
  // Factor on particle a's rest resistance from its cluster (1: its own law).
  double yield_factor(long a) const { return factor_.empty() ? 1.0 : factor_[static_cast<std::size_t>(a)]; }
  // The clusters of the last update, summed over the regions.
  const ClusterStats& cluster_stats() const { return stats_; }

 private:
  friend struct pastemix::model::CheckpointAccess;  // model/checkpoint.cpp: saves and restores the state
  std::vector<FluidRegion> regions_;
  std::vector<double> surface_;  // m, current free surface per region
  std::vector<int> region_of_;   // per particle, -1 outside every region
  std::vector<double> v_sub_;    // m3, per particle
  double margin_ = 0.0;                     // m; 0: no candidate list
  bool stale_ = true;
  // At the end of a batch (end_batch), what the threads' lanes hold, merged: ascending particle indices
  // (the checkpoint keeps them; a restored run makes its lanes anew from members_).
  std::vector<long> candidates_, members_;
  std::vector<double> surface_at_refresh_;  // m, per region
  // One thread's share of the step (update() uses lane 0 for every particle).
  struct Wet {
    double volume;  // m3, V_sub of the member
    int region;
  };
  struct alignas(64) Lane {
    std::vector<long> candidates;              // the thread's particles within the margin, ascending
    std::array<std::vector<long>, 2> members;  // ascending; [par]: those of the last update_part
    std::array<std::vector<Wet>, 2> wet;       // per member: its wetted volume and region
    // Per region, the members' wetted volumes summed in the members' order while they were found (m3): with
    // one lane, that is rise()'s ascending sum itself.
    std::array<std::vector<double>, 2> wet_sum;
    int par = 0;
    bool stale = true, refreshed = false, pending = false, cluster_due = false;  // pending: rise not summed
    bool visited = false;  // its candidates were visited since the lane was made (their flags are set)
    long since = 0;                            // steps since the last cluster update (since_clusters_)
    std::vector<double> surface, surface_at_refresh;  // m, the thread's copy (the same bits in every lane)
    std::vector<long> changed;                 // scratch of update_part: its members whose phi may have changed
    std::vector<double> sum;                   // m3 per region, scratch of rise()
    std::vector<std::size_t> head;             // scratch of the merges
  };
  static constexpr long kNoLanes = -2;
  std::vector<Lane> lanes_;
  long partition_ = kNoLanes;  // the stamp begin_batch() made the lanes for
  void refresh(const Particles& p, Lane& lane, const std::vector<std::uint32_t>* own) const;
  // update_part's visits with one region: the particles id(q), q < visits, into the lane's [par] lists
  // (field.cpp). Returns the members found.
  template <class Id>
  std::size_t visit_one_region(const Particles& p, Lane& lane, std::size_t visits, Id&& id);
  // A visited particle found wetted: its flags, its member and wet entries (field.cpp).
  void wetted(Lane& lane, std::size_t a, double vs, int region, long& member, Wet& wet);
  // The surfaces after the step whose members are in every lane's [par] (sums in ascending particle order).
  void rise(int par, Lane& scratch, std::vector<double>& surface) const;
  // Calls f(lane, q) for every lane's entry q of list(lane), in ascending particle order.
  template <class List, class F>
  void merged(List&& list, std::vector<std::size_t>& head, F&& f) const;
  // Whether every lane's list(lane) lies below the next non-empty lane's (the World's slabs after its sort).
  template <class List>
  bool in_order(List&& list) const;
  void gather_members();  // members_ from the lanes' last members
  // Per particle, what the kick needs and update() already knows (the kick's own expressions, so the same
  // bits): the submerged fraction phi of this step, and, while the particle stays in region rest_region_,
  // its yield number and rest drag D(0+) (both constant for a sphere in one fluid; gravity g_).
  std::vector<double> phi_, y_, d0_;
  std::vector<int> rest_region_;
  // A linear law (D = k s, no rest part: laws' linear_slope) has a closed-form kick (drag_kick.h): its slope
  // k (N s/m, 0 for any other law) and, for this step's phi and the World's half step dt_/2, its factors
  // (v' = v decay + F gain: decay -, gain s/kg, the 1/phi folded in).
  std::vector<double> lin_k_, lin_decay_, lin_gain_;
  void keep_sphere(const Particles& p, std::size_t a, int region) {
    const double r = p.radius[a];
    const double phi = std::min(1.0, v_sub_[a] / (4.0 / 3.0 * kPi * r * r * r));
    // A sphere under the surface keeps its phi to the bit (the same expressions of the same r): its
    // constants are made once per stay in a region; one at the surface gets its linear factors each step.
    const bool moved = phi != phi_[a];
    phi_[a] = phi;
    if (rest_region_[a] != region || (moved && (lin_k_[a] > 0.0 || aff_k_[a] > 0.0))) enter(p, a, region);
  }
  // A law with an affine branch (laws' affine_part, D = D(0+) + k s below s_max): k (N s/m, 0: none), s_max^2
  // less a margin (m2/s2), and for this step's phi and the half step dt_/2 the kick's factors (drag_kick.h
  // affine_kick: decay -, gain s/kg, f_gain = gain / phi s/kg). Not in the checkpoint: restored() remakes them.
  std::vector<double> aff_k_, aff_limit2_, aff_decay_, aff_gain_, aff_fgain_;
  void enter(const Particles& p, std::size_t a, int region);  // the constants of keep_sphere
  void keep_affine(const Particles& p, std::size_t a, int region, bool new_region);  // enter()'s aff_ part
  std::vector<double> buoyant_density_;  // kg/m3 per region, 0 where buoyancy is off (the inline kick)
  Vec3 kick_general(long a, const Vec3& v, const Vec3& F, double mass, double radius, double h, const Vec3& g) const;
#if defined(__AVX512F__)
  // The kick's force of particles a0 .. a0 + 7 (model/simd_vec3.h layout): F = f + g m, less g rho_b V_sub
  // where buoyancy is on (lane l of `buoyant`; rho_vsub[l] = rho_b V_sub), as kick() forms it.
  static simd::Aos8 total_force8(const Particles& p, long a0, const Vec3& g, const double* rho_vsub, unsigned buoyant) {
    using namespace simd;
    const Aos8 m = spread(_mm512_loadu_pd(&p.mass[a0])), f = load_aos8(&p.f[a0]), G = repeat(g);
    Aos8 force{_mm512_add_pd(f.f0, _mm512_mul_pd(G.f0, m.f0)), _mm512_add_pd(f.f1, _mm512_mul_pd(G.f1, m.f1)),
               _mm512_add_pd(f.f2, _mm512_mul_pd(G.f2, m.f2))};
    if (buoyant == 0) return force;
    const Aos8 rv = spread(_mm512_loadu_pd(rho_vsub));
    // The particles' lanes in the three registers' layout (particle l owns components 3l .. 3l + 2).
    __mmask8 on[3] = {0xff, 0xff, 0xff};  // all eight (the usual case: one region, buoyancy on)
    if (buoyant != 0xffu) {
      on[0] = on[1] = on[2] = 0;
      for (int c = 0; c < 24; ++c)
        if ((buoyant >> (c / 3)) & 1u) on[c / 8] = static_cast<__mmask8>(on[c / 8] | (1u << (c % 8)));
    }
    force.f0 = _mm512_mask_sub_pd(force.f0, on[0], force.f0, _mm512_mul_pd(G.f0, rv.f0));
    force.f1 = _mm512_mask_sub_pd(force.f1, on[1], force.f1, _mm512_mul_pd(G.f1, rv.f1));
    force.f2 = _mm512_mask_sub_pd(force.f2, on[2], force.f2, _mm512_mul_pd(G.f2, rv.f2));
    return force;
  }
#elif defined(PASTEMIX_AVX2_LANES)
  static avx2::Aos4 total_force4(const Particles& p, long a0, const Vec3& g, const double* rho_vsub, unsigned buoyant) {
    using namespace avx2;
    const Aos4 m = spread(_mm256_loadu_pd(&p.mass[a0])), f = load_aos4(&p.f[a0].x), G = repeat(g.x, g.y, g.z);
    Aos4 force{_mm256_add_pd(f.f0, _mm256_mul_pd(G.f0, m.f0)), _mm256_add_pd(f.f1, _mm256_mul_pd(G.f1, m.f1)),
               _mm256_add_pd(f.f2, _mm256_mul_pd(G.f2, m.f2))};
    if (buoyant == 0) return force;
    const Aos4 rv = spread(_mm256_loadu_pd(rho_vsub));
    const Aos4 less{_mm256_sub_pd(force.f0, _mm256_mul_pd(G.f0, rv.f0)), _mm256_sub_pd(force.f1, _mm256_mul_pd(G.f1, rv.f1)),
                    _mm256_sub_pd(force.f2, _mm256_mul_pd(G.f2, rv.f2))};
    if (buoyant == 0xfu) return less;
    // Component c of the twelve (register c / 4, lane c % 4) belongs to particle c / 3.
    alignas(32) std::int64_t on[12];
    for (int c = 0; c < 12; ++c) on[c] = ((buoyant >> (c / 3)) & 1u) ? -1 : 0;
    const auto pick = [&](int r, __m256d keep, __m256d sub) {
      return _mm256_blendv_pd(keep, sub, _mm256_castsi256_pd(_mm256_load_si256(reinterpret_cast<const __m256i*>(on + 4 * r))));
    };
    return {pick(0, force.f0, less.f0), pick(1, force.f1, less.f1), pick(2, force.f2, less.f2)};
  }
#endif
  // Clusters are recomputed only when their input changed: the members, their positions, the surfaces or
  // the pair list (a bed at rest in the paste keeps its clusters, to the bit: the same input, the same
  // factors).
  long pairs_version_ = 0, clustered_version_ = -1;
  std::vector<long> clustered_members_;
  std::vector<Vec3> clustered_x_;
  std::vector<double> clustered_surface_;
  bool clusters_unchanged(const Particles& p) const;
  // Collective yield (collective.h): per-particle factor (empty while no region is collective), the
  // particles it was last set for, steps since the last cluster update.
  double dt_ = 0.0;
  Vec3 g_{0, 0, -9.81};
  double cluster_interval_ = INFINITY;  // s: the smallest collective_interval of the regions (inf: none)
  std::vector<double> factor_;
  std::vector<long> factored_;
  long since_clusters_ = 0;
  ClusterStats stats_;
  CollectiveYield collective_;
  std::vector<long> region_members_;
  std::vector<double> region_d0_, region_factor_;
  void update_clusters(const Particles& p, const std::vector<std::uint32_t>* pair_i,
                       const std::vector<std::uint32_t>* pair_j, int threads);
  // The cluster update of region k: its members and their phi D(0+) into region_members_ / region_d0_.
  CollectiveInput region_input(const Particles& p, std::size_t k, const std::vector<std::uint32_t>* pair_i,
                               const std::vector<std::uint32_t>* pair_j);
  void apply_factors(const ClusterStats& s);  // region_factor_ onto factor_, the stats summed
  void clustered(const Particles& p);         // what clusters_unchanged() compares next time
  int pending_region_ = -1;                   // the region whose footprints are being measured, -1: none
  const std::vector<std::uint32_t>* pending_pi_ = nullptr;
  const std::vector<std::uint32_t>* pending_pj_ = nullptr;
};

}  // namespace pastemix::model::fluid
