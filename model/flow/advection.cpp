// SPDX-License-Identifier: MIT
#include "model/flow/advection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "model/flow/plic.h"

namespace pastemix::flow {

namespace {

// Fractions this close to 0 or 1 are empty or full for the reconstruction (no plane is fitted).
constexpr double kFull = 1e-12;

double clamp01(double a) { return std::clamp(a, 0.0, 1.0); }

// Youngs normal in unit-cell coordinates: minus the alpha gradient by 1-2-1 weighted central differences
// over the 3 x 3 neighbours across each axis (one cell of index = one unit, so anisotropic cells need no
// rescaling here).
std::array<double, 3> youngs_normal(const Grid& g, const std::vector<double>& alpha, const std::array<int, 3>& q) {
  std::array<double, 3> n{};
  for (int d = 0; d < 3; ++d) {
    const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;
    double sum = 0.0;
    for (int s1 = -1; s1 <= 1; ++s1)
      for (int s2 = -1; s2 <= 1; ++s2) {
        const double w = (s1 == 0 ? 2.0 : 1.0) * (s2 == 0 ? 2.0 : 1.0);
        std::array<int, 3> p = q, m = q;
        p[e1] = m[e1] = g.clamp_cell(e1, q[e1] + s1);
        p[e2] = m[e2] = g.clamp_cell(e2, q[e2] + s2);
        p[d] = g.clamp_cell(d, q[d] + 1);
        m[d] = g.clamp_cell(d, q[d] - 1);
        sum += w * (clamp01(alpha[g.cell(p)]) - clamp01(alpha[g.cell(m)]));
      }
    n[d] = -sum / 32.0;
  }
  return n;
}

// Paste volume (fraction of the donor cell's volume) leaving the donor through its face along d when the
// CFL number of the fluid's volume flux there is v (v > 0: through its high face; v < 0: its low face).
// The donor's fluid fills eps (its fluid fraction, 1 without particles) of the cell, alpha of it paste, and
// the fluid leaving is the strip of its own volume of width |v| / eps next to that face ([1 - w, 1] or
// [0, w]; w <= 1: at most all of it), so the paste leaving is eps times what that strip of the reconstructed
// cell holds. (Cut as if the fluid filled the cell, width |v|, a partly full donor lost up to 1 / eps times
// the paste it had: alpha went to -0.20 and 1.21 in tests/model/flow/advection_test.cpp.) A full donor gives
// |v| exactly, an empty one 0; with eps = 1 every product below is the plain transport's, bit for bit.
double donor_flux(const Grid& g, const std::vector<double>& alpha, const std::array<int, 3>& donor, int d, double v,
                  double eps) {
  const double a = alpha[g.cell(donor)];
  const double s = std::abs(v);
  if (a <= kFull) return 0.0;
  if (a >= 1.0 - kFull) return s;
  const double w = std::min(1.0, s / eps);
  const std::array<double, 3> n = youngs_normal(g, alpha, donor);
  if (std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]) < 1e-14) return eps * a * w;
  const double c = plic::plane_constant(n, a);
  std::array<double, 3> lo{0.0, 0.0, 0.0}, hi{1.0, 1.0, 1.0};
  if (v > 0.0) lo[d] = 1.0 - w; else hi[d] = w;
  return eps * plic::box_fraction(n, c, lo, hi);
}

// Koren-limited value at a control-volume face, for the flow from `up` towards `down` (`far` is upstream of `up`).
double limited(double far, double up, double down) {
  const double dd = down - up;
  if (dd == 0.0) return up;
  const double r = (up - far) / dd;
  const double phi = std::max(0.0, std::min({2.0 * r, (1.0 + 2.0 * r) / 3.0, 2.0}));
  return up + 0.5 * phi * dd;
}

template <class F>
void for_faces(const Grid& g, int c, F&& f) {
  const auto fd = g.face_dims(c);
#pragma omp parallel for schedule(static)
  for (int k = 0; k < fd[2]; ++k)
    for (int j = 0; j < fd[1]; ++j)
      for (int i = 0; i < fd[0]; ++i) f(std::array<int, 3>{i, j, k});
}

template <class F>
void for_cells(const Grid& g, F&& f) {
#pragma omp parallel for schedule(static)
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) f(std::array<int, 3>{i, j, k});
}

struct Sweep {
  std::vector<double> V, F, M;  // on the d-faces: CFL number, paste flux (cell fractions), mass flux (kg/m3)
};

