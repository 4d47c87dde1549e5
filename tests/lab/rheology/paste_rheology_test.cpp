// SPDX-License-Identifier: MIT
// The paste-rheology model (lab/rheology/paste_rheology.h): anchors, the mixture densities, the published prior
// range, Krieger-Dougherty, the uncertainty propagation, the store's keys and the calibration record.
#include "lab/rheology/paste_rheology.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <tuple>
#include <fstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "tests/input_error.h"

using namespace pastemix;
using namespace pastemix::lab::rheology;

namespace {

Anchor thesis_anchor() {
  Anchor a;
  a.yield_stress = 137.97, a.yield_stress_sd = 6.03;  // the slump reduction (paste.yield_stress)
  a.plastic_viscosity = 0.7, a.curve = "published_4_19";
  a.density = 1843.0;
  return a;
}

Model model(Family f, double shape, double sd = kNaN) {
  Model m;
  m.family = f, m.anchor = thesis_anchor(), m.shape = shape, m.shape_sd = sd;
  return m;
}

using pastemix::test::input_error_of;

}  // namespace

TEST_CASE("rheology: each family gives back its anchor exactly, at every shape of its prior") {
  for (Family f : {Family::exponential, Family::packing}) {
    const Prior p = prior(f, thesis_anchor());
    for (double shape : {p.lo, p.mid(), p.hi}) {
      const Model m = model(f, shape, p.sd());
      CHECK(yield_stress(m, 0.75) == 137.97);
      CHECK(plastic_viscosity(m, 0.75) == 0.7);
      CHECK(density(m.anchor, 0.75) == 1843.0);
      const Point at = evaluate(m, 0.75);
      CHECK(at.yield_stress == 137.97);
      CHECK(at.yield_stress_sd == 6.03);               // the anchor's own, nothing from the shape
      CHECK(std::isnan(at.plastic_viscosity_sd));      // the thesis gives none
      // Lower solids: a thinner paste.
      CHECK(yield_stress(m, 0.725) < 137.97);
      CHECK(yield_stress(m, 0.70) < yield_stress(m, 0.725));
      CHECK(plastic_viscosity(m, 0.70) < plastic_viscosity(m, 0.725));
    }
  }
}

TEST_CASE("rheology: solids volume fraction and the mixture rule against hand values, and the density gap as air") {
  const Anchor a = thesis_anchor();
  // phi = (C/2710) / (C/2710 + (1-C)/1000): 75 % -> 0.52539..., rho_mix = 1 / (0.75/2710 + 0.25/1000).
  CHECK(solids_volume_fraction(a, 0.75) == doctest::Approx((0.75 / 2710) / (0.75 / 2710 + 0.25 / 1000)).epsilon(1e-14));
  CHECK(solids_volume_fraction(a, 0.70) == doctest::Approx(0.46269).epsilon(1e-4));
  CHECK(mixture_density(a, 0.75) == doctest::Approx(1898.43).epsilon(1e-5));
  CHECK(air_content(a) == doctest::Approx(1.0 - 1843.0 / 1898.43).epsilon(1e-4));
  CHECK(100 * air_content(a) == doctest::Approx(2.92).epsilon(2e-3));
  // Constant air: rho(C) = 1843 rho_mix(C) / rho_mix(0.75).
  CHECK(density(a, 0.725) == doctest::Approx(1843.0 * mixture_density(a, 0.725) / mixture_density(a, 0.75)));
  CHECK(density(a, 0.70) == doctest::Approx(1738.85).epsilon(1e-5));  // 1843 x 1791.1 / 1898.4
}

