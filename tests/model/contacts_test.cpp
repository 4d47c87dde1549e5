// SPDX-License-Identifier: MIT
// Contact history survives neighbour-list rebuilds (it is keyed by the particle-id pair).
#include "model/contacts.h"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "model/world.h"
#include "base/rng.h"
#include "model/laws/constant_torque.h"
#include "model/laws/hertz_mindlin.h"
#include "tests/model/scene_text.h"
#include "tests/model/wall_box.h"

using namespace pastemix;
using namespace pastemix::model;

TEST_CASE("contacts: the tangential spring survives neighbour rebuilds (rebuild every step = never)") {
  // An oblique impact: the tangential spring carries the whole contact. With a 1 nm skin the pair list is
  // rebuilt at nearly every step; with 1 mm, never during the contact. Same bits if the history is carried.
  auto run = [](double skin, long* rebuilds) {
    const std::string text = fmt::format(
        "time_step = 1e-7\nend_time = 1\n[domain]\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\n[physics]\ngravity = [0, 0, 0]\n"
        "[contact]\nlaw = \"hertz_mindlin\"\n[neighbor]\nskin = {}\n{}{}"
        "[[particle]]\nmaterial = \"m\"\nradius = 0.01\nposition = [-0.01, 0, 0]\nvelocity = [1, 0.3, 0]\n"
        "[[particle]]\nmaterial = \"m\"\nradius = 0.01\nposition = [0.01, 0, 0]\nvelocity = [-1, -0.3, 0]\n",
        skin, model::test::material("m", 2800, 4.8e10, 0.2), model::test::interaction("m/m", 0.8, 0.5));
    World w = make_world(model::test::scene_from(text));
    for (int k = 0; k < 2000; ++k) w.step();
    *rebuilds = w.profile().rebuilds;
    return std::pair{w.particles().v[0], w.particles().omega[0]};
  };
  long many = 0, few = 0;
  const auto [v_many, w_many] = run(1e-9, &many);
  const auto [v_few, w_few] = run(1e-3, &few);
  MESSAGE("rebuilds: " << many << " (1 nm skin) vs " << few << " (1 mm skin); spin after impact " << w_few.z << " rad/s");
  CHECK(many > 1000);
  CHECK(few == 1);
  CHECK(std::abs(w_few.z) > 1.0);  // the tangential force did act
  CHECK(v_many.x == v_few.x);
  CHECK(v_many.y == v_few.y);
  CHECK(w_many.z == w_few.z);
}

