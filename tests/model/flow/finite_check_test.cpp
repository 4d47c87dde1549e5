// SPDX-License-Identifier: MIT
// The step's guard against non-finite values (model/flow/finite_check.h): a NaN, an infinity or a density of
// zero stops the run at the stage that made it, naming the array, the cell or face and the time.
#include "model/flow/finite_check.h"

#include <doctest/doctest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "base/error.h"
#include "model/flow/solver.h"
#include "tests/input_error.h"
#include "tests/model/flow/flow_fixture.h"

using namespace pastemix;
using namespace pastemix::flow;

namespace {

Grid box() { return pastemix::test::cube_box({5, 4, 6}, 0.01, true); }

using pastemix::test::runtime_failure_of;

// A law that turns non-finite above a strain rate: stands for a viscosity formula evaluated out of its range.
class BrokenAbove final : public Rheology {
 public:
  explicit BrokenAbove(double gamma) : gamma_(gamma) {}
  double viscosity(double g) const override { return g > gamma_ ? std::numeric_limits<double>::quiet_NaN() : 0.5; }
  bool shear_dependent() const override { return true; }
  std::string describe() const override { return "NaN above a strain rate"; }

 private:
  double gamma_;
};

}  // namespace

TEST_CASE("finite check: the first bad cell or face is named with its (i, j, k), the stage and the time") {
  const Grid g = box();
  std::vector<double> v(g.cell_count(), 1.0);
  const CheckPoint at{"after advection", 0.25, 17};
  CHECK_NOTHROW(require_finite_cells(g, v, "paste fraction", at));
  v[g.cell(2, 1, 3)] = std::nan("");
  v[g.cell(4, 3, 5)] = std::nan("");  // after the first: not the one named
  const std::string m = runtime_failure_of([&] { require_finite_cells(g, v, "paste fraction", at); });
  CHECK(m.find("paste fraction non-finite: nan at cell (2, 1, 3), after advection") != std::string::npos);
  CHECK(m.find("t = 0.25 s (step 17)") != std::string::npos);
  v.assign(v.size(), 1.0);
  v[g.cell(0, 2, 1)] = 0.0;
  CHECK_NOTHROW(require_finite_cells(g, v, "viscosity", at));  // zero is finite
  CHECK(runtime_failure_of([&] { require_finite_cells(g, v, "viscosity", at, true); })
            .find("viscosity not positive: 0 at cell (0, 2, 1)") != std::string::npos);
  Faces u;
  for (int c = 0; c < 3; ++c) u[c].assign(g.face_count(c), 0.0);
  u[1][g.face(1, {1, 4, 2})] = -std::numeric_limits<double>::infinity();
  CHECK(runtime_failure_of([&] { require_finite_faces(g, u, "velocity", at); }).find("velocity non-finite: -inf at y face (1, 4, 2)") !=
        std::string::npos);
}

TEST_CASE("finite check: the solver stops at the stage that made the bad value") {
  omp_set_num_threads(1);
  const Grid g = box();
  SUBCASE("a NaN velocity given to the step") {
    FlowSolver s(g, Phases{}, FlowSettings{});
    s.add_paste_box({0, 0, 0}, {0.05, 0.04, 0.03});
    s.step(1e-3);
    s.velocity()[0][g.face(0, {2, 1, 3})] = std::nan("");
    const std::string m = runtime_failure_of([&] { s.step(1e-3); });
    CHECK(m.find("velocity non-finite: nan at x face (2, 1, 3), on entry to the step, in the step from t = 0.001 s "
                 "(step 1)") != std::string::npos);
  }
  SUBCASE("a face density of zero (an air density of 0 in an empty cell)") {
    Phases ph;
    ph.rho_air = 0.0;
    FlowSolver s(g, ph, FlowSettings{});
    s.add_paste_box({0, 0, 0}, {0.05, 0.04, 0.02});
    CHECK(runtime_failure_of([&] { s.step(1e-3); }).find("face density not positive: 0 at x face (0, 0, 2), after the face densities") !=
          std::string::npos);
  }
  SUBCASE("a law that returns NaN once the paste shears") {
    Phases ph;
    ph.paste = std::make_shared<BrokenAbove>(1e-3);
    FlowSolver s(g, ph, FlowSettings{});
    s.add_paste_box({0, 0, 0}, {0.02, 0.04, 0.06});  // a column that collapses
    std::string m;
    for (int i = 0; i < 20 && m.empty(); ++i) m = runtime_failure_of([&] { s.step(1e-3); });
    // The lagged strain rate is zero in the first step, so the first bad viscosity comes after a step of flow.
    CHECK(m.find("viscosity non-finite: nan at cell (") != std::string::npos);
    CHECK(m.find(", after the viscosities, in the step from t = 0.001 s (step 1)") != std::string::npos);
  }
}