TEST_CASE("rheology: the prior ends are the published factors 2 and 4.5 per 2.5 points, for both families") {
  const Anchor a = thesis_anchor();
  const Prior e = prior(Family::exponential, a);
  CHECK(e.lo == doctest::Approx(std::log(2.0) / 2.5));
  CHECK(e.hi == doctest::Approx(std::log(4.5) / 2.5));
  CHECK(e.lo == doctest::Approx(0.277).epsilon(1e-3));
  CHECK(e.hi == doctest::Approx(0.602).epsilon(1e-3));
  const Prior p = prior(Family::packing, a);
  CHECK(p.lo < p.hi);
  CHECK(p.lo > solids_volume_fraction(a, 0.75));  // the 75 % paste flows: phi_m above its phi
  for (auto [f, shape, factor] : {std::tuple{Family::exponential, e.lo, 2.0}, std::tuple{Family::exponential, e.hi, 4.5},
                                  std::tuple{Family::packing, p.hi, 2.0}, std::tuple{Family::packing, p.lo, 4.5}}) {
    const Model m = model(f, shape);
    CHECK(yield_stress(m, 0.75) / yield_stress(m, 0.725) == doctest::Approx(factor).epsilon(1e-12));
  }
  // The exponential rule per wt %: tau(72.5)/tau(75) = exp(-2.5 b) exactly as written.
  const Model m = model(Family::exponential, 0.5);
  CHECK(yield_stress(m, 0.70) == doctest::Approx(137.97 * std::exp(-2.5)).epsilon(1e-13));
  CHECK(e.sd() == doctest::Approx((e.hi - e.lo) / std::sqrt(12.0)));
}

TEST_CASE("rheology: Krieger-Dougherty on the same phi, with the family's packing fraction") {
  const Anchor a = thesis_anchor();
  const double phi_m = 0.56, phi = solids_volume_fraction(a, 0.725), phi_a = solids_volume_fraction(a, 0.75);
  const Model pk = model(Family::packing, phi_m);
  const double kd = std::pow((1 - phi / phi_m) / (1 - phi_a / phi_m), -2.5 * phi_m);
  CHECK(plastic_viscosity(pk, 0.725) == doctest::Approx(0.7 * kd).epsilon(1e-12));
  // Exponential: the packing fraction whose packing-family tau ratio 72.5/75 equals exp(2.5 b).
  const Model ex = model(Family::exponential, 0.44);
  const Model twin = model(Family::packing, packing_fraction(ex));
  CHECK(yield_stress(twin, 0.725) == doctest::Approx(yield_stress(ex, 0.725)).epsilon(1e-12));
  CHECK(plastic_viscosity(ex, 0.725) == doctest::Approx(plastic_viscosity(twin, 0.725)).epsilon(1e-12));
}

TEST_CASE("rheology: the shape parameter's sd propagates to tau_y and eta_B (delta method)") {
  const Model m = model(Family::exponential, 0.44, 0.05);
  const Point pt = evaluate(m, 0.725);
  // tau = tau_75 exp(100 b (C - 0.75)): d tau / d b = -2.5 tau; the anchor's relative sd adds in quadrature.
  const double expect = std::hypot(pt.yield_stress / 137.97 * 6.03, 2.5 * pt.yield_stress * 0.05);
  CHECK(pt.yield_stress_sd == doctest::Approx(expect).epsilon(1e-6));
  CHECK(pt.plastic_viscosity_sd > 0.0);
}

TEST_CASE("rheology: a shape parameter outside its prior range is an error naming it and the range") {
  const Anchor a = thesis_anchor();
  const std::string e = input_error_of([&] { check_shape(Family::exponential, a, 0.9, "record.toml"); });
  CHECK(e.find("record.toml") != std::string::npos);
  CHECK(e.find("exponential.b") != std::string::npos);
  CHECK(e.find("outside its prior range [0.277259, 0.601631]") != std::string::npos);
  const std::string p = input_error_of([&] { check_shape(Family::packing, a, 0.70, "x"); });
  CHECK(p.find("packing.phi_m") != std::string::npos);
  CHECK(input_error_of([&] { check_shape(Family::exponential, a, std::nan(""), "x"); }).find("finite") != std::string::npos);
  CHECK(input_error_of([&] { check_shape(Family::exponential, a, 0.4, "x"); }).empty());
  // The store refuses it too (nothing half-written: it throws before returning any parameter).
  ShapeSource s;
  CHECK(input_error_of([&] { store_parameters(model(Family::exponential, 0.2), s, {0.725}, {"2"}, "slump"); })
            .find("exponential.b = 0.2") != std::string::npos);
  Anchor bad = a;
  bad.plastic_viscosity = -1;
  CHECK(input_error_of([&] { check_anchor(bad, "m.toml"); }).find("plastic_viscosity") != std::string::npos);
}

