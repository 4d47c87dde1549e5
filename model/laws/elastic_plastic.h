// SPDX-License-Identifier: MIT
// Elastic-plastic spring-dashpot rolling resistance (Ai et al. 2011, model C; LIGGGHTS epsd2):
//   k_r = 2.25 k_n mu_r^2 R*^2 on the relative rotation,  |M| <= mu_r R* F_n,
//   dashpot C_r = eta_r 2 sqrt(I_r k_r), I_r = 1.4 m* R*^2, only while the spring is below its limit.
// It acts on the whole relative rotation, twist about n included (as epsd2 does): with the tangential part
// only, a sphere spinning about the vertical on a floor never stops and a pile never comes to rest.
#pragma once

#include <cmath>

#include "base/params.h"
#include "model/laws/rolling.h"
#include "model/material.h"

namespace pastemix::model {

struct ElasticPlastic {
  static constexpr const char* name = "elastic_plastic";
  struct Params {
    using Law = ElasticPlastic;
    double rolling_friction = 0.0;  // -, mu_r
    double rolling_damping = 0.0;   // -, eta_r (critical-damping ratio)
  };
  static constexpr int history_size = 3;  // the rolling spring (N.m)
  static constexpr bool needs_rotation = true;
  static constexpr bool kick_friction = false;

  // [contact] rolling_damping: eta_r, default 0.3 (Ai et al.'s choice).
  static Params from_params(const pastemix::Params& contact, const MaterialPair& pair) {
    return {pair.rolling_friction, contact.number_or("rolling_damping", 0.3, Range::non_negative)};
  }

  static Vec3 moment(const Params& p, const RollingInput& in, double* history) {
    Vec3 m{history[0], history[1], history[2]};
    const Vec3 wr = in.w_rel;
    const double kn = in.normal_stiffness;
    const double kr = 2.25 * kn * p.rolling_friction * p.rolling_friction * in.R_star * in.R_star;
    m -= wr * (kr * in.dt);
    const double m_max = p.rolling_friction * in.R_star * in.normal_force;
    const double m_len = norm(m);
    Vec3 total = m;
    if (m_len > m_max) {
      m *= m_max / m_len;
      total = m;
    } else {
      // Rolling inertia of the pair about the contact: I_r = m* R*^2 (sphere-sphere estimate, 1.4 of the
      // solid-sphere 2/5 m r^2 seen from the contact point, as LIGGGHTS epsd2 approximates).
      const double cr = p.rolling_damping * 2.0 * std::sqrt(1.4 * in.m_star * in.R_star * in.R_star * kr);
      total -= wr * cr;
    }
    history[0] = m.x;
    history[1] = m.y;
    history[2] = m.z;
    return total;
  }
};

}  // namespace pastemix::model
