// SPDX-License-Identifier: MIT
#include "model/flow/rheology.h"

#include <fmt/format.h>

namespace pastemix::flow {

std::string Newtonian::describe() const { return fmt::format("Newtonian, eta = {:.6g} Pa s", eta_); }

}  // namespace pastemix::flow
