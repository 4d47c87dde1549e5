// SPDX-License-Identifier: MIT
#include "model/coupling/exchange.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "base/error.h"
#include "model/coupling/kernel.h"

namespace pastemix::coupling {

namespace {

// A face of component c on a wall (a bounded axis's end): its velocity is fixed, it takes no reaction.
bool wall_face(const flow::Grid& g, int c, long f) {
  if (g.periodic(c)) return false;
  const auto fd = g.face_dims(c);
  const long q0 = f % fd[0], q1 = (f / fd[0]) % fd[1], q2 = f / (static_cast<long>(fd[0]) * fd[1]);
  const long along = c == 0 ? q0 : (c == 1 ? q1 : q2);
  return along == 0 || along == g.n[c];
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

}  // namespace

Exchange::Exchange(const flow::Grid& g, double width_factor) : g_(g), c_(width_factor) {
  g_.check();
  if (!(width_factor >= kMinWidthFactor))
    throw std::invalid_argument(fmt::format("coupling: kernel width factor {} below its minimum {}", width_factor, kMinWidthFactor));
}

FaceWeights Exchange::face_weights(std::span<const Stencil> s) const {
  FaceWeights out;
  for (int c = 0; c < 3; ++c) out.offset[c].assign(1, 0);
  std::array<std::vector<std::pair<long, double>>, 3> acc;
  for (const Stencil& st : s) {
    for (auto& a : acc) a.clear();
    for (const auto& [k, wk] : st.axis[2])
      for (const auto& [j, wj] : st.axis[1])
        for (const auto& [ii, wi] : st.axis[0]) {
          const std::array<int, 3> q{ii, j, k};
          const double half = 0.5 * wi * wj * wk;
          for (int c = 0; c < 3; ++c) {
            std::array<int, 3> hi = q;
            hi[c] = g_.periodic(c) ? (q[c] + 1) % g_.n[c] : q[c] + 1;
            acc[c].emplace_back(g_.face(c, q), half);
            acc[c].emplace_back(g_.face(c, hi), half);
          }
        }
    for (int c = 0; c < 3; ++c) {
      std::sort(acc[c].begin(), acc[c].end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (std::size_t e = 0; e < acc[c].size(); ++e) {
        const long f = acc[c][e].first;
        double w = acc[c][e].second;
        while (e + 1 < acc[c].size() && acc[c][e + 1].first == f) w += acc[c][++e].second;
        if (wall_face(g_, c, f)) continue;
        out.face[c].push_back(f);
        out.w[c].push_back(w);
      }
      out.offset[c].push_back(out.face[c].size());
    }
  }
  return out;
}

Exchange::Rows Exchange::rows(const ExchangeParticles& p, const flow::Faces& face_mass, const flow::Faces* paste_mask,
                              std::vector<double>* share) const {
  const std::size_t n = p.centre.size();
  FaceWeights own;
  if (p.weights == nullptr) {
    std::vector<Stencil> s(n);
    for (std::size_t i = 0; i < n; ++i) s[i] = stencil(g_, p.centre[i], p.diameter[i], c_);
    own = face_weights(s);
  } else if (p.weights->size() != n) {
    throw std::invalid_argument(fmt::format("coupling exchange: face weights of {} particles for {} particles",
                                            p.weights->size(), n));
  }
  const FaceWeights& fw = p.weights != nullptr ? *p.weights : own;
  Rows out;
  if (share != nullptr) share->assign(n, 0.0);
  for (int c = 0; c < 3; ++c) {
    out[c].offset.reserve(n + 1);
    out[c].face.reserve(fw.face[c].size());
    out[c].w.reserve(fw.w[c].size());
  }
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      RowTable& r = out[c];
      const std::size_t first = r.face.size();
      double sum = 0.0, unmasked = 0.0;
      for (std::size_t e = fw.offset[c][i]; e < fw.offset[c][i + 1]; ++e) {
        const long f = fw.face[c][e];
        double w = fw.w[c][e];
        if (!(face_mass[c][f] > 0.0)) continue;
        unmasked += w;
        if (paste_mask != nullptr) {
          const double a = std::clamp((*paste_mask)[c][f], 0.0, 1.0);
          w *= a >= kMinPasteFraction ? a : 0.0;
        }
        if (w == 0.0) continue;
        r.face.push_back(f);
        r.w.push_back(w);
        sum += w;
      }
      if (sum > 0.0)
        for (std::size_t e = first; e < r.w.size(); ++e) r.w[e] /= sum;
      r.offset.push_back(r.face.size());
      if (share != nullptr && unmasked > 0.0) (*share)[i] += sum / unmasked / 3.0;
    }
  return out;
}

double Exchange::Row::at(const std::vector<double>& field) const {
  double s = 0.0;
  for (std::size_t e = 0; e < face.size(); ++e) s += w[e] * field[face[e]];
  return s;
}

void Exchange::Row::spread(double amount, std::vector<double>& field) const {
  for (std::size_t e = 0; e < face.size(); ++e) field[face[e]] += w[e] * amount;
}

void Exchange::check(const ExchangeParticles& p, const std::vector<std::array<double, 3>>& v) const {
  const std::size_t n = p.centre.size();
  if (p.diameter.size() != n || p.mass.size() != n || p.beta.size() != n || p.yield_force.size() != n || v.size() != n)
    throw std::invalid_argument("coupling exchange: particle arrays differ in length");
  for (std::size_t i = 0; i < n; ++i)
    if (!(p.mass[i] > 0.0) || !(p.beta[i] >= 0.0) || !(p.yield_force[i] >= 0.0) || !std::isfinite(p.beta[i]) ||
        !std::isfinite(p.yield_force[i]))
      throw std::invalid_argument(fmt::format("coupling exchange: particle {}: mass {} kg, beta {} kg/s, yield force {} N "
                                              "(need mass > 0, beta >= 0, yield force >= 0, finite)",
                                              i, p.mass[i], p.beta[i], p.yield_force[i]));
}

ExchangeStats Exchange::apply(double dt, const ExchangeParticles& p, std::vector<std::array<double, 3>>& v,
                              flow::Faces& u, const flow::Faces& face_mass, const flow::Faces* paste_mask,
                              std::vector<std::array<double, 3>>& impulse) const {
  check(p, v);
  const Rows W = rows(p, face_mass, paste_mask);
  ExchangeStats st;
  impulse.assign(p.centre.size(), {0.0, 0.0, 0.0});
  yield_part(dt, p, W, v, u, face_mass, impulse, st);
  for (int c = 0; c < 3; ++c) drag_part(c, dt, p, W, v, u[c], face_mass[c], impulse, st);
  return st;
}

void Exchange::hand_back(int c, const RowTable& W, const std::vector<double>& given_up,
                         const std::vector<std::array<double, 3>>& subcycle_impulse,
                         std::vector<std::array<double, 3>>& returned, ExchangeStats& st) {
  for (std::size_t i = 0; i < subcycle_impulse.size(); ++i) {
    if (subcycle_impulse[i][c] == 0.0) continue;
    const Row r = W[i];
    double back = 0.0;  // N s: particle i's part of what its faces gave up
    for (std::size_t e = 0; e < r.face.size(); ++e) back -= given_up[r.face[e]] * r.w[e] * subcycle_impulse[i][c];
    returned[i][c] = back;
    st.clipped += std::abs(back);
  }
}

ExchangeStats Exchange::react(const ExchangeParticles& p, flow::Faces& u, const flow::Faces& face_mass,
                              const flow::Faces* paste_mask, const std::vector<std::array<double, 3>>& subcycle_impulse,
                              const flow::Faces* start_mass, std::vector<std::array<double, 3>>* returned) const {
  const std::size_t n = p.centre.size();
  if (subcycle_impulse.size() != n)
    throw std::invalid_argument("coupling exchange: sub-cycle impulses and particles differ in length");
  if ((start_mass == nullptr) != (returned == nullptr))
    throw std::invalid_argument("coupling exchange: the reaction's start mass comes with the returned impulses");
  if (returned != nullptr) returned->assign(n, {0.0, 0.0, 0.0});
  const Rows W = rows(p, face_mass, paste_mask);
  ExchangeStats st;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> reaction(u[c].size(), 0.0), given_up;
    for (std::size_t i = 0; i < n; ++i) {
      if (subcycle_impulse[i][c] == 0.0) continue;
      if (W[c][i].face.empty()) st.dropped_yield += std::abs(subcycle_impulse[i][c]);
      else W[c][i].spread(-subcycle_impulse[i][c], reaction);
    }
    if (start_mass != nullptr) given_up.assign(u[c].size(), 0.0);
    bool any = false;
    for (std::size_t f = 0; f < u[c].size(); ++f) {
      if (reaction[f] == 0.0) continue;
      double take = 1.0;
      if (start_mass != nullptr && face_mass[c][f] < (*start_mass)[c][f]) {
        take = face_mass[c][f] / (*start_mass)[c][f];
        given_up[f] = 1.0 - take;
        any = true;
      }
      u[c][f] += take * reaction[f] / face_mass[c][f];
    }
    if (any) hand_back(c, W[c], given_up, subcycle_impulse, *returned, st);
  }
  return st;
}

ExchangeStats Exchange::bound_reaction(const ExchangeParticles& p, const flow::Faces& before, flow::Faces& u,
                                       const flow::Faces& face_mass, const flow::Faces* paste_mask,
                                       const std::vector<std::array<double, 3>>& subcycle_impulse,
                                       std::span<const std::array<double, 3>> velocity,
                                       std::vector<std::array<double, 3>>& returned,
                                       const flow::Faces* start_mass) const {
  const std::size_t n = p.centre.size();
  if (subcycle_impulse.size() != n || velocity.size() != n)
    throw std::invalid_argument("coupling exchange: sub-cycle impulses, velocities and particles differ in length");
  returned.assign(n, {0.0, 0.0, 0.0});
  const Rows W = rows(p, face_mass, paste_mask);
  ExchangeStats st;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> reaction(u[c].size(), 0.0), lo(before[c]), hi(before[c]);
    for (std::size_t i = 0; i < n; ++i) {
      if (subcycle_impulse[i][c] == 0.0) continue;
      const Row r = W[c][i];
      r.spread(-subcycle_impulse[i][c], reaction);
      for (long f : r.face) lo[f] = std::min(lo[f], velocity[i][c]), hi[f] = std::max(hi[f], velocity[i][c]);
    }
    std::vector<double> given_up(u[c].size(), 0.0);  // per face, the share of its reaction it gives up, [0, 1]
    bool any = false;
    for (std::size_t f = 0; f < u[c].size(); ++f) {
      const double R = reaction[f];
      if (R == 0.0) continue;
      // The excess (m/s) past the hull on the side the reaction pushed, at most the reaction's own kick.
      const double excess = R > 0.0 ? u[c][f] - hi[f] : lo[f] - u[c][f];
      if (!(excess > 0.0)) continue;
      // The kick react gave it (m/s): the share min(1, m / m_start) of its reaction with start_mass.
      const double full = std::abs(R) / face_mass[c][f];
      const double m0 = start_mass != nullptr ? (*start_mass)[c][f] : 0.0;
      const double kick = face_mass[c][f] < m0 ? full * face_mass[c][f] / m0 : full;
      // Only a face that kept most of its kick: one whose stresses passed the force on (the paste around a
      // yield-held sphere creeps at 1e-6 m/s, past a hull of ~0) is left alone.
      if (std::copysign(1.0, R) * (u[c][f] - before[c][f]) < kKeptKick * kick) continue;
      if (paste_mask != nullptr && (*paste_mask)[c][f] >= kThinPaste) continue;
      const double back = std::min(excess, kick);
      u[c][f] -= std::copysign(back, R);
      given_up[f] = back / full;
      ++st.clipped_faces;
      any = true;
    }
    if (any) hand_back(c, W[c], given_up, subcycle_impulse, returned, st);
  }
  return st;
}