namespace {

// An open box 5 x 5 x 5 cm (floor and four sides, rock-like walls of material 1) and 300 spheres of
// material 0, a third of them pressed into a wall, the rest near one or inside; random velocities and spins.
struct WallScene {
  std::vector<Wall> walls;
  Particles p;
  explicit WallScene(bool funnel = false) {
    if (funnel) {
      make_funnel();
      return;
    }
    const double L = 0.05;
    walls = model::test::open_box(L, 1);
    p.enable_rotation();
    Rng rng(5);
    for (int k = 0; k < 300; ++k) {
      const double r = rng.uniform(1.2e-3, 2.5e-3);
      // Distance to the nearest wall: overlapping (a third), within the skin, or farther.
      const double gap = k % 3 == 0 ? -r * rng.uniform(1e-4, 0.02) : r * rng.uniform(0.0, 0.3);
      Vec3 x{rng.uniform(r, L - r), rng.uniform(r, L - r), rng.uniform(r, L - r)};
      const int side = k % 5;
      if (side == 0) x.z = r + gap;
      if (side == 1) x.x = r + gap;
      if (side == 2) x.x = L - r - gap;
      if (side == 3) x.y = r + gap;
      if (side == 4) x.y = L - r - gap;
      if (k % 7 == 0) x.z = r + gap;  // some in a corner (two walls)
      p.add(0, r, 2760, x, {rng.normal(), rng.normal(), rng.normal()},
            {100 * rng.normal(), 100 * rng.normal(), 100 * rng.normal()});
      p.f.back() = {rng.normal(), rng.normal(), rng.normal()};  // a pair sum before the walls
      p.torque.back() = {1e-3 * rng.normal(), 1e-3 * rng.normal(), 0};
      p.rolling_capacity.back() = 1e-4 * rng.uniform(0, 1);
    }
  }
  // A funnel as the scenes build it (surfaces of revolution about x = y = 0.1 m, material 1): a cone from
  // r = 2 cm at z = 0.25 m to 9.5 cm at 0.37 m and its exit tube, r = 2 cm from 0.23 to 0.25 m, with a box floor
  // below; 300 spheres against the cone or the tube from inside (a third pressed in, the rest within 0.3 r),
  // some on the axis.
  void make_funnel() {
    const auto revolution = [&](double r0, double z0, double r1, double z1) {
      Wall w;
      w.kind = WallKind::revolution, w.material = 1, w.origin = {0.1, 0.1, 0.0};
      w.r0 = r0, w.z0 = z0, w.r1 = r1, w.z1 = z1;
      walls.push_back(w);
    };
    revolution(0.02, 0.25, 0.095, 0.37);
    revolution(0.02, 0.23, 0.02, 0.25);
    walls.push_back(model::test::open_box(0.2, 1)[0]);
    p.enable_rotation();
    Rng rng(11);
    for (int k = 0; k < 300; ++k) {
      const double r = rng.uniform(1.2e-3, 2.5e-3);
      const double gap = k % 3 == 0 ? -r * rng.uniform(1e-4, 0.02) : r * rng.uniform(0.0, 0.3);
      const Wall& w = walls[k % 4 == 0 ? 1 : 0];
      // A point of the meridian segment and the unit normal into the funnel (towards the axis; up on the cone).
      const double s = rng.uniform(0.05, 0.95), ar = w.r1 - w.r0, az = w.z1 - w.z0, l = std::hypot(ar, az);
      const double rho = w.r0 + s * ar - (r + gap) * az / l, z = w.z0 + s * az + (r + gap) * ar / l;
      const double phi = rng.uniform(0.0, 6.283185307179586);
      Vec3 x{0.1 + rho * std::cos(phi), 0.1 + rho * std::sin(phi), z};
      if (k % 50 == 7) x.x = 0.1, x.y = 0.1;  // on the axis (no radial direction)
      p.add(0, r, 2760, x, {rng.normal(), rng.normal(), rng.normal()},
            {100 * rng.normal(), 100 * rng.normal(), 100 * rng.normal()});
      p.f.back() = {rng.normal(), rng.normal(), rng.normal()};
      p.torque.back() = {1e-3 * rng.normal(), 1e-3 * rng.normal(), 0};
      p.rolling_capacity.back() = 1e-4 * rng.uniform(0, 1);
    }
  }
};

}  // namespace

