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

// Keeps the entries whose new index is not kGone (new indices ascend with the old ones: in place).
template <class T>
void compact(std::vector<T>& v, const std::vector<std::uint32_t>& map) {
  if (v.empty()) return;
  std::size_t out = 0;
  for (std::size_t a = 0; a < map.size(); ++a)
    if (map[a] != Particles::kGone) v[out++] = v[a];
  v.resize(out);
}

}  // namespace

std::vector<std::uint32_t> Particles::remove_if(const std::vector<char>& gone) {
  std::vector<std::uint32_t> map(size(), kGone);
  std::uint32_t next = 0;
  for (std::size_t a = 0; a < map.size(); ++a)
    if (!gone[a]) map[a] = next++;
  compact(id, map);
  compact(material, map);
  compact(radius, map);
  compact(mass, map);
  compact(inv_mass, map);
  compact(x, map);
  compact(v, map);
  compact(f, map);
  compact(omega, map);
  compact(torque, map);
  compact(inv_inertia, map);
  compact(rolling_capacity, map);
  return map;
}

}  // namespace pastemix::model
