// SPDX-License-Identifier: MIT
// [[material]], [[interaction]], which materials can touch, and the Plan the laws make of them.
#include <array>

#include <fmt/format.h>

#include "base/error.h"
#include "model/scene/read.h"

namespace pastemix::model {

std::vector<int> read_materials(const Params& root, std::vector<Material>& out) {
  std::vector<int> line;
  for (const Params& m : root.tables("material")) {
    Material mat;
    mat.name = m.string("name");
    for (const auto& other : out)
      if (other.name == mat.name) m.fail("name", fmt::format("material '{}' is defined twice", mat.name));
    mat.density = m.number("density", Range::positive);
    mat.youngs_modulus = m.number("youngs_modulus", Range::positive);
    mat.poisson_ratio = m.number("poisson_ratio", Range::non_negative);
    if (mat.poisson_ratio >= 0.5) m.fail("poisson_ratio", "expected a value in [0, 0.5)");
    out.push_back(mat);
    line.push_back(m.line());
  }
  if (out.empty()) root.fail("material", "a scene needs at least one [[material]]");
  return line;
}

namespace {

// The two material indices of "a/b".
std::array<int, 2> pair_of(const Params& it, const std::vector<Material>& mats) {
  const std::string names = it.string("materials");
  const auto slash = names.find('/');
  if (slash == std::string::npos) it.fail("materials", "expected \"a/b\" (two material names)");
  const std::string part[2] = {names.substr(0, slash), names.substr(slash + 1)};
  std::array<int, 2> idx{-1, -1};
  for (int q = 0; q < 2; ++q) {
    for (std::size_t k = 0; k < mats.size(); ++k)
      if (mats[k].name == part[q]) idx[static_cast<std::size_t>(q)] = static_cast<int>(k);
    if (idx[static_cast<std::size_t>(q)] < 0) it.fail("materials", fmt::format("material '{}' is not defined", part[q]));
  }
  return idx;
}

}  // namespace

void read_interactions(const Params& root, Scene& s) {
  const std::size_t nm = s.materials.size();
  s.pairs.assign(nm * nm, MaterialPair{});
  for (const Params& it : root.tables("interaction")) {
    const auto idx = pair_of(it, s.materials);
    MaterialPair mp;
    mp.restitution = it.number("restitution", Range::positive);
    if (mp.restitution > 1.0) it.fail("restitution", "expected a value in (0, 1]");
    mp.friction = it.number_or("friction", 0.0, Range::non_negative);
    mp.rolling_friction = it.number_or("rolling_friction", 0.0, Range::non_negative);
    for (auto [a, b] : {std::pair{idx[0], idx[1]}, std::pair{idx[1], idx[0]}}) {
      MaterialPair q = mp;
      q.a = &s.materials[static_cast<std::size_t>(a)];
      q.b = &s.materials[static_cast<std::size_t>(b)];
      s.pairs[static_cast<std::size_t>(a) * nm + static_cast<std::size_t>(b)] = q;
    }
  }
}

ParticleSources read_particle_sources(const Params& root, const Scene& s) {
  ParticleSources src;
  src.initial = root.optional_table("initial_state");
  if (src.initial)  // an earlier run's snapshot (a settled bed) brings its own particle materials
    for (int m : initial_state_materials(*src.initial, s.path, s.materials)) src.materials.insert(m);
  src.particles = root.tables("particle");
  src.factories = root.tables("factory");
  for (const Params& p : src.particles) src.particle_material.push_back(material_index(p, "material", s.materials));
  for (const Params& f : src.factories) src.factory_material.push_back(material_index(f, "material", s.materials));
  for (int m : src.particle_material) src.materials.insert(m);
  for (int m : src.factory_material) src.materials.insert(m);
  if (src.materials.empty()) root.fail("particle", "the scene has no [[particle]], [[factory]] or [initial_state]");
  return src;
}

void require_interactions(const Scene& s, const std::set<int>& particle_materials,
                          const std::vector<int>& material_line) {
  const std::size_t nm = s.materials.size();
  auto require_pair = [&](int a, int b, const std::string& what) {
    if (!s.pairs[static_cast<std::size_t>(a) * nm + static_cast<std::size_t>(b)].a)
      throw InputError(s.path, material_line[static_cast<std::size_t>(a)], "interaction",
                       fmt::format("no [[interaction]] for materials '{}/{}' ({}): add one with restitution, "
                                   "friction and rolling_friction",
                                   s.materials[static_cast<std::size_t>(a)].name,
                                   s.materials[static_cast<std::size_t>(b)].name, what));
  };
  for (int a : particle_materials)
    for (int b : particle_materials) require_pair(a, b, "particles of both can touch");
  for (const Wall& w : s.walls)
    for (int a : particle_materials) require_pair(a, w.material, fmt::format("particles touch wall '{}'", w.name));
}

// Which arrays and passes: the laws mix each pair's coefficients (and read their own [contact] keys).
void plan_laws(const Params& contact, bool rotation_switch, const std::set<int>& particle_materials, Scene& s) {
  const std::size_t nm = s.materials.size();
  s.laws = ContactLaws::table_of(s.plan.law);
  s.rolling = RollingLaws::table_of(s.plan.rolling);
  std::visit(
      [&](auto& table, auto& rolling) {
        using Law = LawOf<decltype(table)>;
        using Roll = LawOf<decltype(rolling)>;
        table.resize(nm * nm);
        rolling.resize(nm * nm);
        for (std::size_t k = 0; k < nm * nm; ++k)
          if (s.pairs[k].a) table[k] = Law::from_params(contact, s.pairs[k]), rolling[k] = Roll::from_params(contact, s.pairs[k]);
        s.plan.tangential = false;
        for (int a : particle_materials)
          for (std::size_t b = 0; b < nm; ++b)
            if (s.pairs[static_cast<std::size_t>(a) * nm + b].a)
              s.plan.tangential = s.plan.tangential || Law::needs_history(table[static_cast<std::size_t>(a) * nm + b]);
        if (Roll::needs_rotation && !rotation_switch)
          contact.fail("rolling", "rolling resistance needs rotation: set [physics] rotation = true");
        s.plan.rotation = rotation_switch && (s.plan.tangential || Roll::needs_rotation);
        // A rolling spring's slots follow the contact law's (kept even without friction: one layout).
        s.plan.history_width =
            Roll::history_size > 0 ? Law::history_size + Roll::history_size : Law::history_width(s.plan.tangential);
      },
      s.laws, s.rolling);
}

}  // namespace pastemix::model