namespace {

void check_batched_walls(WallScene& a, WallScene& b) {
  const int n_walls = static_cast<int>(a.walls.size());
  Material rock{"rock", 2760, 4.68e7, 0.19}, steel{"steel", 7800, 2e11, 0.3};
  std::vector<HertzMindlin::Params> laws;
  std::vector<ConstantTorque::Params> rolling;
  for (const Material* m0 : {&rock, &steel})
    for (const Material* m1 : {&rock, &steel}) {
      laws.push_back(HertzMindlin::from_pair({m0, m1, 0.79, 0.466, 0.15}));
      rolling.push_back({0.15});
    }
  const StepContext ctx{0.0, 1e-5, 2};
  WallContacts wa, wb;
  wa.resize(a.p.size(), n_walls, 3);
  wb.resize(b.p.size(), n_walls, 3);
  WallState ws;
  ws.update(a.walls, 0.0);
  std::vector<long> idx(a.p.size());
  for (std::size_t k = 0; k < idx.size(); ++k) idx[k] = static_cast<long>(k);
  long touching = 0;
  for (int step = 0; step < 3; ++step) {  // the springs of steps 1 and 2 start from those of the step before
    wa.rebuild(a.walls, a.p, 0.0, 1e-3, 1);
    wb.rebuild(b.walls, b.p, 0.0, 1e-3, 1);
    for (std::size_t k = 0; k < a.p.size(); ++k) {
      Vec3 f = a.p.f[k], t = a.p.torque[k];
      double rc = a.p.rolling_capacity[k];
      wall_forces_one<HertzMindlin, ConstantTorque>(laws, rolling, ctx, a.walls, ws, a.p, wa, k, f, t, rc);
      a.p.f[k] = f, a.p.torque[k] = t, a.p.rolling_capacity[k] = rc;
    }
    // In blocks of 61 particles (not a multiple of the batch: some batches span two blocks' contacts): step 0
    // ascending blocks of consecutive particles (the listed particles only, the cursor moving on), step 1
    // the blocks in descending order (the cursor searches back), step 2 blocks of every other particle (not
    // consecutive: each particle's row tested). A particle's wall forces are its own: any order, same bits.
    std::vector<long> order;
    for (std::size_t k = 0; k < idx.size(); ++k)
      order.push_back(step < 2 ? idx[k] : static_cast<long>(2 * k < idx.size() ? 2 * k : 2 * k - idx.size() + 1 - idx.size() % 2));
    std::vector<std::size_t> starts;
    for (std::size_t q = 0; q < order.size(); q += 61) starts.push_back(q);
    if (step == 1) std::reverse(starts.begin(), starts.end());
    for (std::size_t q : starts)
      wall_forces_block<HertzMindlin, ConstantTorque>(laws, rolling, ctx, b.walls, ws, b.p, wb, order.data() + q,
                                                      static_cast<int>(std::min<std::size_t>(61, order.size() - q)));
    for (std::size_t k = 0; k < a.p.size(); ++k) {
      CAPTURE(k);
      CHECK(a.p.f[k].x == b.p.f[k].x);
      CHECK(a.p.f[k].y == b.p.f[k].y);
      CHECK(a.p.f[k].z == b.p.f[k].z);
      CHECK(a.p.torque[k].x == b.p.torque[k].x);
      CHECK(a.p.torque[k].y == b.p.torque[k].y);
      CHECK(a.p.torque[k].z == b.p.torque[k].z);
      CHECK(a.p.rolling_capacity[k] == b.p.rolling_capacity[k]);
    }
    CHECK(wa.touching == wb.touching);
    CHECK(wa.history == wb.history);
    touching = std::count(wa.touching.begin(), wa.touching.end(), 1u);
    // Move every sphere a little (some contacts open, some close, most keep their spring).
    for (WallScene* s : {&a, &b})
      for (std::size_t k = 0; k < s->p.size(); ++k) s->p.x[k] += s->p.v[k] * 2e-5;
  }
  MESSAGE(touching << " touching wall contacts of " << wa.near.size() << " candidates");
  CHECK(touching > 50);
  CHECK(static_cast<std::size_t>(touching) < wa.near.size());
}

}  // namespace

TEST_CASE("contacts: the batched wall pass gives the per-particle wall pass's bits (forces, springs, flags)") {
  WallScene a, b;
  check_batched_walls(a, b);
}

// The funnel's distances go eight at a time through model/wall_batch.h in the batched pass.
TEST_CASE("contacts: the batched wall pass gives the per-particle pass's bits against a funnel's cone and tube") {
  WallScene a(true), b(true);
  check_batched_walls(a, b);
}

TEST_CASE("contacts: the wall candidate lists do not depend on the thread count") {
  WallScene s;
  WallContacts w1, w3;
  w1.resize(s.p.size(), 5, 3);
  w3.resize(s.p.size(), 5, 3);
  w1.rebuild(s.walls, s.p, 0.0, 1e-3, 1);
  w3.rebuild(s.walls, s.p, 0.0, 1e-3, 3);
  CHECK(w1.near.size() > 100);
  CHECK(w1.start == w3.start);
  CHECK(w1.near == w3.near);
}