// The fluxes of one sweep along d, from the current alpha and the frozen velocity u0.
// eps_cell: the cells' fluid fractions at the step's start (nullptr: no particles, every cell's fluid fills it).
Sweep sweep_fluxes(const Grid& g, const Phases& ph, double dt, int d, const std::vector<double>& alpha,
                   const Faces& u0, const std::vector<double>* eps_cell) {
  Sweep s;
  const long nf = g.face_count(d);
  s.V.assign(nf, 0.0);
  s.F.assign(nf, 0.0);
  s.M.assign(nf, 0.0);
  for_faces(g, d, [&](const std::array<int, 3>& q) {
    const long f = g.face(d, q);
    const double v = u0[d][f] * dt / g.h[d];
    if (v == 0.0) return;
    std::array<int, 3> donor = q;
    if (v > 0.0) {
      donor[d] = g.wrap_cell(d, q[d] - 1);
    } else {
      donor[d] = g.wrap_cell(d, q[d]);
    }
    double flux = 0.0;  // inflow through an open side brings air
    if (donor[d] >= 0)
      flux = donor_flux(g, alpha, donor, d, v, eps_cell != nullptr ? (*eps_cell)[g.cell(donor)] : 1.0);
    s.V[f] = v;
    s.F[f] = v > 0.0 ? flux : -flux;
    s.M[f] = ph.rho_air * v + (ph.rho_paste - ph.rho_air) * s.F[f];
  });
  return s;
}

}  // namespace

namespace {

// Face values of a cell quantity value(cell index): the mean of the face's two cells; a boundary face takes its
// one cell's. The one averaging rule of the densities and of the fluid fraction.
template <class CellValue>
Faces face_mean_of(const Grid& g, CellValue value) {
  Faces out;
  for (int c = 0; c < 3; ++c) {
    out[c].assign(g.face_count(c), 0.0);
    for_faces(g, c, [&](const std::array<int, 3>& q) {
      std::array<int, 3> a = q, b = q;
      a[c] = g.wrap_cell(c, q[c] - 1);
      b[c] = g.wrap_cell(c, q[c]);
      double sum = 0.0;
      int count = 0;
      if (a[c] >= 0) sum += value(g.cell(a)), ++count;
      if (b[c] >= 0) sum += value(g.cell(b)), ++count;
      out[c][g.face(c, q)] = sum / count;
    });
  }
  return out;
}

}  // namespace

Faces face_densities(const Grid& g, const Phases& ph, const std::vector<double>& alpha) {
  return face_mean_of(g, [&](long cell) { return ph.density(clamp01(alpha[cell])); });
}

Faces face_means(const Grid& g, const std::vector<double>& cells) {
  return face_mean_of(g, [&](long cell) { return cells[cell]; });
}