ExchangeStats Exchange::correct(double dt, const ExchangeParticles& p, std::vector<std::array<double, 3>>& v,
                                flow::Faces& u, const flow::Faces& face_mass, const flow::Faces* paste_mask,
                                const std::vector<std::array<double, 3>>& reference,
                                std::vector<std::array<double, 3>>& impulse) const {
  check(p, v);
  if (reference.size() != p.centre.size())
    throw std::invalid_argument("coupling exchange: reference velocities and particles differ in length");
  const Rows W = rows(p, face_mass, paste_mask);
  ExchangeStats st;
  impulse.assign(p.centre.size(), {0.0, 0.0, 0.0});
  for (int c = 0; c < 3; ++c) drag_part(c, dt, p, W, v, u[c], face_mass[c], impulse, st, &reference);
  return st;
}

std::vector<std::array<double, 3>> Exchange::fluid_velocity(const ExchangeParticles& p, const flow::Faces& u,
                                                            const flow::Faces& face_mass, const flow::Faces* paste_mask,
                                                            std::vector<double>& paste_share) const {
  const Rows W = rows(p, face_mass, paste_mask, &paste_share);
  std::vector<std::array<double, 3>> out(p.centre.size(), {0.0, 0.0, 0.0});
  for (std::size_t i = 0; i < p.centre.size(); ++i) {
    if (W[0][i].face.empty() || W[1][i].face.empty() || W[2][i].face.empty()) {
      paste_share[i] = 0.0;
      continue;
    }
    for (int c = 0; c < 3; ++c) out[i][c] = W[c][i].at(u[c]);
  }
  return out;
}

