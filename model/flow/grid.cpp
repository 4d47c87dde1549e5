// SPDX-License-Identifier: MIT
#include "model/flow/grid.h"

#include <stdexcept>

#include <fmt/format.h>

namespace pastemix::flow {

const char* boundary_name(BoundaryType t) {
  switch (t) {
    case BoundaryType::no_slip: return "no_slip";
    case BoundaryType::free_slip: return "free_slip";
    case BoundaryType::open: return "open";
    case BoundaryType::periodic: return "periodic";
  }
  return "?";
}

void Grid::check() const {
  for (int d = 0; d < 3; ++d) {
    if (n[d] < 1) throw std::invalid_argument(fmt::format("grid: axis {} has {} cells", d, n[d]));
    if (!(h[d] > 0.0)) throw std::invalid_argument(fmt::format("grid: axis {} has cell size {}", d, h[d]));
    const bool lo = side(d, 0).type == BoundaryType::periodic, hi = side(d, 1).type == BoundaryType::periodic;
    if (lo != hi) throw std::invalid_argument(fmt::format("grid: axis {} is periodic on one side only", d));
  }
}

std::string Grid::describe() const {
  return fmt::format("{} x {} x {} cells of {:.4g} x {:.4g} x {:.4g} m", n[0], n[1], n[2], h[0], h[1], h[2]);
}

}  // namespace pastemix::flow
