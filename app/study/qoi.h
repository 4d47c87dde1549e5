// SPDX-License-Identifier: MIT
// Quantities of interest for `pastemix sweep`: each is one function of the World, taken either as its
// maximum over all steps or at the end of the run. The registry (qoi.cpp) has one line per QoI.
#pragma once

#include <string>
#include <vector>

#include "model/scene.h"

namespace pastemix::app::study {

struct QoiDef {
  std::string name, unit, what;
  bool max_over_steps = false;  // true: max over every step; false: evaluated once at the end
  double (*eval)(const model::World&) = nullptr;
};

const std::vector<QoiDef>& qoi_registry();
// Throws InputError (field "--qoi") listing the names when unknown.
const QoiDef& find_qoi(const std::string& name);

}  // namespace pastemix::app::study