TEST_CASE("contacts: one law for every pair is detected at the rebuild (its parameters then load once per batch)") {
  Rng rng(3);
  auto list = [&](int materials, bool mixed) {
    Particles p;
    for (int k = 0; k < 400; ++k)
      p.add(mixed ? k % materials : materials - 1, 1e-3, 2760,
            {rng.uniform(0, 0.02), rng.uniform(0, 0.02), rng.uniform(0, 0.02)}, {}, {});
    CandidatePairs c = build_pairs(p.x, p.radius, 5e-4);
    PairList L;
    L.rebuild(c, p, materials, 2);
    CHECK(L.size() > 100);
    const std::uint32_t found = L.uniform_law;
    L.find_uniform_law();  // as after a checkpoint's restore
    CHECK(L.uniform_law == found);
    return found;
  };
  CHECK(list(1, false) == 0u);
  CHECK(list(2, false) == 3u);  // material 1 with 1: entry 1 * 2 + 1
  CHECK(list(2, true) == PairList::kNone);
}

// The history carry-over at a rebuild (PairList::rebuild tries the old pair after the last one found, then
// the old row of the first particle): a new list that keeps most old pairs in order, drops some, inserts new
// ones and swaps neighbours carries exactly the springs of the old touching pairs, zeros elsewhere, on 1 and
// 2 threads.
TEST_CASE("contacts: the springs carried at a rebuild, for a list that kept, dropped, added and reordered pairs") {
  Particles p;
  Rng rng(23);
  const int np = 400;
  for (int a = 0; a < np; ++a) p.add(0, 1e-3, 2760, {rng.uniform(0, 0.1), rng.uniform(0, 0.1), 0.0}, {}, {});
  CandidatePairs old_pairs;
  for (std::uint32_t a = 0; a < np; ++a)
    for (std::uint32_t b : {a + 1, a + 7, a + 30})
      if (b < np) old_pairs.i.push_back(a), old_pairs.j.push_back(b);
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    PairList L;
    L.width = 3;
    CandidatePairs first = old_pairs;
    L.rebuild(first, p, 1, threads);
    // Old springs: pair k touching every third, spring (k, k + 0.5, -k).
    for (std::size_t k = 0; k < L.size(); ++k) {
      L.touching[k] = k % 3 != 1;
      for (int e = 0; e < 3; ++e) L.history[3 * k + e] = L.touching[k] ? (e == 0 ? k : e == 1 ? k + 0.5 : -1.0 * k) : 0.0;
    }
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> old_at;
    for (std::size_t k = 0; k < L.size(); ++k) old_at[{L.i[k], L.j[k]}] = k;
    const std::vector<double> old_hist = L.history;
    const std::vector<std::uint32_t> old_touch = L.touching;
    // The new list: every 11th old pair dropped, a new pair after every 13th, neighbours swapped every 17th.
    CandidatePairs next;
    for (std::size_t k = 0; k < old_pairs.i.size(); ++k) {
      if (k % 11 == 5) continue;
      next.i.push_back(old_pairs.i[k]), next.j.push_back(old_pairs.j[k]);
      if (k % 13 == 0 && old_pairs.j[k] + 2 < np) next.i.push_back(old_pairs.i[k]), next.j.push_back(old_pairs.j[k] + 2);
      if (k % 17 == 3 && next.i.size() >= 2) {
        std::swap(next.i[next.i.size() - 1], next.i[next.i.size() - 2]);
        std::swap(next.j[next.j.size() - 1], next.j[next.j.size() - 2]);
      }
    }
    const CandidatePairs expect = next;
    L.rebuild(next, p, 1, threads);
    REQUIRE(L.size() == expect.i.size());
    int carried = 0, fresh = 0;
    for (std::size_t k = 0; k < L.size(); ++k) {
      CAPTURE(k);
      REQUIRE(L.i[k] == expect.i[k]);
      REQUIRE(L.j[k] == expect.j[k]);
      const auto it = old_at.find({L.i[k], L.j[k]});
      const bool carry = it != old_at.end() && old_touch[it->second];
      REQUIRE(L.touching[k] == (carry ? 1u : 0u));
      for (int e = 0; e < 3; ++e) REQUIRE(L.history[3 * k + e] == (carry ? old_hist[3 * it->second + e] : 0.0));
      carried += carry, fresh += it == old_at.end();
    }
    CHECK(carried > 500);
    CHECK(fresh > 50);
  }
}
