// SPDX-License-Identifier: MIT
// The yield-stress laws (model/flow/bingham.h): their values against the formulas' limits, and reading them
// from a [flow.paste] table or the lab's parameter store, with every mistake an error naming file:line:key.
#include "model/flow/bingham.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "model/flow/flow_config.h"
#include "model/flow/solver.h"
#include "tests/input_error.h"

using namespace pastemix;
using namespace pastemix::flow;
namespace fs = std::filesystem;

TEST_CASE("bingham: Papanastasiou's law at its limits (plug eta_B + tau_y m, yielded eta_B + tau_y / gamma_dot)") {
  const Bingham b(138.0, 0.7, 1000.0);
  CHECK(b.viscosity(0.0) == doctest::Approx(0.7 + 138.0 * 1000.0).epsilon(1e-15));
  // Far above 1/m the exponential is gone: the exact Bingham viscosity.
  CHECK(b.viscosity(50.0) == doctest::Approx(0.7 + 138.0 / 50.0).epsilon(1e-14));
  // Across the series switch (m gd = 1e-8) the law is continuous to 1e-12 relative.
  const double g = 1e-8 / 1000.0;
  CHECK(b.viscosity(g * (1 - 1e-9)) == doctest::Approx(b.viscosity(g * (1 + 1e-9))).epsilon(1e-12));
  // The stress eta gd at gd = ln 5 / m is 0.8 tau_y (+ eta_B gd): the creep rate of a paste at 0.8 tau_y.
  const double gc = std::log(5.0) / 1000.0;
  CHECK(b.viscosity(gc) * gc == doctest::Approx(0.8 * 138.0 + 0.7 * gc).epsilon(1e-12));
  CHECK_THROWS_AS(Bingham(138.0, 0.7, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(Bingham(-1.0, 0.7, 10.0), std::invalid_argument);
}

TEST_CASE("bingham: Herschel-Bulkley with n = 1 is the Bingham law, and above 1/m it is K gd^n + tau_y") {
  const Bingham b(100.0, 0.5, 200.0);
  const HerschelBulkley hb1(100.0, 0.5, 1.0, 200.0);
  for (double g : {0.0, 1e-4, 0.01, 1.0, 100.0}) CHECK(hb1.viscosity(g) == doctest::Approx(b.viscosity(g)).epsilon(1e-14));
  const HerschelBulkley hb(100.0, 2.0, 0.5, 200.0);
  const double g = 40.0;  // m g = 8000: the exponential is 0 in double
  CHECK(hb.viscosity(g) * g == doctest::Approx(2.0 * std::sqrt(g) + 100.0).epsilon(1e-14));
  CHECK(std::isfinite(hb.viscosity(0.0)));
  CHECK(hb.viscosity(0.0) == doctest::Approx(2.0 * std::sqrt(200.0) + 100.0 * 200.0).epsilon(1e-14));
}

namespace {

const char* kCase = R"([flow]
box = [0.1, 0.1, 0.1]
cell = 0.01
end_time = 0.1
[flow.paste]
law = "bingham"
density = 1843.0
yield_stress = 138.0
plastic_viscosity = 0.7
regularisation = 500.0
)";

std::string error_of(const std::string& text, const std::string& path = "case.toml") {
  return pastemix::test::input_error_of([&] {
    const Params file = Params::parse(text, path);
    read_flow_case(file.table("flow"));
    file.finish();
  });
}

using pastemix::test::replace;

struct Dir {
  fs::path path = fs::temp_directory_path() / fmt::format("pastemix_flow_bingham_{}", static_cast<long>(::getpid()));
  Dir() { fs::create_directories(path); }
  ~Dir() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

// A store cut down to the keys the reader needs (the contract with `lab reduce`).
const char* kStore = R"([paste_rheology.cw_75.solids_fraction]
value = 0.75
[paste_rheology.cw_75.yield_stress]
value = 137.97
[paste_rheology.cw_75.plastic_viscosity]
value = 0.7
[paste_rheology.cw_75.density]
value = 1843.0
)";

}  // namespace

TEST_CASE("bingham config: law = bingham reads tau_y, eta_B, m and the density") {
  const Params file = Params::parse(kCase, "case.toml");
  const FlowCase c = read_flow_case(file.table("flow"));
  file.finish();
  CHECK(c.phases.rho_paste == 1843.0);
  CHECK(c.phases.paste->shear_dependent());
  CHECK(c.phases.paste->viscosity(0.0) == doctest::Approx(0.7 + 138.0 * 500.0));
  CHECK(c.phases.paste->describe().find("m = 500 s") != std::string::npos);
}

TEST_CASE("bingham config: a missing m, a viscosity key, a negative tau_y and a typo name file, line and key") {
  CHECK(error_of(replace(kCase, "regularisation = 500.0\n", "")).find("case.toml:6: key 'law'") != std::string::npos);
  CHECK(error_of(replace(kCase, "regularisation = 500.0", "regularisation = -5.0")).find("case.toml:10: key 'regularisation'") !=
        std::string::npos);
  CHECK(error_of(replace(kCase, "plastic_viscosity = 0.7", "viscosity = 0.7")).find("case.toml:9: key 'viscosity'") !=
        std::string::npos);
  CHECK(error_of(replace(kCase, "yield_stress = 138.0", "yield_stress = -1.0")).find("case.toml:8: key 'yield_stress'") !=
        std::string::npos);
  CHECK(error_of(replace(kCase, "yield_stress = 138.0", "yield_stres = 138.0")).find("yield_stress") != std::string::npos);
  CHECK(error_of(replace(kCase, "yield_stress = 138.0", "yield_stress = nan")).find("case.toml:8: key 'yield_stress'") !=
        std::string::npos);
  CHECK(error_of(replace(kCase, "\"bingham\"", "\"casson\"")).find("case.toml:6: key 'law'") != std::string::npos);
}

TEST_CASE("bingham config: herschel_bulkley reads K and n") {
  const std::string hb = replace(replace(kCase, "\"bingham\"", "\"herschel_bulkley\""), "plastic_viscosity = 0.7",
                                 "consistency = 2.0\nflow_index = 0.5");
  const Params file = Params::parse(hb, "case.toml");
  const FlowCase c = read_flow_case(file.table("flow"));
  file.finish();
  CHECK(c.phases.paste->viscosity(40.0) * 40.0 == doctest::Approx(2.0 * std::sqrt(40.0) + 138.0).epsilon(1e-12));
}

TEST_CASE("bingham config: rheology_from takes tau_y, eta_B and the density from the store, never from both") {
  Dir d;
  d.write("parameters.toml", kStore);
  const std::string from = replace(kCase, "density = 1843.0\nyield_stress = 138.0\nplastic_viscosity = 0.7\n",
                                   "rheology_from = \"parameters.toml\"\nsolids_fraction = 0.75\n");
  const std::string path = d.write("case.toml", from);
  const FlowCase c = load_flow_case(path);
  CHECK(c.phases.rho_paste == 1843.0);
  CHECK(c.phases.paste->viscosity(0.0) == doctest::Approx(0.7 + 137.97 * 500.0));
  CHECK(error_of(replace(from, "0.75", "0.725"), path).find("no entry for solids content 0.725") != std::string::npos);
  CHECK(error_of(replace(from, "solids_fraction = 0.75\n", "solids_fraction = 0.75\ndensity = 1.0\n"), path)
            .find("key 'density': give either rheology_from or density") != std::string::npos);
  CHECK(error_of(replace(from, "parameters.toml", "nowhere.toml"), path).find("no such parameter store") != std::string::npos);
  CHECK(error_of(replace(from, "solids_fraction = 0.75\n", ""), path).find("needs solids_fraction") != std::string::npos);
}

TEST_CASE("bingham: at rest is judged on the paste's alpha-weighted RMS speed, not on the air at the interface") {
  // Four cells along a periodic x; x-face velocities 0, 0, 0.01, 0.01 m/s give cell speeds 0, 0.005, 0.01, 0.005.
  Grid g;
  g.n = {4, 1, 1};
  g.h = {0.01, 0.01, 0.01};
  for (auto& b : g.bc) b.type = BoundaryType::periodic;
  FlowSolver s(g, Phases{}, FlowSettings{});
  s.set_alpha({1.0, 0.5, 0.1, 0.0});
  s.velocity()[0] = {0.0, 0.0, 0.01, 0.01};
  // sqrt((1 x 0 + 0.5 x 0.005^2 + 0.1 x 0.01^2 + 0) / 1.6) = 3.75e-3 m/s; the fastest cell with alpha >= 1/2: 0.005.
  CHECK(paste_rms_speed(s) == doctest::Approx(3.75e-3).epsilon(1e-12));
  CHECK(paste_speed(s) == doctest::Approx(5e-3).epsilon(1e-12));
  CHECK(!at_rest(s));
  CHECK(at_rest(s, 4e-3));
  s.set_alpha({0.0, 0.0, 0.0, 0.0});
  CHECK(paste_rms_speed(s) == 0.0);  // no paste: nothing moves
}
