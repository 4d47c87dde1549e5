// SPDX-License-Identifier: MIT
// The wall candidate lists' rebuild in steps (model/wall_contacts.cpp), as World::rebuild_neighbors' team
// runs them: any split of the particle blocks among threads, in any order, gives the lists, the carried
// springs and the touching flags of the one-call rebuild.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "base/rng.h"
#include "model/contacts.h"
#include "tests/model/wall_box.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

// A 5 cm box (floor and four sides) and a funnel's cone above it; 2000 spheres (1.2-2.5 mm) in and above
// the box, many near a wall.
struct Scene {
  std::vector<Wall> walls;
  Particles p;
  Scene() {
    const double h = 0.025;
    walls = model::test::open_box(2 * h, 0);
    Wall cone;
    cone.kind = WallKind::revolution, cone.origin = {h, h, 0.06};
    cone.r0 = 0.01, cone.z0 = 0.0, cone.r1 = 0.03, cone.z1 = 0.03;
    walls.push_back(cone);
    Rng rng(17);
    for (int k = 0; k < 2000; ++k) {
      const double r = rng.uniform(1.2e-3, 2.5e-3);
      const Vec3 x{rng.uniform(0.0, 2 * h), rng.uniform(0.0, 2 * h), rng.uniform(0.0, 0.1)};
      p.add(0, r, 2760, x, {}, {});
    }
  }
};

// Touch every other candidate and give it a spring, so that the next rebuild has something to carry.
void touch_half(WallContacts& w) {
  for (std::size_t c = 0; c < w.near.size(); ++c) {
    w.touching[c] = c % 2;
    for (int e = 0; e < w.width; ++e) w.history[c * w.width + e] = w.touching[c] ? 1.0 + c + 0.25 * e : 0.0;
  }
}

}  // namespace

TEST_CASE("wall lists: the rebuild in steps, blocks split and ordered any way, equals the one-call rebuild") {
  Scene s;
  const double skin = 1e-3;
  WallContacts whole, steps;
  whole.resize(s.p.size(), static_cast<int>(s.walls.size()), 3);
  steps.resize(s.p.size(), static_cast<int>(s.walls.size()), 3);
  for (int round = 0; round < 3; ++round) {
    CAPTURE(round);
    whole.rebuild(s.walls, s.p, 0.0, skin, 1);
    // Blocks taken from the back, odd ones first (as two threads with a shared counter might), the rows in
    // three uneven pieces.
    steps.prepare(s.p.size(), s.walls.size());
    const long blocks = WallContacts::blocks(s.p.size());
    CHECK(blocks > 2);
    for (int parity : {1, 0})
      for (long b = blocks - 1; b >= 0; --b)
        if (b % 2 == parity) steps.flag_blocks(s.walls, s.p, 0.0, skin, b, b + 1);
    steps.lay_out();
    const long n = static_cast<long>(s.p.size());
    steps.fill_rows(n / 3, n);
    steps.fill_rows(0, 7);
    steps.fill_rows(7, n / 3);
    steps.swap_in();
    CHECK(whole.near.size() > 100);
    CHECK(steps.start == whole.start);
    CHECK(steps.near == whole.near);
    CHECK(steps.touching == whole.touching);
    CHECK(steps.history == whole.history);
    // From the second round on, the springs of the candidates that stayed were carried into the new lists.
    int carried = 0;
    for (std::size_t c = 0; c < whole.near.size(); ++c) carried += whole.touching[c] != 0;
    if (round > 0) CHECK(carried > 20);
    // Contacts for the next round's carry-over, then the spheres move by up to a skin.
    touch_half(whole);
    touch_half(steps);
    Rng rng(100 + round);
    for (Vec3& x : s.p.x) x += Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)} * skin;
  }
}

// The particles the wall pass visits in a block of consecutive ones (WallContacts::listed): exactly those
// with a candidate wall, ascending, after a rebuild, a renaming (a spatial sort's permutation with removals)
// and a resize.
TEST_CASE("wall lists: the listed particles are those with candidates, after a rebuild and a renaming") {
  Scene s;
  WallContacts w;
  w.resize(s.p.size(), static_cast<int>(s.walls.size()), 3);
  CHECK(w.listed.empty());
  const auto expected = [&] {
    std::vector<std::uint32_t> e;
    for (std::size_t a = 0; a + 1 < w.start.size(); ++a)
      if (w.start[a + 1] > w.start[a]) e.push_back(static_cast<std::uint32_t>(a));
    return e;
  };
  w.rebuild(s.walls, s.p, 0.0, 1e-3, 1);
  CHECK(w.listed.size() > 100);
  CHECK(w.listed.size() < s.p.size() / 2);
  CHECK(w.listed == expected());
  // Reverse the order and drop every tenth particle.
  const std::size_t n = s.p.size();
  std::vector<std::uint32_t> map(n);
  std::uint32_t kept = 0;
  for (std::size_t a = n; a-- > 0;) map[a] = a % 10 == 0 ? Particles::kGone : kept++;
  w.rename(map, kept);
  CHECK(w.listed == expected());
  CHECK(std::is_sorted(w.listed.begin(), w.listed.end()));
  w.resize(kept, static_cast<int>(s.walls.size()), 3);
  CHECK(w.listed.empty());
}
