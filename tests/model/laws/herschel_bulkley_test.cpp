// SPDX-License-Identifier: MIT
// The Herschel-Bulkley drag law (laws/herschel_bulkley.h): at n = 1 it is the Bingham law (eta_B = K) to
// round-off, in its drag and through the engine's kick; at tau_y = 0 with the Stokes branch it is the power-law
// form 3 pi K d^2 (s/d)^n; a scene selects it by name with its own keys, and a bad flow index is an input
// error at its key.
#include "model/laws/herschel_bulkley.h"

#include <doctest/doctest.h>

#include <cmath>

#include "base/error.h"
#include "model/fluid/drag_kick.h"
#include "model/fluid/fluid_scene.h"
#include "base/units.h"
#include "model/laws/bingham_dedegil.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

constexpr double kPi = units::pi;

// The paste of the thesis (1843 kg/m3, 138 Pa, 0.7 Pa.s) as both laws, with n = 1.
const BinghamDedegil::Params kBingham{1843.0, 138.0, 0.7};
const HerschelBulkley::Params kHb1{1843.0, 138.0, 0.7, 1.0};

std::vector<drag::DragCurve> curves() {
  return {{drag::CurveId::stokes, {}},
          {drag::CurveId::published_4_19, {}},
          {drag::CurveId::power_blend, {24.0, 1.0, 0.5, 0.4, 1.5}},
          {drag::CurveId::yield_blend, {110.0, 1.0, 0.5, 0.4, 1.5, 20.0}}};
}

}  // namespace

TEST_CASE("herschel_bulkley: at n = 1 the drag is the Bingham law's to round-off (1e-14)") {
  for (const auto& c : curves())
    for (double d : {1e-3, 5e-3, 0.0126, 0.05})
      for (double s = 1e-9; s < 20.0; s *= 1.7) {
        const double y = 0.01;
        const double hb = HerschelBulkley::magnitude(HerschelBulkley::sphere(kHb1, c, d, y), s);
        const double bi = BinghamDedegil::magnitude(BinghamDedegil::sphere(kBingham, c, d, y), s);
        CAPTURE(c.info().name);
        CAPTURE(d);
        CAPTURE(s);
        CHECK(std::abs(hb - bi) <= 1e-14 * bi);
      }
  const drag::DragCurve c{drag::CurveId::stokes, {}};
  CHECK(HerschelBulkley::yield_term(HerschelBulkley::sphere(kHb1, c, 0.01, 0.0)) ==
        BinghamDedegil::yield_term(BinghamDedegil::sphere(kBingham, c, 0.01, 0.0)));
}

TEST_CASE("herschel_bulkley: at n = 1 the engine's kick gives the Bingham law's velocities to round-off") {
  // A 12.6 mm steel ball (8135 kg/m3) entering the paste at 1.5 m/s, 2000 kicks of 5 us: both laws through the
  // one kernel (drag_kick_implicit), as FluidField::kick runs it.
  const drag::DragCurve c{drag::CurveId::published_4_19, {}};
  const double d = 0.0126, m = 8135.0 * kPi * d * d * d / 6.0, w = (8135.0 - 1843.0) * 9.81 * kPi * d * d * d / 6.0;
  auto run = [&](auto law, const auto& prm) {
    using Law = decltype(law);
    const auto sphere = Law::sphere(prm, c, d, 0.0);
    auto magnitude = [&](double s) { return Law::magnitude(sphere, s); };
    const double d0 = magnitude(fluid::kRestSpeed);
    fluid::Vec v{0.2, 0.0, -1.5};
    for (int n = 0; n < 2000; ++n) v = fluid::drag_kick_implicit(magnitude, d0, d0, v, {0.0, 0.0, -w}, m, 5e-6);
    return v;
  };
  const fluid::Vec hb = run(HerschelBulkley{}, kHb1), bi = run(BinghamDedegil{}, kBingham);
  CHECK(bi[2] < 0.0);  // still moving: the comparison is not of two zeros
  for (int k = 0; k < 3; ++k) CHECK(std::abs(hb[k] - bi[k]) <= 1e-12 * std::abs(bi[2]));
}

TEST_CASE("herschel_bulkley: with tau_y = 0 and the Stokes branch the drag is 3 pi K d^2 (s/d)^n") {
  // The power-law limit of the law's own form (24/Re_HB with Re_HB = rho s^2 / (K (s/d)^n)).
  const drag::DragCurve c{drag::CurveId::stokes, {}};
  for (double n : {0.5, 0.8, 1.3}) {
    const HerschelBulkley::Params p{1200.0, 0.0, 2.0, n};
    for (double s : {1e-4, 1e-2, 0.3}) {
      const double d = 0.004;
      CHECK(HerschelBulkley::magnitude(HerschelBulkley::sphere(p, c, d, 0.0), s) ==
            doctest::Approx(3.0 * kPi * 2.0 * d * d * std::pow(s / d, n)).epsilon(1e-13));
    }
  }
}

TEST_CASE("herschel_bulkley: a scene selects it by name, reads its keys, and refuses a bad flow index at its key") {
  auto scene = [](const std::string& n) {
    return "[[fluid]]\nx = [0, 0.1]\ny = [0, 0.1]\nbottom = 0\nsurface = 0.1\nrheology = \"herschel_bulkley\"\n"
           "density = 1843\nyield_stress = 120\nconsistency = 2.5\nflow_index = " +
           n + "\ncurve = \"published_4_19\"\n";
  };
  const Params root = Params::parse(scene("0.5"), "hb.toml");
  const auto regions = fluid::read_fluid_regions(root, "hb.toml", {-1, -1, -1}, {1, 1, 1});
  REQUIRE(regions.size() == 1);
  CHECK(regions[0].law_name() == "herschel_bulkley");
  CHECK(regions[0].yield_stress() == 120.0);
  CHECK(std::get<HerschelBulkley::Params>(regions[0].law).flow_index == 0.5);
  const Params bad = Params::parse(scene("3.0"), "hb.toml");
  try {
    (void)fluid::read_fluid_regions(bad, "hb.toml", {-1, -1, -1}, {1, 1, 1});
    FAIL("a flow index of 3 was accepted");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK(what.find("hb.toml:10") != std::string::npos);
    CHECK(what.find("flow_index") != std::string::npos);
  }
}
