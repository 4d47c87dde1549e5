// SPDX-License-Identifier: MIT
// Outflow boundary ([domain] on_exit = "remove", model/world.cpp): a sphere thrown over a wall is removed and
// recorded and the run goes on; the remaining contacts keep their springs; the same bits at any thread
// count; too much escaped mass still stops the run.
#include "model/world.h"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <tuple>

#include "base/error.h"
#include "base/h5.h"
#include "base/units.h"
#include "model/parallel.h"
#include "tests/model/scene_text.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

std::string header(double dt, double end, const std::string& gravity, const std::string& domain_max,
                   const std::string& outflow, bool rotation = true, const std::string& domain_min = "[-0.5, -0.5, -0.05]") {
  return fmt::format(
      "seed = 3\ntime_step = {}\nend_time = {}\n[domain]\nmin = {}\nmax = {}\n{}"
      "[physics]\ngravity = {}\nrotation = {}\n[contact]\nlaw = \"hertz_mindlin\"\n",
      dt, end, domain_min, domain_max, outflow, gravity, rotation ? "true" : "false");
}

std::string sphere(double r, const std::string& pos, const std::string& vel = "[0, 0, 0]") {
  return fmt::format("[[particle]]\nmaterial = \"rock\"\nradius = {}\nposition = {}\nvelocity = {}\n", r, pos, vel);
}

const std::string kRock = model::test::material("rock", 2760, 4.68e7, 0.19);

}  // namespace

