// SPDX-License-Identifier: MIT
// PairList::partition (model/contacts.h): the threads' particles and pairs, apart from the list's rebuild
// (model/contacts.cpp). Any partition gives the same bits (each particle's pair sum runs in ascending pair
// order); what it decides is how long the other thread waits for the one partitioning at each rebuild (2
// threads, bench pour, 214 rebuilds: 0.042 s of partition on thread 0 beside thread 1's 0.031 s of list
// work, in a run of 0.56-0.60 s; issue 19).
#include "model/contacts.h"

#include <algorithm>
#include <stdexcept>

namespace pastemix::model {

namespace {

// The segments of a thread's pair list (PairList::Segment): runs of at least kMinRun consecutive pair
// indices without kCrossBit, and the stretches between them.
void cut_segments(const std::vector<std::uint32_t>& ks, std::vector<PairList::Segment>& segs) {
  segs.clear();
  const auto n = static_cast<std::uint32_t>(ks.size());
  std::uint32_t rest = 0;  // where the stretch not yet in a segment begins
  for (std::uint32_t q = 0; q < n;) {
    if ((ks[q] & PairList::kCrossBit) != 0) {
      ++q;
      continue;
    }
    std::uint32_t e = q + 1;
    while (e < n && ks[e] == ks[e - 1] + 1) ++e;  // a cross entry has the top bit: never the next index
    if (e - q >= PairList::kMinRun) {
      if (rest < q) segs.push_back({rest, q, false});
      segs.push_back({q, e, true});
      rest = e;
    }
    q = e;
  }
  if (rest < n) segs.push_back({rest, n, false});
}

// The cumulated shares: thread t's slab ends where the cumulated cost reaches total x upto[t + 1].
std::vector<double> cumulated_shares(int n_threads, const std::vector<double>* share) {
  const auto nt = static_cast<std::size_t>(n_threads);
  std::vector<double> upto(nt + 1, 0.0);
  const bool given = share && share->size() == nt;
  for (std::size_t u = 0; u < nt; ++u)
    upto[u + 1] = given ? upto[u] + (*share)[u] : static_cast<double>(u + 1) / n_threads;
  return upto;
}

// Index slabs: particle a goes to the thread whose share of the cost, cumulated along the index, it starts
// in. One pass, no bins (the bins' index a * 4096 / np, an integer division per particle, was a quarter of
// the partition's time on the bench pour).
void owners_by_index(const double* cost, std::size_t np, const std::vector<double>& upto, std::uint8_t* owner) {
  double total = 0.0;
  for (std::size_t a = 0; a < np; ++a) total += cost[a];
  const std::size_t last = upto.size() - 2;  // the last thread
  std::size_t t = 0;
  double run = 0.0;  // the cost of particles 0 .. a - 1
  for (std::size_t a = 0; a < np; ++a) {
    while (t < last && run >= total * upto[t + 1]) ++t;  // thread t's share is used up
    owner[a] = static_cast<std::uint8_t>(t);
    run += cost[a];
  }
}

// Space slabs: slices across the longest side of the box lo .. hi, of about equal cost, cut at the
// boundaries of 4096 bins along it.
void owners_by_space(const std::vector<Vec3>& x, const double* cost, const Vec3& lo, const Vec3& hi,
                     const std::vector<double>& upto, std::uint8_t* owner) {
  const std::size_t np = x.size();
  const int n_threads = static_cast<int>(upto.size()) - 1;
  const Vec3 ext = hi - lo;
  const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
  auto coord = [&](const Vec3& q) { return axis == 0 ? q.x - lo.x : axis == 1 ? q.y - lo.y : q.z - lo.z; };
  const double len = axis == 0 ? ext.x : axis == 1 ? ext.y : ext.z;
  constexpr int kBins = 4096;
  std::vector<double> bin(kBins + 1, 0.0);
  std::vector<int> bin_of(np);
  const double scale = len > 0.0 ? kBins / len : 0.0;
  double total = 0.0;
  for (std::size_t a = 0; a < np; ++a) {
    bin_of[a] = std::clamp(static_cast<int>(coord(x[a]) * scale), 0, kBins - 1);
    bin[static_cast<std::size_t>(bin_of[a])] += cost[a];
    total += cost[a];
  }
  // First bin of each thread's slab.
  std::vector<int> first(static_cast<std::size_t>(n_threads) + 1, kBins);
  first[0] = 0;
  double run = 0.0;
  int t = 1;
  for (int b = 0; b < kBins && t < n_threads; ++b) {
    run += bin[static_cast<std::size_t>(b)];
    while (t < n_threads && run >= total * upto[static_cast<std::size_t>(t)])
      first[static_cast<std::size_t>(t++)] = b + 1;
  }
  for (std::size_t a = 0; a < np; ++a) {
    // The slab whose first bin is the last at or below the particle's (first[] ascends from first[0] = 0).
    int o = 0;
    while (o + 1 < n_threads && first[static_cast<std::size_t>(o) + 1] <= bin_of[a]) ++o;
    owner[a] = static_cast<std::uint8_t>(o);
  }
}

}  // namespace

void PairList::partition(int n_threads, const std::vector<Vec3>& x, const std::vector<double>* extra,
                         const std::vector<double>* share, const std::array<double, 6>* box) {
  threads = n_threads;
  ++partitions;
  const std::size_t np = x.size(), n = size(), ws = static_cast<std::size_t>(width);
  const auto nt = static_cast<std::size_t>(std::max(n_threads, 1));
  own.resize(nt);
  mine.resize(nt);
  cross.assign(n, kNone);
  cross_pairs.clear();
  ghosts.clear();
  work.clear();
  parity = 0;
  if (n_threads <= 1 || np == 0) {
    owner.assign(np, 0);
    for (auto& list : own) list.clear();
    for (auto& list : mine) list.clear();
    segments.assign(nt, {});
    return;
  }
  if (n >= kCrossBit) throw std::length_error("pair list too long for the threads' pair lists (2^31 pairs)");
  if (n_threads > 255) throw std::length_error("more than 255 threads for the partition's owners");
  // Cost of a particle, in rough units of one candidate test: its kick and walls (4), its candidate pairs
  // (1 each) and its touching pairs (5 more each: the force law), plus `extra`.
  cost_scratch.assign(np, 4.0);
  double* cost = cost_scratch.data();
  if (extra && extra->size() == np)
    for (std::size_t a = 0; a < np; ++a) cost[a] += (*extra)[a];
  const std::uint32_t *I = i.data(), *J = j.data(), *T = touching.data();
  for (std::size_t k = 0; k < n; ++k) {
    const double c = 1.0 + 5.0 * T[k];
    cost[I[k]] += c;
    cost[J[k]] += c;
  }
  owner.resize(np);
  const std::vector<double> upto = cumulated_shares(n_threads, share);
  if (slabs == Slabs::index) {
    // A sorted store: index ranges are spatial slabs (no box needed).
    owners_by_index(cost, np, upto, owner.data());
  } else {
    Vec3 lo = x[0], hi = x[0];
    if (box) {
      lo = {(*box)[0], (*box)[1], (*box)[2]}, hi = {(*box)[3], (*box)[4], (*box)[5]};
    } else {
      for (const Vec3& q : x) {
        lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
        hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
      }
    }
    owners_by_space(x, cost, lo, hi, upto, owner.data());
  }
  // The lists are counted, then filled through raw cursors (push_back per entry, whose size and capacity
  // the compiler reloads after every store, was a third of the partition).
  const std::uint8_t* O = owner.data();
  std::vector<std::size_t> count(nt, 0);
  std::vector<std::uint32_t*> at(nt);
  for (std::size_t a = 0; a < np; ++a) ++count[O[a]];
  work.assign(nt, 0.0);
  for (std::size_t t = 0; t < nt; ++t) own[t].resize(count[t]), at[t] = own[t].data();
  for (std::size_t a = 0; a < np; ++a) {
    *at[O[a]]++ = static_cast<std::uint32_t>(a);
    work[O[a]] += cost[a];
  }
  // Each thread's pairs, ascending: those of its particles i, and the cross pairs of its particles j too.
  std::fill(count.begin(), count.end(), 0);
  std::size_t n_cross = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint8_t oi = O[I[k]], oj = O[J[k]];
    ++count[oi];
    if (oj != oi) ++count[oj], ++n_cross;
  }
  for (std::size_t t = 0; t < nt; ++t) mine[t].resize(count[t]), at[t] = mine[t].data();
  cross_pairs.resize(n_cross);
  std::uint32_t* C = cross.data();
  std::size_t c = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint8_t oi = O[I[k]], oj = O[J[k]];
    if (oj == oi) {
      *at[oi]++ = static_cast<std::uint32_t>(k);
      continue;
    }
    const auto tagged = static_cast<std::uint32_t>(k) | kCrossBit;
    *at[oi]++ = tagged;
    *at[oj]++ = tagged;
    C[k] = static_cast<std::uint32_t>(c);
    cross_pairs[c++] = static_cast<std::uint32_t>(k);
  }
  segments.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) cut_segments(mine[t], segments[t]);
  // Ghosts: every particle of a cross pair.
  ghost_of.assign(np, kNone);
  for (std::uint32_t k : cross_pairs)
    for (std::uint32_t q : {i[k], j[k]})
      if (ghost_of[q] == kNone) {
        ghost_of[q] = static_cast<std::uint32_t>(ghosts.size());
        ghosts.push_back(q);
      }
  for (auto& g : ghost) g.resize(ghosts.size());
  for (auto& h : cross_hist) h.assign(cross_pairs.size() * ws, 0.0);
  for (std::size_t e = 0; e < cross_pairs.size(); ++e)
    std::copy_n(&history[cross_pairs[e] * ws], ws, &cross_hist[0][e * ws]);
}

}  // namespace pastemix::model
