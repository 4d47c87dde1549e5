// SPDX-License-Identifier: MIT
#include "model/fluid/field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "model/fluid/buoyancy.h"

namespace pastemix::model::fluid {

FluidField::FluidField(std::vector<FluidRegion> regions) : regions_(std::move(regions)) {
  for (const FluidRegion& r : regions_) {
    surface_.push_back(r.z_surface0);
    if (r.collective) cluster_interval_ = std::min(cluster_interval_, r.collective_interval);
    buoyant_density_.push_back(r.buoyancy ? r.density() : 0.0);
  }
}

namespace {

// Volume (m3) of a sphere of radius r at height z that lies between the bottom and the surface.
inline double wetted_volume(const FluidRegion& reg, double z, double r, double z_s, bool partial) {
  if (!partial) {
    // The thesis's rule: all or nothing, by the centre.
    return (z < z_s && z > reg.z_bottom) ? 4.0 / 3.0 * kPi * r * r * r : 0.0;
  }
  return fluid::submerged_volume(z, r, z_s) - fluid::submerged_volume(z, r, reg.z_bottom);
}

}  // namespace

void FluidField::refresh(const Particles& p, Lane& lane, const std::vector<std::uint32_t>* own) const {
  lane.candidates.clear();
  auto test = [&](long a) {
    const Vec3& x = p.x[a];
    const double reach = p.radius[a] + margin_;
    for (std::size_t k = 0; k < regions_.size(); ++k) {
      const FluidRegion& reg = regions_[k];
      if (x.x >= reg.x_min - reach && x.x <= reg.x_max + reach && x.y >= reg.y_min - reach &&
          x.y <= reg.y_max + reach && x.z >= reg.z_bottom - reach && x.z <= lane.surface[k] + reach) {
        lane.candidates.push_back(a);
        return;
      }
    }
  };
  if (own)
    for (std::uint32_t a : *own) test(static_cast<long>(a));
  else
    for (long a = 0; a < static_cast<long>(p.size()); ++a) test(a);
  lane.surface_at_refresh = lane.surface;
  lane.stale = false, lane.refreshed = true;
}

template <class List>
bool FluidField::in_order(List&& list) const {
  long last = -1;
  for (const Lane& lane : lanes_) {
    const auto& l = list(lane);
    if (l.empty()) continue;
    if (l.front() <= last) return false;
    last = l.back();
  }
  return true;
}

template <class List, class F>
void FluidField::merged(List&& list, std::vector<std::size_t>& head, F&& f) const {
  const std::size_t lanes = lanes_.size();
  // Lanes whose lists follow each other (every particle of one below every particle of the next: the
  // World's slabs after its spatial sort) are read one after the other, without comparisons.
  if (in_order(list)) {
    for (std::size_t t = 0; t < lanes; ++t) {
      const std::size_t n = list(lanes_[t]).size();
      for (std::size_t q = 0; q < n; ++q) f(lanes_[t], q);
    }
    return;
  }
  // A k-way merge of ascending lists (head: [0, lanes) next entry, [lanes, 2 lanes) length), read once per
  // lane: the lists of the other threads are not re-read in the loop.
  head.assign(2 * lanes, 0);
  for (std::size_t t = 0; t < lanes; ++t) head[lanes + t] = list(lanes_[t]).size();
  for (;;) {
    std::size_t best = lanes;
    long low = 0;
    for (std::size_t t = 0; t < lanes; ++t)
      if (head[t] < head[lanes + t]) {
        const long a = list(lanes_[t])[head[t]];
        if (best == lanes || a < low) best = t, low = a;
      }
    if (best == lanes) return;
    f(lanes_[best], head[best]++);
  }
}

void FluidField::rise(int par, Lane& scratch, std::vector<double>& surface) const {
  std::vector<double>& wet = scratch.sum;  // reused: no allocation per step
  const auto p = static_cast<std::size_t>(par);
  if (lanes_.size() == 1) {
    wet = lanes_[0].wet_sum[p];  // one lane: its members' sum is the ascending one (issue 19: ~3 % of a bed in air)
  } else if (in_order([p](const Lane& l) -> const std::vector<long>& { return l.members[p]; }) &&
             lanes_[0].wet_sum[p].size() == regions_.size()) {
    // Lanes whose members follow each other (the World's slabs after its spatial sort): the ascending sum
    // is lane 0's own sum continued over the other lanes' members in order, the same additions as below
    // (case 3's rock lies in one slab: ~95 % of the members were added again here every step, by each thread).
    wet = lanes_[0].wet_sum[p];
    for (std::size_t t = 1; t < lanes_.size(); ++t)
      for (const Wet& w : lanes_[t].wet[p]) wet[static_cast<std::size_t>(w.region)] += w.volume;
  } else {
    wet.assign(regions_.size(), 0.0);
    merged([p](const Lane& l) -> const std::vector<long>& { return l.members[p]; }, scratch.head,
           [&](const Lane& l, std::size_t q) { wet[static_cast<std::size_t>(l.wet[p][q].region)] += l.wet[p][q].volume; });
  }
  for (std::size_t k = 0; k < regions_.size(); ++k)
    if (regions_[k].surface_rise) surface[k] = regions_[k].z_surface0 + wet[k] / regions_[k].area();
}

void FluidField::gather_members() {
  members_.clear();
  const auto p = static_cast<std::size_t>(lanes_[0].par);
  merged([p](const Lane& l) -> const std::vector<long>& { return l.members[p]; }, lanes_[0].head,
         [&](const Lane& l, std::size_t q) { members_.push_back(l.members[p][q]); });
}

void FluidField::update(const Particles& p, const std::vector<std::uint32_t>* pair_i,
                        const std::vector<std::uint32_t>* pair_j) {
  begin_batch(p, 1, -1);
  update_part(p, 0, nullptr);
  if (lanes_[0].cluster_due) step_clusters(p, pair_i, pair_j, 1);
  end_batch();
}

void FluidField::begin_batch(const Particles& p, int threads, long partition) {
  const std::size_t n = p.size();
  const bool sized = region_of_.size() == n;
  const bool same_lanes = sized && partition == partition_ && lanes_.size() == static_cast<std::size_t>(threads);
  if (!sized) {  // every flag anew (the first step, or particles were removed)
    region_of_.assign(n, -1);
    v_sub_.assign(n, 0.0);
    if (rest_region_.size() != n) {
      phi_.assign(n, 0.0), y_.assign(n, 0.0), d0_.assign(n, 0.0), rest_region_.assign(n, -1);
      lin_k_.assign(n, 0.0), lin_decay_.assign(n, 1.0), lin_gain_.assign(n, 0.0);
      aff_k_.assign(n, 0.0), aff_limit2_.assign(n, 0.0), aff_decay_.assign(n, 1.0), aff_gain_.assign(n, 0.0);
      aff_fgain_.assign(n, 0.0);
    }
    members_.clear();
  } else if (!same_lanes) {
    // The owners may have changed: the last members are cleared here, where a lane would clear only its own.
    for (long a : members_) region_of_[static_cast<std::size_t>(a)] = -1, v_sub_[static_cast<std::size_t>(a)] = 0.0;
  }
  if (!same_lanes) {
    lanes_.assign(static_cast<std::size_t>(threads), Lane{});
    for (Lane& lane : lanes_) lane.surface_at_refresh = surface_;
    partition_ = partition;
  }
  if (cluster_interval_ != INFINITY && factor_.size() != n) factor_.assign(n, 1.0), factored_.clear(), since_clusters_ = 0;
  for (Lane& lane : lanes_) lane.surface = surface_, lane.since = since_clusters_, lane.pending = false;
}

// Particle a found in region `region` with wetted volume vs (m^3): its flags, and its member and wet entries. A
// sphere that stays in its region with the same wetted volume (every sphere under the surface) would get
// keep_sphere's phi to the bit and no new constants (set_step resets rest_region_ when they must be made
// anew): it is not listed in lane.changed, so keep_sphere, with its division, is skipped.
inline void FluidField::wetted(Lane& lane, std::size_t a, double vs, int region, long& member, Wet& wet) {
  const bool same = region_of_[a] == region && v_sub_[a] == vs && rest_region_[a] == region;
  region_of_[a] = region;
  v_sub_[a] = vs;
  if (!same) lane.changed.push_back(static_cast<long>(a));
  member = static_cast<long>(a);
  wet = {vs, region};
}

// One region (the usual case): visit()'s steps with the wetted volumes of a block of visits first, in a loop
// that stores nothing to the field, so that the neighbouring spheres' divisions overlap, and the region's sum
// in a register (in the array, each addition waited on the last one's store). A sphere outside the region's
// footprint gets volume 0, which visit() treats as it treats "outside": the same members, flags and sums, in
// the same order (issue 19, session 38: the "inside" variant of bench/fluid_hook.sh spent ~17 ns per
// particle-step in this pass on a Zen 3 VM; its fluid stage 0.333-0.468 -> 0.267-0.334 s, 3 interleaved pairs).
template <class Id>
std::size_t FluidField::visit_one_region(const Particles& p, Lane& lane, std::size_t visits, Id&& id) {
  std::vector<long>& members = lane.members[static_cast<std::size_t>(lane.par)];
  std::vector<Wet>& wet = lane.wet[static_cast<std::size_t>(lane.par)];
  const FluidRegion& reg = regions_[0];
  const double z_s = lane.surface[0];
  constexpr std::size_t kBlock = 64;
  std::size_t ids[kBlock];
  double vol[kBlock];
  double sum = 0.0;
  std::size_t found = 0;
  for (std::size_t b0 = 0; b0 < visits; b0 += kBlock) {
    const std::size_t nb = std::min(kBlock, visits - b0);
    for (std::size_t q = 0; q < nb; ++q) ids[q] = id(b0 + q);
    for (std::size_t q = 0; q < nb; ++q) {
      const Vec3& x = p.x[ids[q]];
      const double vs = wetted_volume(reg, x.z, p.radius[ids[q]], z_s, reg.partial_submergence);
      vol[q] = reg.contains_xy(x.x, x.y) ? vs : 0.0;
    }
    for (std::size_t q = 0; q < nb; ++q) {
      const std::size_t a = ids[q];
      const double vs = vol[q];
      if (vs <= 0.0) {
        region_of_[a] = -1, v_sub_[a] = 0.0;
        continue;
      }
      wetted(lane, a, vs, 0, members[found], wet[found]);
      ++found;
      sum += vs;
    }
  }
  lane.wet_sum[static_cast<std::size_t>(lane.par)][0] = sum;
  return found;
}

void FluidField::update_part(const Particles& p, int thread, const std::vector<std::uint32_t>* own) {
  Lane& lane = lanes_[static_cast<std::size_t>(thread)];
  if (lane.pending) rise(lane.par, lane, lane.surface);  // the last step's rise (every lane: the same bits)
  const bool listed = margin_ > 0.0;
  if (listed) {
    for (std::size_t k = 0; k < lane.surface.size() && !lane.stale; ++k)
      if (lane.surface[k] - lane.surface_at_refresh[k] > 0.5 * margin_) lane.stale = true;
    // The last members lose their flags, unless the candidates are those of the last step (no refresh
    // since): then every last member is visited below and gets its flags anew.
    const bool refreshing = lane.stale || !lane.visited;
    if (lane.stale) refresh(p, lane, own);
    if (refreshing)
      for (long a : lane.members[static_cast<std::size_t>(lane.par)])
        region_of_[static_cast<std::size_t>(a)] = -1, v_sub_[static_cast<std::size_t>(a)] = 0.0;
    lane.visited = true;
  }
  lane.par ^= 1;
  std::vector<long>& members = lane.members[static_cast<std::size_t>(lane.par)];
  std::vector<Wet>& wet = lane.wet[static_cast<std::size_t>(lane.par)];
  std::vector<double>& wet_sum = lane.wet_sum[static_cast<std::size_t>(lane.par)];
  wet_sum.assign(regions_.size(), 0.0);
  // Sized for every visited particle and cut to the members found: no capacity test per member.
  const std::size_t visits = listed ? lane.candidates.size() : own ? own->size() : p.size();
  members.resize(visits), wet.resize(visits);
  std::size_t found = 0;
  std::vector<long>& changed = lane.changed;
  changed.clear();
  auto visit = [&](std::size_t a) __attribute__((always_inline)) {
    const Vec3& x = p.x[a];
    for (std::size_t k = 0; k < regions_.size(); ++k) {
      const FluidRegion& reg = regions_[k];
      if (!reg.contains_xy(x.x, x.y)) continue;
      const double vs = wetted_volume(reg, x.z, p.radius[a], lane.surface[k], reg.partial_submergence);
      if (vs <= 0.0) continue;
      wetted(lane, a, vs, static_cast<int>(k), members[found], wet[found]);
      ++found;
      wet_sum[k] += vs;
      return;  // the first region that holds the particle owns it
    }
    region_of_[a] = -1, v_sub_[a] = 0.0;
  };
  const auto visited = [&](std::size_t q) -> std::size_t {
    return listed ? static_cast<std::size_t>(lane.candidates[q]) : own ? (*own)[q] : q;
  };
  if (regions_.size() == 1) {
    found = visit_one_region(p, lane, visits, visited);
  } else {
    for (std::size_t q = 0; q < visits; ++q) visit(visited(q));
  }
  members.resize(found), wet.resize(found);
  // The constants of the members whose wetted volume or region changed, in a loop of their own (a sphere's
  // constants depend on it alone: the same bits in any order). At the surface, where the volumes change each
  // step, this is most members (case 3: ~65 %); apart from the visits, the chains of divisions and exp of
  // neighbouring spheres overlap.
  for (long a : changed) keep_sphere(p, static_cast<std::size_t>(a), region_of_[static_cast<std::size_t>(a)]);
  lane.pending = true;
  // Collective yield: the clusters every `every` steps (the smallest interval of the collective regions).
  const long every = dt_ > 0.0 ? std::max(1L, std::lround(cluster_interval_ / dt_)) : 1L;
  lane.cluster_due = cluster_interval_ != INFINITY && lane.since % every == 0;
  ++lane.since;
}

void FluidField::step_clusters(const Particles& p, const std::vector<std::uint32_t>* pair_i,
                               const std::vector<std::uint32_t>* pair_j, int threads) {
  rise(lanes_[0].par, lanes_[0], surface_);  // this step's rise: the clusters see the risen surface
  for (Lane& lane : lanes_) lane.surface = surface_, lane.pending = false;
  gather_members();
  if (!clusters_unchanged(p)) update_clusters(p, pair_i, pair_j, threads);
}

void FluidField::end_batch() {
  if (lanes_.empty()) return;
  Lane& first = lanes_[0];
  if (first.pending) {
    rise(first.par, first, surface_);
    for (Lane& lane : lanes_) lane.surface = surface_, lane.pending = false;
  }
  gather_members();
  bool refreshed = false;
  for (Lane& lane : lanes_) refreshed |= lane.refreshed, lane.refreshed = false;
  if (refreshed) {
    candidates_.clear();
    merged([](const Lane& l) -> const std::vector<long>& { return l.candidates; }, first.head,
           [&](const Lane& l, std::size_t q) { candidates_.push_back(l.candidates[q]); });
  }
  surface_at_refresh_ = first.surface_at_refresh, stale_ = first.stale, since_clusters_ = first.since;
}

bool FluidField::clusters_unchanged(const Particles& p) const {
  if (clustered_version_ != pairs_version_ || clustered_members_ != members_ || clustered_surface_ != surface_)
    return false;
  for (std::size_t q = 0; q < members_.size(); ++q) {
    const Vec3& x = p.x[static_cast<std::size_t>(members_[q])];
    const Vec3& x0 = clustered_x_[q];
    if (x.x != x0.x || x.y != x0.y || x.z != x0.z) return false;
  }
  return true;
}

CollectiveInput FluidField::region_input(const Particles& p, std::size_t k, const std::vector<std::uint32_t>* pair_i,
                                         const std::vector<std::uint32_t>* pair_j) {
  region_members_.clear();
  region_d0_.clear();
  auto take = [&](long a) {
    const std::size_t i = static_cast<std::size_t>(a);
    if (region_of_[i] != static_cast<int>(k)) return;
    region_members_.push_back(a);
    region_d0_.push_back(phi_[i] * d0_[i]);  // phi D(0+) (keep_sphere: this region, gravity g_)
  };
  if (margin_ > 0.0)
    for (long a : members_) take(a);  // ascending (the candidates' order)
  else
    for (std::size_t a = 0; a < p.size(); ++a) take(static_cast<long>(a));
  return {&p, &region_members_, &region_d0_, pair_i, pair_j, surface_[k], regions_[k].yield_stress()};
}

void FluidField::apply_factors(const ClusterStats& s) {
  for (std::size_t q = 0; q < region_members_.size(); ++q) {
    if (region_factor_[q] == 1.0) continue;
    factor_[static_cast<std::size_t>(region_members_[q])] = region_factor_[q];
    factored_.push_back(region_members_[q]);
  }
  stats_.clusters += s.clusters;
  stats_.largest = std::max(stats_.largest, s.largest);
  stats_.min_factor = std::min(stats_.min_factor, s.min_factor);
}

void FluidField::clustered(const Particles& p) {
  clustered_version_ = pairs_version_, clustered_members_ = members_, clustered_surface_ = surface_;
  clustered_x_.resize(members_.size());
  for (std::size_t q = 0; q < members_.size(); ++q) clustered_x_[q] = p.x[static_cast<std::size_t>(members_[q])];
}

void FluidField::update_clusters(const Particles& p, const std::vector<std::uint32_t>* pair_i,
                                 const std::vector<std::uint32_t>* pair_j, int threads) {
  if (!pair_i || !pair_j) throw std::logic_error("FluidField: a collective region needs the pair list in update()");
  for (long a : factored_) factor_[static_cast<std::size_t>(a)] = 1.0;
  factored_.clear();
  stats_ = ClusterStats{};
  long collective = 0;
  for (const FluidRegion& reg : regions_) collective += reg.collective ? 1 : 0;
  for (std::size_t k = 0; k < regions_.size(); ++k) {
    if (!regions_[k].collective) continue;
    const CollectiveInput in = region_input(p, k, pair_i, pair_j);
    if (threads > 1 && collective == 1) {  // the team measures the footprints (finish_clusters() ends it)
      collective_.begin(in, threads);
      pending_region_ = static_cast<int>(k), pending_pi_ = pair_i, pending_pj_ = pair_j;
      return;
    }
    apply_factors(collective_.factors(in, region_factor_));
  }
  clustered(p);
}

void FluidField::finish_clusters(const Particles& p) {
  const std::size_t k = static_cast<std::size_t>(pending_region_);
  const CollectiveInput in{&p, &region_members_, &region_d0_, pending_pi_, pending_pj_, surface_[k],
                           regions_[k].yield_stress()};
  apply_factors(collective_.finish(in, region_factor_));
  pending_region_ = -1;
  clustered(p);
}

namespace {

// v[a] moves to map[a] (a permutation; an array not yet sized for the particles stays as it is).
template <class T>
void permute(std::vector<T>& v, const std::vector<std::uint32_t>& map) {
  if (v.size() != map.size()) return;
  std::vector<T> out(v.size());
  for (std::size_t a = 0; a < map.size(); ++a) out[map[a]] = v[a];
  v.swap(out);
}

// The indices of a list renamed through map, ascending again.
void rename(std::vector<long>& list, const std::vector<std::uint32_t>& map) {
  for (long& a : list) a = static_cast<long>(map[static_cast<std::size_t>(a)]);
  std::sort(list.begin(), list.end());
}

}  // namespace

void FluidField::particles_moved(const std::vector<std::uint32_t>& map) {
  for (auto* v : {&v_sub_, &phi_, &y_, &d0_, &lin_k_, &lin_decay_, &lin_gain_, &factor_}) permute(*v, map);
  for (auto* v : {&aff_k_, &aff_limit2_, &aff_decay_, &aff_gain_, &aff_fgain_}) permute(*v, map);
  permute(region_of_, map);
  permute(rest_region_, map);
  rename(candidates_, map);
  rename(members_, map);
  rename(factored_, map);
  for (Lane& lane : lanes_) {  // the next begin_batch clears the last members by their new indices
    rename(lane.candidates, map);
    for (auto& list : lane.members) rename(list, map);
  }
  // The clusters' change test compares member lists and positions by index: renamed, it would compare
  // other orders. The rebuild that sorted has bumped pairs_version_ (mark_stale) and so forces the next
  // cluster update anyway; this only says so here too.
  clustered_version_ = -1;
}

namespace {

// Yield number Y = tau_y / (|g| d (rho_p - rho_f)) of a particle, for curves that depend on it (constant per
// particle, so each particle still sees one monotone Cd(Re') curve). A particle lighter than the fluid has no
// finite Y: +inf (only its limit matters to such curves).
double yield_number(const FluidRegion& reg, double mass, double radius, const Vec3& g) {
  if (reg.yield_stress() <= 0.0) return 0.0;
  const double d = 2.0 * radius;
  const double rho_p = mass / (4.0 / 3.0 * kPi * radius * radius * radius), gmag = norm(g);
  return (rho_p > reg.density() && gmag > 0.0) ? reg.yield_stress() / (gmag * d * (rho_p - reg.density()))
                                                   : std::numeric_limits<double>::infinity();
}

// The law's sphere of diameter 2 radius and yield number y in region reg, and D(s) with or without the yield
// term (pi d/2)^2 tau_y (the switch keeps tau_y inside Re'): f(magnitude), one visit of the law per call.
template <class F>
auto with_drag(const FluidRegion& reg, double y, double radius, F&& f) {
  const double d = 2.0 * radius;
  return std::visit(
      [&](const auto& prm) {
        using Law = typename std::decay_t<decltype(prm)>::Law;
        const auto sphere = Law::sphere(prm, reg.curve, d, y);
        const double off = reg.yield_term ? 0.0 : Law::yield_term(sphere);
        return f([&](double s) { return Law::magnitude(sphere, s) - off; });
      },
      reg.law);
}

double rest_drag(const FluidRegion& reg, double y, double radius) {
  return with_drag(reg, y, radius, [](const auto& magnitude) { return magnitude(kRestSpeed); });
}

// N s/m: the slope k of a law that is linear without a rest part, D(s) = k s (the law's linear_slope with
// this curve), else 0. Such a law has neither a yield stress nor a yield term, so the switches do not apply.
double linear_slope(const FluidRegion& reg, double radius) {
  return std::visit(
      [&](const auto& prm) {
        using Law = typename std::decay_t<decltype(prm)>::Law;
        const auto sphere = Law::sphere(prm, reg.curve, 2.0 * radius, 0.0);
        if constexpr (requires { Law::linear_slope(sphere); })
          return Law::linear_slope(sphere);
        else
          return 0.0;
      },
      reg.law);
}

// The law's affine branch for this sphere (laws' affine_part; none: k = 0). The yield_term switch shifts D by
// a constant, so the slope and the branch are the same with it off.
AffinePart affine_part(const FluidRegion& reg, double y, double radius) {
  return std::visit(
      [&](const auto& prm) {
        using Law = typename std::decay_t<decltype(prm)>::Law;
        const auto sphere = Law::sphere(prm, reg.curve, 2.0 * radius, y);
        if constexpr (requires { Law::affine_part(sphere); })
          return Law::affine_part(sphere);
        else
          return AffinePart{};
      },
      reg.law);
}

}  // namespace

void FluidField::enter(const Particles& p, std::size_t a, int region) {
  const double r = p.radius[a], phi = phi_[a];
  const bool new_region = rest_region_[a] != region;
  if (new_region) {
    const FluidRegion& reg = regions_[static_cast<std::size_t>(region)];
    y_[a] = yield_number(reg, p.mass[a], r, g_);
    d0_[a] = rest_drag(reg, y_[a], r);
    lin_k_[a] = linear_slope(reg, r);
    rest_region_[a] = region;
  }
  if (lin_k_[a] > 0.0) {
    // m dv/dt = F - phi k v over the World's half kick dt/2: the closed form with mass m/phi and force F/phi,
    // i.e. v decay + F gain / phi (one multiplication per component in the kick instead of a division).
    const LinearKick c = linear_kick(lin_k_[a], p.mass[a] / phi, 0.5 * dt_);
    lin_decay_[a] = c.decay, lin_gain_[a] = c.gain / phi;
  }
  keep_affine(p, a, region, new_region);
}

// The affine branch of the sphere's law (once per stay in a region) and its kick factors for this phi (the
// mass m / phi of kick_general's scaled equation, the World's half step).
void FluidField::keep_affine(const Particles& p, std::size_t a, int region, bool new_region) {
  if (new_region) {
    const FluidRegion& reg = regions_[static_cast<std::size_t>(region)];
    const AffinePart part = affine_part(reg, y_[a], p.radius[a]);
    // The branch ends at s_max (the curve's Re' limit); kicks within 1e-6 of it take the general kernel, so
    // rounding of s_max cannot put an evaluation of the iterations on the other branch.
    const double lim = part.s_max * (1.0 - 1e-6);
    aff_k_[a] = part.k, aff_limit2_[a] = lim * lim;
  }
  if (!(aff_k_[a] > 0.0)) return;
  const double phi = phi_[a];
  const LinearKick c = linear_kick(aff_k_[a], p.mass[a] / phi, 0.5 * dt_);
  aff_decay_[a] = c.decay, aff_gain_[a] = c.gain, aff_fgain_[a] = c.gain / phi;
}

void FluidField::restored(const Particles& p) {
  const std::size_t n = p.size();
  aff_k_.assign(n, 0.0), aff_limit2_.assign(n, 0.0), aff_decay_.assign(n, 1.0), aff_gain_.assign(n, 0.0);
  aff_fgain_.assign(n, 0.0);
  lanes_.clear(), partition_ = kNoLanes;  // made anew from members_ by the next begin_batch
  if (rest_region_.size() != n) return;  // update() makes every constant anew
  for (std::size_t a = 0; a < n; ++a)
    if (rest_region_[a] >= 0) keep_affine(p, a, rest_region_[a], true);
}

Vec3 FluidField::kick_general(long a, const Vec3& v, const Vec3& F, double mass, double radius, double h,
                      const Vec3& g) const {
  const std::size_t i = static_cast<std::size_t>(a);
  const FluidRegion& reg = regions_[static_cast<std::size_t>(region_of_[i])];
  const double vs = v_sub_[i];
  const double phi = phi_[i];  // submerged fraction (update())
  Vec3 force = F;
  if (reg.buoyancy) force -= g * (reg.density() * vs);
  if (lin_k_[i] > 0.0) {  // linear drag (drag_kick.h) at another h or gravity than kick()'s kept ones
    const LinearKick c = linear_kick(lin_k_[i], mass / phi, h);
    return v * c.decay + force * (c.gain / phi);
  }
  // m dv/dt = F - phi D  <=>  (m/phi) dv/dt = F/phi - D: the kernel's kick with scaled mass and force.
  // (x / 1 is x exactly: a sphere fully under the surface skips the four divisions, the same bits.)
  const bool whole = phi == 1.0;
  const double m_eff = whole ? mass : mass / phi;
  const fluid::Vec Fv = whole ? fluid::Vec{force.x, force.y, force.z} : fluid::Vec{force.x / phi, force.y / phi, force.z / phi};
  const fluid::Vec v0{v.x, v.y, v.z};
  // The sphere's constants kept by update() (for the gravity they were kept for; a caller with another
  // gravity gets them anew).
  const bool kept = g.x == g_.x && g.y == g_.y && g.z == g_.z;
  const double y = kept ? y_[i] : yield_number(reg, mass, radius, g);
  const double d0 = kept ? d0_[i] : rest_drag(reg, y, radius);
  // The cluster's share of the rest resistance (collective.h); the speed-dependent part stays the sphere's.
  const fluid::Vec out = with_drag(reg, y, radius, [&](const auto& magnitude) {
    return drag_kick_implicit(magnitude, d0, d0 * yield_factor(a), v0, Fv, m_eff, h);
  });
  return {out[0], out[1], out[2]};
}

}  // namespace pastemix::model::fluid