TEST_CASE("outflow: a sphere thrown over the wall of an open box is removed, recorded in the HDF5, the run completes") {
  // Sphere 0 leaves the 20 x 20 x 10 cm open box at (1, 0, 2) m/s: over the wall at x = 0.2 m (t = 0.1 s,
  // z = 0.201 m, above the 0.1 m wall) and out of the domain at x = 0.2505 m, t = 0.1505 s (no force along x
  // in flight: x = 0.1 + t exactly up to round-off). Sphere 1 rests on the floor and must stay.
  const std::string dir = "model_outflow_test_out";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const double r = 0.005, dt = 1e-4;
  const std::string scene =
      header(dt, 0.3, "[0, 0, -9.81]", "[0.2505, 0.25, 0.3]", "on_exit = \"remove\"\nmax_escaped_fraction = 0.6\n",
             true, "[-0.05, -0.05, -0.01]") +
      kRock + model::test::interaction("rock/rock", 0.5, 0.466) +
      "[[wall]]\nname = \"box\"\ntype = \"box\"\nmaterial = \"rock\"\nmin = [0, 0, 0]\nmax = [0.2, 0.2, 0.1]\n" +
      sphere(r, "[0.1, 0.1, 0.05]", "[1, 0, 2]") + sphere(r, "[0.05, 0.05, 0.005]") +
      "[output]\ninterval = 0.1\n";
  {
    std::ofstream f(dir + "/throw.toml");
    f << scene;
  }
  const auto run = pastemix::test::run_pastemix("run " + dir + "/throw.toml --out " + dir + " --quiet --threads 1");
  MESSAGE(run.output);
  REQUIRE(run.exit_code == 0);
  const double mass = 2760 * 4.0 / 3.0 * units::pi * r * r * r;
  CHECK(run.output.find("outflow: 1 particle(s) left the domain and were removed") != std::string::npos);
  CHECK(run.output.find("50 % of the") != std::string::npos);

  H5Reader h5(dir + "/throw.h5");
  CHECK(h5.attribute_string("/", "on_exit") == "remove");
  CHECK(h5.attribute_int("/", "escaped_count") == 1);
  CHECK(h5.attribute_double("/", "escaped_mass") == doctest::Approx(mass).epsilon(1e-12));
  CHECK(h5.attribute_double("/", "max_escaped_fraction") == 0.6);
  REQUIRE(h5.read_ints("/escaped/id") == std::vector<std::int64_t>{0});
  const double t = h5.read_doubles("/escaped/time").at(0);
  CHECK(t > 0.1505 - 1e-9);
  CHECK(t <= 0.1505 + dt + 1e-9);
  CHECK(h5.read_doubles("/escaped/mass").at(0) == doctest::Approx(mass).epsilon(1e-12));
  CHECK(h5.read_doubles("/escaped/radius").at(0) == r);
  CHECK(h5.read_ints("/escaped/material").at(0) == 0);
  const auto x = h5.read_doubles("/escaped/position"), v = h5.read_doubles("/escaped/velocity");
  REQUIRE(x.size() == 3);
  CHECK(x[0] > 0.2505);
  CHECK(x[2] == doctest::Approx(0.05 + 2 * t - 0.5 * 9.81 * t * t).epsilon(1e-3));  // ballistic flight
  CHECK(v[0] == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(h5.dims("/escaped/velocity") == std::vector<std::uint64_t>{1, 3});
  // The run went on to its end; the last snapshot holds only sphere 1, at rest on the floor.
  CHECK(h5.attribute_int("/profile", "steps") == 3000);
  const auto snaps = h5.read_doubles("/snapshots/time");
  const std::string last = fmt::format("/snapshots/{:06d}", snaps.size() - 1);
  CHECK(h5.attribute_double(last, "time_s") == doctest::Approx(0.3));
  CHECK(h5.read_ints(last + "/id") == std::vector<std::int64_t>{1});
  CHECK(h5.read_doubles(last + "/position").at(2) == doctest::Approx(r).epsilon(1e-3));
  // Before the escape both spheres are in the snapshot.
  CHECK(h5.read_ints("/snapshots/000001/id").size() == 2);
  CHECK(h5.read_ints("/snapshots/000002/id").size() == 1);
}

TEST_CASE("outflow: removing a lower-index particle keeps the remaining contacts' springs (spheres held by friction)") {
  // On a plane tilted at 0.9 x atan(mu_s) (gravity tilted instead), rotation locked: two touching spheres lie
  // across the slope and a third sits in the groove between them, its weight along the slope carried by the
  // tangential springs of its two pair contacts, theirs by the springs of their wall contacts: static
  // friction holds all three. Sphere 0, far away, flies out of the domain top at t ~ 0.152 s: the held
  // spheres' dense indices shift down by one and their springs must follow them. Without the renaming the
  // springs would restart from zero (the spheres slip ~1e-6 m until they have built up again) or be read
  // from the wrong contact.
  const double mu = 0.341, R = 0.005;
  const double th = 0.9 * std::atan(mu);
  const std::string grav = fmt::format("[{}, 0, {}]", 9.81 * std::sin(th), -9.81 * std::cos(th));
  auto run = [&](const std::string& domain_max) {
    const std::string scene =
        header(2e-6, 1.0, grav, domain_max, "on_exit = \"remove\"\nmax_escaped_fraction = 0.5\n", false) + kRock +
        model::test::interaction("rock/rock", 0.5, mu) +
        "[[wall]]\nname = \"incline\"\ntype = \"plane\"\nmaterial = \"rock\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n" +
        sphere(R, "[-0.4, 0, 0.5]", "[0, 0, 4]") + sphere(R, fmt::format("[0, {}, {}]", -R, R)) +
        sphere(R, fmt::format("[0, {}, {}]", R, R)) + sphere(R, fmt::format("[0, 0, {}]", R + std::sqrt(3.0) * R + 1e-7)) +
        // Without the spatial sort: the check below follows the spheres by dense index and compares the bits
        // with a 4-sphere run, whose sort would order the force sums differently (world_sort_test.cpp tests
        // the sort's renaming of the springs).
        "[neighbor]\nsort_every = 0\n";
    World w = make_world(model::test::scene_from(scene));
    while (w.time() < 0.05) w.step();
    const std::vector<Vec3> x0(w.particles().x.begin() + 1, w.particles().x.end());
    long pairs = 0;
    while (w.time() < 0.25) {
      w.step();
      if (w.steps() % 1000 == 0) pairs = std::max(pairs, w.energies().pair_contacts);
    }
    return std::make_tuple(x0, w.particles().x, w.escaped(), pairs);
  };
  const auto [x0, x, escaped, pairs] = run("[0.5, 0.5, 1.0]");
  REQUIRE(escaped.size() == 1);
  CHECK(escaped[0].id == 0);
  CHECK(escaped[0].time > 0.05);  // removed while the spheres are judged
  CHECK(escaped[0].time < 0.25);
  CHECK(pairs >= 2);  // the groove sphere on both lower ones (which may part: their wall friction holds them)
  REQUIRE(x.size() == 3);
  double moved = 0.0;
  for (std::size_t a = 0; a < 3; ++a) moved = std::max(moved, norm(x[a] - x0[a]));
  MESSAGE(fmt::format("sphere 0 removed at t = {:.5f} s; largest displacement of the held spheres over [0.05, 0.25] s "
                      "{:.3e} m",
                      escaped[0].time, moved));
  CHECK(moved < 1e-9);  // stuck, as without any removal
  // The same scene with a domain tall enough that sphere 0 never leaves: the held spheres' forces never
  // involve it, so they must follow the very same trajectory, bit for bit.
  const auto [x0_kept, x_kept, none, pairs_kept] = run("[0.5, 0.5, 3.0]");
  CHECK(none.empty());
  REQUIRE(x_kept.size() == 4);
  CHECK(std::memcmp(&x[0], &x_kept[1], 3 * sizeof(Vec3)) == 0);
}

TEST_CASE("outflow: a removal gives the same bits on 1 and 2 threads (and in batches)") {
  // A pile thrown down onto a floor into a pool of paste, and four spheres shot sideways out of the 20 x 20 cm
  // domain through its edge while the pile's contacts (pairs and walls, histories in use) go on.
  auto run = [](int threads, long batch) {
    omp_set_num_threads(threads);
    std::string text =
        header(4e-6, 1.0, "[0, 0, -9.81]", "[0.1, 0.1, 1.0]", "on_exit = \"remove\"\nmax_escaped_fraction = 0.5\n",
               true, "[-0.1, -0.1, -0.05]") +
        "rolling = \"constant_torque\"\n" + kRock + model::test::interaction("rock/rock", 0.79, 0.466, 0.15) +
        "[[wall]]\nname = \"floor\"\ntype = \"plane\"\nmaterial = \"rock\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n"
        "[[factory]]\nmaterial = \"rock\"\nmass = 0.02\nshape = \"cylinder\"\ncenter = [0, 0]\nradius = 0.025\n"
        "z_min = 0.002\nz_max = 0.06\nvelocity = [0, 0, -1.5]\n[[factory.psd]]\nd_min = 5e-3\nd_max = 8e-3\n"
        "fraction = 1.0\n"
        // Paste under the pile: the fluid hook's per-particle flags and candidates must follow the removals.
        "[[fluid]]\nname = \"paste\"\nx = [-0.03, 0.03]\ny = [-0.03, 0.03]\nbottom = 0.0\nsurface = 0.015\n"
        "density = 1843\nrheology = \"bingham\"\nyield_stress = 138\nplastic_viscosity = 0.7\n"
        "curve = \"published_4_19\"\nsolids_fraction = 0.75\n" +
        sphere(0.003, "[0.04, 0.0, 0.01]", "[4, 0, 0]") + sphere(0.003, "[-0.04, 0.0, 0.01]", "[-4, 0, 0]") +
        sphere(0.003, "[0.0, 0.04, 0.01]", "[0, 4, 0]") + sphere(0.003, "[0.0, -0.04, 0.01]", "[0, -4.5, 0]");
    Scene scene = model::test::scene_from(text);
    scene.config.parallel_min_items = 0;  // force the parallel paths even for this small scene
    World w = make_world(scene);
    for (long k = 0; k < 6000; k += batch) w.advance(batch);  // 0.024 s: out at ~0.015 s; the pile collides
    const Energies e = w.energies();
    REQUIRE(w.fluid() != nullptr);
    long wet = 0;
    for (std::size_t a = 0; a < w.particles().size(); ++a) wet += w.fluid()->inside(static_cast<long>(a));
    CHECK(wet > 0);
    omp_set_num_threads(omp_get_num_procs());
    return std::make_tuple(w.particles().x, w.particles().v, w.escaped(), e.pair_contacts);
  };
  const auto [xa, va, ea, pairs] = run(1, 1);
  const auto [xb, vb, eb, pairs_b] = run(2, 1);
  const auto [xc, vc, ec, pairs_c] = run(2, 500);
  MESSAGE(fmt::format("{} spheres left, {} removed, {} touching pairs at the end", xa.size(), ea.size(), pairs));
  CHECK(ea.size() >= 4);
  CHECK(pairs > 0);
  REQUIRE(xa.size() == xb.size());
  REQUIRE(xa.size() == xc.size());
  CHECK(std::memcmp(xa.data(), xb.data(), xa.size() * sizeof(Vec3)) == 0);
  CHECK(std::memcmp(va.data(), vb.data(), va.size() * sizeof(Vec3)) == 0);
  CHECK(std::memcmp(xa.data(), xc.data(), xa.size() * sizeof(Vec3)) == 0);
  REQUIRE(ea.size() == eb.size());
  REQUIRE(ea.size() == ec.size());
  for (std::size_t k = 0; k < ea.size(); ++k) {
    CHECK(ea[k].id == eb[k].id);
    CHECK(ea[k].time == eb[k].time);
    CHECK(ea[k].id == ec[k].id);
    CHECK(std::memcmp(&ea[k].x, &eb[k].x, sizeof(Vec3)) == 0);
  }
}

TEST_CASE("outflow: more escaped mass than max_escaped_fraction stops the run with particle, time and cause") {
  // No floor: both spheres fall out of the domain's bottom together (50 % of the mass > 5 %).
  const std::string fall = header(1e-4, 1.0, "[0, 0, -9.81]", "[0.5, 0.5, 1.0]", "on_exit = \"remove\"\n") + kRock +
                           model::test::interaction("rock/rock", 0.5, 0.0) + sphere(0.005, "[0, 0, 0.01]") +
                           sphere(0.005, "[0.2, 0, 0.3]");
  World w = make_world(model::test::scene_from(fall));
  std::string msg = model::test::failure_of([&] {
    for (int k = 0; k < 10000; ++k) w.step();
  });
  MESSAGE(msg);
  CHECK(msg.find("particle id 0 at t = 0.11") != std::string::npos);  // z = 0.01 - g t^2 / 2 < -0.05 at t ~ 0.1106 s
  CHECK(msg.find("left the domain") != std::string::npos);
  CHECK(msg.find("max_escaped_fraction = 0.05") != std::string::npos);
  CHECK(msg.find("50 %") != std::string::npos);
  CHECK(w.escaped().empty());  // nothing recorded or removed: the run stopped
  CHECK(w.particles().size() == 2);

  // With max_escaped_fraction = 1 every sphere may leave: the run goes on with none left.
  std::string all = fall;
  all.replace(all.find("on_exit = \"remove\"\n"), 19, "on_exit = \"remove\"\nmax_escaped_fraction = 1\n");
  World empty = make_world(model::test::scene_from(all));
  for (int k = 0; k < 5000; ++k) empty.step();
  CHECK(empty.particles().size() == 0);
  REQUIRE(empty.escaped().size() == 2);
  CHECK(empty.escaped()[0].id == 0);
  CHECK(empty.escaped()[1].id == 1);
  CHECK(empty.escaped_mass() == doctest::Approx(2 * 2760 * 4.0 / 3.0 * units::pi * 1.25e-7).epsilon(1e-12));

  // NaN still stops the run under on_exit = remove (not a removal).
  World n = make_world(model::test::scene_from(fall));
  n.particles().v[1].x = std::nan("");
  msg = model::test::failure_of([&] { n.step(); });
  CHECK(msg.find("particle id 1") != std::string::npos);
  CHECK(msg.find("non-finite") != std::string::npos);
}