void Exchange::yield_part(double dt, const ExchangeParticles& p, const Rows& W, std::vector<std::array<double, 3>>& v,
                          flow::Faces& u, const flow::Faces& face_mass, std::vector<std::array<double, 3>>& impulse,
                          ExchangeStats& st) {
  flow::Faces reaction;  // N s on the faces, applied after all particles: the fluid stays frozen meanwhile
  for (int c = 0; c < 3; ++c) reaction[c].assign(u[c].size(), 0.0);
  for (std::size_t i = 0; i < p.centre.size(); ++i) {
    // A particle with no paste face in its support has no yield part.
    if (p.yield_force[i] == 0.0 || W[0][i].face.empty() || W[1][i].face.empty() || W[2][i].face.empty()) continue;
    std::array<double, 3> w{};
    for (int c = 0; c < 3; ++c) w[c] = v[i][c] - W[c][i].at(u[c]);
    const double speed = std::hypot(w[0], w[1], w[2]);
    if (speed == 0.0) continue;
    const double bound = p.yield_force[i] * dt;  // N s
    const bool stick = p.mass[i] * speed <= bound;
    const double scale = stick ? p.mass[i] : bound / speed;
    st.stuck += stick ? 1 : 0;
    for (int c = 0; c < 3; ++c) {
      const double J = -scale * w[c];
      impulse[i][c] += J;
      v[i][c] += J / p.mass[i];
      W[c][i].spread(-J, reaction[c]);
    }
  }
  for (int c = 0; c < 3; ++c)
    for (std::size_t f = 0; f < u[c].size(); ++f)
      if (reaction[c][f] != 0.0) u[c][f] += reaction[c][f] / face_mass[c][f];
}

