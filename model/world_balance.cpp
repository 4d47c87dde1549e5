// SPDX-License-Identifier: MIT
// The threads' partition and its load balance (issue 19): World::partition, World::update_shares,
// World::imbalanced and balanced_shares, apart from the step (model/world.cpp).
#include "model/world.h"

#include <algorithm>
#include <limits>

namespace pastemix::model {

// The threads' shares for the next partition (balanced_shares, world.h), from the busy times since the last
// partition. Why (issue 19): on this VM one vCPU at a time ran memory-bound code up to 33 % slower than the
// other (the settled bed on one core: 1.91 against 1.43 s; its L2 stream 54 against 148 GB/s; which vCPU
// changes within minutes), and the partition's cost model misjudges some slabs (settled bed: equal model
// costs, busy times 0.289 against 0.241 s), so equal slabs made the fast thread wait at every step. The
// bits never depend on the partition (each particle's pair sum runs in ascending pair order).
std::vector<double> balanced_shares(const std::vector<double>& share, const std::vector<double>& work,
                                    const std::vector<double>& busy) {
  const std::size_t nt = share.size();
  std::vector<double> speed(nt), next = share;
  double sum = 0.0;
  for (std::size_t t = 0; t < nt; ++t) {
    speed[t] = busy[t] > 0.0 ? work[t] / busy[t] : 0.0;
    sum += speed[t];
  }
  if (!(sum > 0.0)) return next;
  const double eq = 1.0 / static_cast<double>(nt);
  double norm = 0.0;
  for (std::size_t t = 0; t < nt; ++t) {
    next[t] = std::clamp(0.5 * share[t] + 0.5 * speed[t] / sum, 0.5 * eq, 1.5 * eq);
    norm += next[t];
  }
  for (double& s : next) s /= norm;
  return next;
}

void World::update_shares(int threads) {
  const auto nt = static_cast<std::size_t>(threads);
  if (share_.size() != nt) share_.assign(nt, 1.0 / threads), busy_.assign(nt, {});
  if (!balance_) return;
  std::vector<double> busy(nt);
  double total = 0.0;
  for (std::size_t t = 0; t < nt; ++t) busy[t] = busy_[t].s, total += busy[t];
  // Too little time measured (a few steps): keep the shares and go on measuring.
  if (pairs_.work.size() != nt || total < 2e-3) return;
  share_ = balanced_shares(share_, pairs_.work, busy);
  busy_.assign(nt, {});
}

// Whether the threads' busy times since the last partition (over 20 ms in all) differ by more than 10 %,
// calling for another partition before the next rebuild: a settled bed rebuilds every few hundred steps,
// too seldom to follow a core that slows down. Between two batches the cross pairs' springs are
// synchronised, so any partition is valid.
bool World::imbalanced(int threads) const {
  const auto nt = static_cast<std::size_t>(threads);
  if (!balance_ || threads <= 1 || busy_.size() != nt || pairs_.work.size() != nt) return false;
  double busy = 0.0, lo = std::numeric_limits<double>::max(), hi = 0.0;
  for (std::size_t t = 0; t < nt; ++t) {
    busy += busy_[t].s;
    lo = std::min(lo, busy_[t].s), hi = std::max(hi, busy_[t].s);
  }
  return busy > 20e-3 && hi > 1.1 * lo;
}

void World::partition(int threads, const std::vector<Vec3>& x, const std::array<double, 6>* box) {
  if (threads > 1) update_shares(threads);
  // A store sorted into cell order at rebuilds: its index ranges are spatial slabs (PairList::Slabs).
  pairs_.slabs = cfg_.sort_every > 0 ? PairList::Slabs::index : PairList::Slabs::space;
  bool costed = false;
  for_each_pass(forces_, [&](const auto& pass) {
    if constexpr (requires { pass.partition_cost(0L); }) costed |= pass.active();
  });
  if (!costed || threads <= 1) return pairs_.partition(threads, x, nullptr, &share_, box);
  pass_cost_.assign(p_.size(), 0.0);
  for_each_pass(forces_, [&](const auto& pass) {
    if constexpr (requires { pass.partition_cost(0L); })
      if (pass.active())
        for (std::size_t a = 0; a < p_.size(); ++a) pass_cost_[a] += pass.partition_cost(static_cast<long>(a));
  });
  pairs_.partition(threads, x, &pass_cost_, &share_, box);
}

}  // namespace pastemix::model
