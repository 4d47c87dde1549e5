// SPDX-License-Identifier: MIT
// The World's health checks (non-finite state, energy blow-ups, the domain), the outflow removal
// (on_exit = "remove") and the energies, apart from the step (model/world.cpp).
#include "model/world.h"

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "base/error.h"

namespace pastemix::model {

namespace {

bool outside(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  return !(x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z);
}

std::string left_domain(const Vec3& lo, const Vec3& hi) {
  return fmt::format("left the domain [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] m", lo.x, hi.x, lo.y,
                     hi.y, lo.z, hi.z);
}

}  // namespace

void World::remove_escaped(Motion& moved) {
  const std::size_t n = p_.size();
  const Vec3 lo = cfg_.domain_min, hi = cfg_.domain_max;
  std::vector<char> gone(n, 0);
  double total = escaped_mass_, leaving = 0.0;  // kg: every particle ever in the world; those leaving now
  std::size_t last = n;
  for (std::size_t a = 0; a < n; ++a) {
    total += p_.mass[a];
    if (!outside(p_.x[a], lo, hi)) continue;
    gone[a] = 1;
    leaving += p_.mass[a];
    last = a;
  }
  bad_index_ = -1;
  if (last == n) return;  // nothing outside (a flag without a cause cannot happen: NaN was checked)
  const double lost = escaped_mass_ + leaving;
  if (lost > cfg_.max_escaped_fraction * total)
    fail(last, fmt::format("{}; {:.6g} kg of particles have now left ({:.3g} % of {:.6g} kg), more than "
                           "[domain] max_escaped_fraction = {:g}: many escapes are a blow-up, not a splash "
                           "(time step too large for the stiffness?)",
                           left_domain(lo, hi), lost, 100.0 * lost / total, total, cfg_.max_escaped_fraction));
  for (std::size_t a = 0; a < n; ++a)
    if (gone[a])
      escaped_.push_back({p_.id[a], t_, p_.mass[a], p_.radius[a], p_.material[a], p_.x[a], p_.v[a]});
  escaped_mass_ = lost;
  const std::vector<std::uint32_t> map = p_.remove_if(gone);
  pairs_.rename(map, p_.size());
  wall_contacts_.rename(map, p_.size());
  for_each_pass(forces_, [&](auto& pass) {
    if constexpr (requires { pass.particles_removed(); })
      if (pass.active()) pass.particles_removed();
    if constexpr (requires { pass.particles_removed(map, p_.size()); })
      if (pass.active()) pass.particles_removed(map, p_.size());
  });
  rebuild_neighbors();
  moved = Motion{};
}

void World::fail(std::size_t a, const std::string& cause) const {
  const Vec3& x = p_.x[a];
  const Vec3& v = p_.v[a];
  throw RuntimeFailure(fmt::format(
      "particle id {} at t = {:.6g} s (step {}): {}; position ({:.6g}, {:.6g}, {:.6g}) m, velocity "
      "({:.6g}, {:.6g}, {:.6g}) m/s",
      p_.id[a], t_, steps_, cause, x.x, x.y, x.z, v.x, v.y, v.z));
}

void World::check_particles(bool domain) const {
  const std::size_t n = p_.size();
  const Vec3 lo = cfg_.domain_min, hi = cfg_.domain_max;
  for (std::size_t a = 0; a < n; ++a) {
    const Vec3& x = p_.x[a];
    const Vec3& v = p_.v[a];
    if (!std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z)) fail(a, "non-finite position or velocity (NaN/inf)");
    if (p_.has_rotation && !std::isfinite(p_.omega[a].x + p_.omega[a].y + p_.omega[a].z))
      fail(a, "non-finite angular velocity");
    if (domain && outside(x, lo, hi)) fail(a, left_domain(lo, hi));
  }
  if (cfg_.kinetic_limit > 0.0) {
    double ke = 0.0, ke_max = -1.0;
    std::size_t worst = 0;
    for (std::size_t a = 0; a < n; ++a) {
      const double e = 0.5 * p_.mass[a] * norm2(p_.v[a]);
      ke += e;
      if (e > ke_max) {
        ke_max = e;
        worst = a;
      }
    }
    if (ke > cfg_.kinetic_limit)
      fail(worst, fmt::format("kinetic-energy blow-up: total {:.6g} J exceeds the limit {:.6g} J (the "
                              "initial energy plus the largest fall in the domain); time step too large for "
                              "the stiffness?",
                              ke, cfg_.kinetic_limit));
  }
}

Energies World::energies() const {
  Energies e;
  const std::size_t n = p_.size();
  for (std::size_t a = 0; a < n; ++a) {
    e.kinetic += 0.5 * p_.mass[a] * norm2(p_.v[a]);
    if (p_.has_rotation) e.rotational += 0.5 * norm2(p_.omega[a]) / p_.inv_inertia[a];
    e.potential -= p_.mass[a] * dot(cfg_.gravity, p_.x[a]);
  }
  const std::size_t nm = materials_.size();
  // The contact law's normal-spring energy (its tangential spring excluded).
  std::visit(
      [&](const auto& table) {
        using Law = LawOf<decltype(table)>;
        auto pair_of = [&](int ma, int mb) -> const auto& { return table[static_cast<std::size_t>(ma) * nm + mb]; };
        for (std::size_t k = 0; k < pairs_.size(); ++k) {
          const auto a = pairs_.i[k], b = pairs_.j[k];
          const double rsum = p_.radius[a] + p_.radius[b];
          const double d = rsum - norm(p_.x[b] - p_.x[a]);
          if (d <= 0.0) continue;
          ++e.pair_contacts;
          const double rs = p_.radius[a] * p_.radius[b] / rsum;
          e.elastic += Law::elastic_energy(pair_of(p_.material[a], p_.material[b]), rs, d);
        }
        for (std::size_t a = 0; a < n; ++a)
          for (const Wall& w : walls_) {
            if (!w.active(t_)) continue;
            Vec3 nn;
            const double d = p_.radius[a] - wall_distance(w, w.displacement(t_), p_.x[a], &nn);
            if (d <= 0.0) continue;
            ++e.wall_contacts;
            e.elastic += Law::elastic_energy(pair_of(p_.material[a], w.material), p_.radius[a], d);
          }
      },
      laws_);
  return e;
}

}  // namespace pastemix::model