namespace {

// Jacobi-preconditioned CG for A x = b (A SPD, applied by apply_A), from the given x; returns the iterations
// and sets `rel` to ||b - A x|| / ||b|| at exit.
template <class Apply>
int conjugate_gradients(Apply&& apply_A, const std::vector<double>& b, const std::vector<double>& diag,
                        std::vector<double>& x, double tol, int max_iterations, double& rel) {
  const std::size_t F = b.size();
  std::vector<double> r(F), z(F), d(F), q(F);
  apply_A(x, q);
  for (std::size_t f = 0; f < F; ++f) r[f] = b[f] - q[f], z[f] = r[f] / diag[f], d[f] = z[f];
  const double bnorm = std::sqrt(dot(b, b));
  double rz = dot(r, z);
  rel = bnorm > 0.0 ? std::sqrt(dot(r, r)) / bnorm : 0.0;
  int it = 0;
  for (; it < max_iterations && rel > tol; ++it) {
    apply_A(d, q);
    const double a = rz / dot(d, q);
    for (std::size_t f = 0; f < F; ++f) x[f] += a * d[f], r[f] -= a * q[f], z[f] = r[f] / diag[f];
    const double rz1 = dot(r, z);
    for (std::size_t f = 0; f < F; ++f) d[f] = z[f] + (rz1 / rz) * d[f];
    rz = rz1;
    rel = std::sqrt(dot(r, r)) / bnorm;
  }
  return it;
}

}  // namespace