TEST_CASE("rheology: the store has the model and, per solids content, value, sd, provenance and the label") {
  ShapeSource prior_src;
  const auto ps = store_parameters(model(Family::exponential, 0.44, 0.09), prior_src, {0.70, 0.725, 0.75},
                                   {"1", "2, 4, 5, 6, 7", "3"}, "slump_tests.csv");
  auto get = [](const std::vector<lab::Parameter>& v, const std::string& key) -> const lab::Parameter& {
    for (const auto& p : v)
      if (p.key == key) return p;
    FAIL("missing " << key);
    return v.front();
  };
  const auto& t72 = get(ps, "paste_rheology.cw_72_5.yield_stress");
  CHECK(t72.provenance == lab::Provenance::assumed);
  CHECK(t72.method == "model exponential, shape parameter at its prior (prior)");
  CHECK(t72.note.find("at-rest effective") != std::string::npos);
  CHECK(t72.note.find("2, 4, 5, 6, 7") != std::string::npos);
  CHECK(std::isfinite(t72.sd));
  CHECK(get(ps, "paste_rheology.cw_75.yield_stress").value == 137.97);
  CHECK(get(ps, "paste_rheology.cw_75.yield_stress").provenance == lab::Provenance::measured);
  CHECK(get(ps, "paste_rheology.model.curve").text == "published_4_19");
  // The band: the shape parameter at -1 / +1 sd (b larger: a thinner 72.5 % paste).
  const Model band = model(Family::exponential, 0.44 + 0.09);
  CHECK(get(ps, "paste_rheology.cw_72_5.plus_sd.yield_stress").value == doctest::Approx(yield_stress(band, 0.725)));
  CHECK(get(ps, "paste_rheology.cw_72_5.plus_sd.plastic_viscosity").value == doctest::Approx(plastic_viscosity(band, 0.725)));
  CHECK(get(ps, "paste_rheology.cw_72_5.minus_sd.yield_stress").value > t72.value);
  CHECK(get(ps, "paste_rheology.cw_70.density").value == doctest::Approx(1738.85).epsilon(1e-5));
  ShapeSource cal;
  cal.calibrated = true, cal.case_id = 2, cal.record = "rheology_calibration.toml";
  const auto pc = store_parameters(model(Family::packing, 0.55, 0.004), cal, {0.725}, {"2"}, "slump_tests.csv");
  CHECK(get(pc, "paste_rheology.cw_72_5.plastic_viscosity").provenance == lab::Provenance::calibrated);
  CHECK(get(pc, "paste_rheology.cw_72_5.yield_stress").method == "model packing, shape parameter calibrated on case 2");
  CHECK(solids_key(0.725) == "cw_72_5");
  CHECK(solids_key(0.7) == "cw_70");
}

TEST_CASE("rheology: the calibration record round-trips and a malformed one names the file and key") {
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("pastemix_rheo_{}", static_cast<long>(::getpid()));
  std::filesystem::create_directories(dir);
  Calibration c;
  c.family = Family::packing, c.shape = 0.5512345678901234, c.sd = 0.0031, c.case_id = 2, c.detail = "test \"q\"";
  const std::string path = (dir / "cal.toml").string();
  std::ofstream(path) << calibration_toml(c, "pastemix calibrate rheology --case 2", "2026-12-01T00:00:00Z");
  const Calibration back = read_calibration(path);
  CHECK(back.family == Family::packing);
  CHECK(back.shape == c.shape);
  CHECK(back.sd == c.sd);
  CHECK(back.case_id == 2);
  CHECK(back.detail == c.detail);
  std::ofstream(path) << "[rheology_calibration]\nfamily = \"exponential\"\nshape = 0.4\nsd = 0.01\ncase = 2\nsahpe = 1\n";
  const std::string e = input_error_of([&] { read_calibration(path); });
  CHECK(e.find("cal.toml:6") != std::string::npos);
  CHECK(e.find("sahpe") != std::string::npos);
  CHECK(input_error_of([&] { read_calibration((dir / "none.toml").string()); }).find("no such calibration record") !=
        std::string::npos);
  std::filesystem::remove_all(dir);
}
