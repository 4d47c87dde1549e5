// SPDX-License-Identifier: MIT
// The registered contact laws. A new law is one header in laws/ plus one entry in ContactLaws below.
//
// A law provides: `struct Params` (SI, per material pair), `from_pair(...)`, `history_width(...)`,
// `needs_torque`, and a stateless inline `force(params, geometry, history, width)`. The world selects the
// law once per step with std::visit over LawParams and runs a template loop in which force() inlines.
#pragma once

#include <concepts>
#include <string>
#include <variant>
#include <vector>

#include "model/laws/hertz_mindlin.h"

namespace pastemix::model {

template <class L>
concept ContactLaw = requires(const typename L::Params& p, const typename L::Geometry& g, double* h) {
  { L::force(p, g, h, 0) } -> std::same_as<typename L::Result>;
  { L::needs_torque } -> std::convertible_to<bool>;
};

template <ContactLaw... Laws>
struct LawList {
  // Per-material-pair parameter tables, one alternative per law.
  using Table = std::variant<std::vector<typename Laws::Params>...>;
};

using ContactLaws = LawList<HertzMindlin>;
using LawTable = ContactLaws::Table;

// Scene names of the laws, in ContactLaws order.
inline const std::vector<std::string>& contact_law_names() {
  static const std::vector<std::string> names{"hertz_mindlin"};
  return names;
}

}  // namespace pastemix::model
