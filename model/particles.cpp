// SPDX-License-Identifier: MIT
#include "model/particles.h"

#include "base/units.h"

namespace pastemix::model {

void Particles::add(int material_index, double radius_m, double density, const Vec3& position,
                    const Vec3& velocity, const Vec3& angular_velocity) {
  const double m = density * 4.0 / 3.0 * units::pi * radius_m * radius_m * radius_m;
  id.push_back(static_cast<std::int64_t>(x.size()));
  material.push_back(material_index);
  radius.push_back(radius_m);
  mass.push_back(m);
  inv_mass.push_back(1.0 / m);
  x.push_back(position);
  v.push_back(velocity);
  f.push_back({});
  if (has_rotation) {
    omega.push_back(angular_velocity);
    torque.push_back({});
    inv_inertia.push_back(1.0 / (0.4 * m * radius_m * radius_m));
    rolling_capacity.push_back(0.0);
  }
}

namespace {

// v[a] moves to map[a] (kGone: dropped); out-of-place, so any injective map works.
template <class T>
void move_to(std::vector<T>& v, const std::vector<std::uint32_t>& map, std::size_t count, std::vector<T>& scratch) {
  if (v.empty()) return;
  scratch.resize(count);
  for (std::size_t a = 0; a < map.size(); ++a)
    if (map[a] != Particles::kGone) scratch[map[a]] = v[a];
  v.swap(scratch);
}

}  // namespace

void Particles::apply_map(const std::vector<std::uint32_t>& map, std::size_t count) {
  // One scratch per element type, reused across the arrays of that type.
  std::vector<Vec3> sv;
  std::vector<double> sd;
  std::vector<int> si;
  std::vector<std::int64_t> sl;
  move_to(id, map, count, sl);
  move_to(material, map, count, si);
  move_to(radius, map, count, sd);
  move_to(mass, map, count, sd);
  move_to(inv_mass, map, count, sd);
  move_to(x, map, count, sv);
  move_to(v, map, count, sv);
  move_to(f, map, count, sv);
  move_to(omega, map, count, sv);
  move_to(torque, map, count, sv);
  move_to(inv_inertia, map, count, sd);
  move_to(rolling_capacity, map, count, sd);
}

std::vector<std::uint32_t> Particles::remove_if(const std::vector<char>& gone) {
  std::vector<std::uint32_t> map(size(), kGone);
  std::uint32_t next = 0;
  for (std::size_t a = 0; a < map.size(); ++a)
    if (!gone[a]) map[a] = next++;
  apply_map(map, next);
  return map;
}

}  // namespace pastemix::model
