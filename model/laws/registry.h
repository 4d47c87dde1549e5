// SPDX-License-Identifier: MIT
// The registered laws: a new contact or rolling law is one header in laws/ plus one entry below. Scene
// names come from the laws themselves (`name`); the scene, the contact loop and the diagnostics reach a law
// only through these lists (std::visit over the tables, then template loops in which the kernels inline).
//
// A contact law provides: `name`; `struct Params` (SI, per material pair, `using Law = ...`);
// `from_params(contact, pair)` (its keys and defaults); `history_size`, `history_width(tangential)`,
// `needs_history(params)`; `needs_torque`; `elastic_energy(params, R*, overlap)`; a stateless inline
// `force(params, geometry, history, width)`; optionally a batch kernel (`Batch`, `kBatch`, `load_params`,
// `force_batch`) with the scalar kernel's bits. A rolling law: see laws/rolling.h. A drag law (the force of a
// fluid at rest on a sphere): see laws/drag_law.h.
#pragma once

#include <concepts>

#include "model/laws/bingham_dedegil.h"
#include "model/laws/constant_torque.h"
#include "model/laws/constant_torque_rstar.h"
#include "model/laws/elastic_plastic.h"
#include "model/laws/drag_law.h"
#include "model/laws/hertz_mindlin.h"
#include "model/laws/herschel_bulkley.h"
#include "model/laws/law_list.h"
#include "model/laws/newtonian_stokes.h"
#include "model/laws/no_rolling.h"
#include "model/laws/rolling.h"

namespace pastemix::model {

template <class L>
concept ContactLaw = requires(const typename L::Params& p, const typename L::Geometry& g, double* h) {
  { L::name } -> std::convertible_to<const char*>;
  { L::force(p, g, h, 0) } -> std::same_as<typename L::Result>;
  { L::needs_torque } -> std::convertible_to<bool>;
  { L::history_size } -> std::convertible_to<int>;
  { L::elastic_energy(p, 1.0, 1.0) } -> std::convertible_to<double>;
};

template <ContactLaw... Laws>
using ContactLawList = LawList<Laws...>;
template <RollingLaw... Laws>
using RollingLawList = LawList<Laws...>;
template <DragLaw... Laws>
using DragLawList = LawList<Laws...>;

using ContactLaws = ContactLawList<HertzMindlin>;
using RollingLaws = RollingLawList<NoRolling, ConstantTorque, ElasticPlastic, ConstantTorqueRstar>;

using DragLaws = DragLawList<NewtonianStokes, BinghamDedegil, HerschelBulkley>;

using LawTable = ContactLaws::Table;
using DragParams = DragLaws::One;  // a fluid region's drag law and its values
using RollingTable = RollingLaws::Table;

// Doubles per contact at most: a contact law's slots, then a rolling law's.
inline constexpr int kMaxHistory = ContactLaws::max_history() + RollingLaws::max_history();

}  // namespace pastemix::model