void Exchange::drag_part(int c, double dt, const ExchangeParticles& p, const Rows& W,
                         std::vector<std::array<double, 3>>& v, std::vector<double>& u, const std::vector<double>& M,
                         std::vector<std::array<double, 3>>& impulse, ExchangeStats& st,
                         const std::vector<std::array<double, 3>>* reference) const {
  const std::size_t n = p.centre.size(), F = u.size();
  std::vector<double> B(n);  // kg/s: beta with the particle eliminated, beta m / (m + dt beta)
  for (std::size_t i = 0; i < n; ++i) B[i] = p.beta[i] * p.mass[i] / (p.mass[i] + dt * p.beta[i]);
  auto mass_of = [&](std::size_t f) { return M[f] > 0.0 ? M[f] : 1.0; };  // faces no particle reaches
  auto apply_A = [&](const std::vector<double>& x, std::vector<double>& y) {
    for (std::size_t f = 0; f < F; ++f) y[f] = mass_of(f) * x[f];
    for (std::size_t i = 0; i < n; ++i)
      if (B[i] > 0.0) W[c][i].spread(dt * B[i] * W[c][i].at(x), y);
  };
  std::vector<double> rhs(F), diag(F), x = u;
  for (std::size_t f = 0; f < F; ++f) rhs[f] = mass_of(f) * u[f], diag[f] = mass_of(f);
  for (std::size_t i = 0; i < n; ++i) {
    if (B[i] == 0.0) continue;
    W[c][i].spread(dt * B[i] * (reference ? (*reference)[i][c] : v[i][c]), rhs);
    for (std::size_t e = 0; e < W[c][i].face.size(); ++e) diag[W[c][i].face[e]] += dt * B[i] * W[c][i].w[e] * W[c][i].w[e];
  }
  double rel = 0.0;
  const int it = conjugate_gradients(apply_A, rhs, diag, x, tolerance, max_iterations, rel);
  if (rel > tolerance)
    throw RuntimeFailure(fmt::format("coupling exchange: the implicit drag solve (component {}) did not converge: "
                                     "relative residual {:.3g} after {} iterations", c, rel, it));
  st.iterations += it;
  st.relative_residual = std::max(st.relative_residual, rel);
  // The particles' impulses decide; the faces take exactly their opposite.
  std::vector<double> reaction(F, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (B[i] == 0.0 || W[c][i].face.empty()) continue;
    const double J = dt * B[i] * (W[c][i].at(x) - (reference ? (*reference)[i][c] : v[i][c]));
    impulse[i][c] += J;
    v[i][c] += J / p.mass[i];
    W[c][i].spread(-J, reaction);
  }
  for (std::size_t f = 0; f < F; ++f)
    if (reaction[f] != 0.0) u[f] += reaction[f] / M[f];
}

}  // namespace pastemix::coupling