AdvectionStats advect(const Grid& g, const Phases& ph, double dt, long step, std::vector<double>& alpha, Faces& u,
                      const FaceMask* blocked_faces, const FluidFractionStep* eps) {
  const Faces u0 = u;
  // A wall inside the box: its faces keep their velocity (0: no flux through them) as the box's walls do.
  const FaceMask none;
  const FaceMask& wall = blocked_faces ? *blocked_faces : none;
  auto fixed = [&](int c, const std::array<int, 3>& q) {
    return g.boundary_face(c, q[c]) || blocked(wall, c, g.face(c, q));
  };
  // The advecting velocity: u itself, or the fluid's volume flux eps_f u with particles in the cells.
  Faces flux_velocity;
  Faces eps_old_face;
  if (eps != nullptr) {
    eps_old_face = face_means(g, *eps->old_cell);
    for (int c = 0; c < 3; ++c) {
      flux_velocity[c].resize(u0[c].size());
      for (std::size_t f = 0; f < u0[c].size(); ++f) flux_velocity[c][f] = (*eps->new_face)[c][f] * u0[c][f];
    }
  }
  const Faces& adv = eps != nullptr ? flux_velocity : u0;
  std::vector<double> dilatation(eps != nullptr ? alpha.size() : 0, 0.0);  // sum over the sweeps of div_d(eps u) dt
  // With particles, the momentum's dilatation terms too (kg/m3 m/s per face, summed over the sweeps), and the
  // faces whose control volume held both phases in some sweep (their velocity keeps the bounded value).
  Faces dilatation_momentum;
  std::array<std::vector<unsigned char>, 3> mixed_face;
  if (eps != nullptr)
    for (int c = 0; c < 3; ++c) dilatation_momentum[c].assign(u0[c].size(), 0.0), mixed_face[c].assign(u0[c].size(), 0);
  AdvectionStats st;
  for (int d = 0; d < 3; ++d)
    for (double v : adv[d]) st.max_cfl = std::max(st.max_cfl, std::abs(v) * dt / g.h[d]);
  if (st.max_cfl > kMaxSweepCfl)
    throw std::logic_error("flow advection: CFL above 1/2 per sweep (the step size is chosen wrongly)");

  // c of Weymouth & Yue, frozen over the step; rho(c) and rho(c) u0 are the dilatation terms' densities.
  std::vector<double> cflag(alpha.size());
  for (std::size_t i = 0; i < alpha.size(); ++i) cflag[i] = alpha[i] > 0.5 ? 1.0 : 0.0;
  Faces rho = face_densities(g, ph, alpha), rho_c = face_densities(g, ph, cflag), mom, mom_c;
  for (int c = 0; c < 3; ++c) {
    mom[c].resize(rho[c].size());
    mom_c[c].resize(rho[c].size());
    for (std::size_t f = 0; f < rho[c].size(); ++f) {
      if (eps != nullptr) rho[c][f] *= eps_old_face[c][f];  // the fluid's mass in the control volume
      mom[c][f] = rho[c][f] * u0[c][f];
      mom_c[c][f] = rho_c[c][f] * u0[c][f];
    }
  }

  const int order = static_cast<int>(step % 3);
  for (int sweep = 0; sweep < 3; ++sweep) {
    const int d = (order + sweep) % 3;
    const Sweep s = sweep_fluxes(g, ph, dt, d, alpha, adv, eps != nullptr ? eps->old_cell : nullptr);

    std::vector<double> next(alpha.size());
    for_cells(g, [&](const std::array<int, 3>& q) {
      std::array<int, 3> lo = q, hi = q;
      hi[d] = g.periodic(d) ? (q[d] + 1) % g.n[d] : q[d] + 1;
      const long fl = g.face(d, lo), fh = g.face(d, hi), ic = g.cell(q);
      if (eps == nullptr) {
        next[ic] = alpha[ic] - (s.F[fh] - s.F[fl]) + cflag[ic] * (s.V[fh] - s.V[fl]);
        return;
      }
      // In units of the cell's fluid at the start (alpha = eps_old alpha / eps_old): a full cell stays full.
      next[ic] = alpha[ic] + (cflag[ic] * (s.V[fh] - s.V[fl]) - (s.F[fh] - s.F[fl])) / (*eps->old_cell)[ic];
      dilatation[ic] += s.V[fh] - s.V[fl];
    });

    for (int c = 0; c < 3; ++c) {
      std::vector<double> mom_next = mom[c], rho_next = rho[c];
      const std::vector<double>& uc = u[c];
      // A control volume holding both phases gets the mass fluxes of its two neighbouring cell faces averaged
      // onto its own faces, and those need not match its content: an air control volume next to the paste
      // can receive and give paste-laden fluxes at different face velocities, leaving a momentum / density
      // ratio far outside the velocities it was built from (measured: air faces kicked by ~1 m/s per step,
      // whatever the step, up to 1000 m/s at density ratio 8300). Transport creates no new extrema, so there
      // the new velocity is bounded by the old ones it depends on (the face and its two neighbours along d,
      // CFL <= 1/2) and the momentum set to match. Single-phase volumes are never touched (the cavity).
      // With particles the paste fraction of a full cell carries the continuity residual (~1e-10: its fluid is
      // eps_f,end, the transported paste eps_old alpha - div(eps_f alpha u) dt), so "both phases" starts at a
      // millionth of either: below that the bound is not needed and the momentum stays conservative.
      const double pure = eps != nullptr ? 1e-6 : 1e-12;
      auto mixed = [&ph, pure](double r) {
        const double lo = std::min(ph.rho_air, ph.rho_paste), hi = std::max(ph.rho_air, ph.rho_paste);
        return r > lo * (1.0 + pure) && r < hi * (1.0 - pure);
      };
      auto bound = [](double& m, double r, double a, double b, double c3) {
        if (!(r > 0.0)) return;
        const double v = std::clamp(m / r, std::min({a, b, c3}), std::max({a, b, c3}));
        m = r * v;
      };
      for_faces(g, c, [&](const std::array<int, 3>& q) {
        if (fixed(c, q)) return;
        const int p = q[d];
        // The control volume's two faces along d and their fluxes.
        double Mh, Vh, Ml, Vl;
        if (d == c) {
          auto at = [&](int i) { std::array<int, 3> r = q; r[d] = g.clamp_face(d, d, i); return g.face(d, r); };
          Mh = 0.5 * (s.M[at(p)] + s.M[at(p + 1)]);
          Vh = 0.5 * (s.V[at(p)] + s.V[at(p + 1)]);
          Ml = 0.5 * (s.M[at(p - 1)] + s.M[at(p)]);
          Vl = 0.5 * (s.V[at(p - 1)] + s.V[at(p)]);
        } else {
          auto at = [&](int cell_c, int face_d) {
            std::array<int, 3> r = q;
            r[c] = g.wrap_cell(c, cell_c);
            r[d] = g.periodic(d) ? ((face_d % g.n[d]) + g.n[d]) % g.n[d] : face_d;
            return g.face(d, r);
          };
          const long ah = at(q[c] - 1, p + 1), bh = at(q[c], p + 1), al = at(q[c] - 1, p), bl = at(q[c], p);
          Mh = 0.5 * (s.M[ah] + s.M[bh]);
          Vh = 0.5 * (s.V[ah] + s.V[bh]);
          Ml = 0.5 * (s.M[al] + s.M[bl]);
          Vl = 0.5 * (s.V[al] + s.V[bl]);
        }
        auto U = [&](int off) { std::array<int, 3> r = q; r[d] = g.clamp_face(c, d, p + off); return uc[g.face(c, r)]; };
        const double uh = Vh > 0.0 ? limited(U(-1), U(0), U(1)) : limited(U(2), U(1), U(0));
        const double ul = Vl > 0.0 ? limited(U(-2), U(-1), U(0)) : limited(U(1), U(0), U(-1));
        const long f = g.face(c, q);
        mom_next[f] = mom[c][f] - (Mh * uh - Ml * ul) + mom_c[c][f] * (Vh - Vl);
        rho_next[f] = rho[c][f] - (Mh - Ml) + rho_c[c][f] * (Vh - Vl);
        // Mixed in the phases, not in the fluid fraction (with particles rho is eps_f rho_f).
        const double e = eps != nullptr ? eps_old_face[c][f] : 1.0;
        const bool two_phase = mixed(rho[c][f] / e) || mixed(rho_next[f] / e);
        if (two_phase) bound(mom_next[f], rho_next[f], U(-1), U(0), U(1));
        if (eps != nullptr) {
          dilatation_momentum[c][f] += mom_c[c][f] * (Vh - Vl);
          if (two_phase) mixed_face[c][f] = 1;
        }
      });
      mom[c].swap(mom_next);
      rho[c].swap(rho_next);
      for (std::size_t f = 0; f < u[c].size(); ++f)
        if (rho[c][f] > 0.0) u[c][f] = mom[c][f] / rho[c][f];
    }
    alpha.swap(next);
  }
  // With particles: the sweeps' dilatation terms are taken back, so each cell's paste changes only by its
  // fluxes (the sum telescopes), and the cell's fluid changes by -div(eps u) dt = eps_new - eps_old: a full
  // cell ends full, eps_old - div(eps u) dt = eps_new, to the continuity residual.
  // The momentum likewise: a single-phase control volume ends with its old momentum minus what crossed its faces
  // (the sum over the faces telescopes: the fluid's momentum is kept to round-off, the particles' moving
  // eps_f notwithstanding; the dilatation terms alone would add rho u div(eps_f u) dt), over the fluid's mass at
  // the end, eps_f,end rho_f(alpha_end) V, which is the mass the rest of the step gives it.
  if (eps != nullptr) {
    for (std::size_t i = 0; i < alpha.size(); ++i)
      alpha[i] = ((*eps->old_cell)[i] * alpha[i] - cflag[i] * dilatation[i]) / (*eps->new_cell)[i];
    const Faces rho_end = face_densities(g, ph, alpha);
    for (int c = 0; c < 3; ++c)
      for_faces(g, c, [&](const std::array<int, 3>& q) {
        const long f = g.face(c, q);
        if (fixed(c, q) || mixed_face[c][f]) return;
        const double m = rho_end[c][f] * (*eps->new_face)[c][f];
        if (m > 0.0) u[c][f] = (mom[c][f] - dilatation_momentum[c][f]) / m;
      });
  }
  // Boundary faces keep their velocity (walls, the open side: set by the projection), and so do blocked faces.
  for (int c = 0; c < 3; ++c)
    for_faces(g, c, [&](const std::array<int, 3>& q) {
      if (fixed(c, q)) u[c][g.face(c, q)] = u0[c][g.face(c, q)];
    });
  st.alpha_min = *std::min_element(alpha.begin(), alpha.end());
  st.alpha_max = *std::max_element(alpha.begin(), alpha.end());
  return st;
}

}  // namespace pastemix::flow
