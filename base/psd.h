// SPDX-License-Identifier: MIT
// Particle-size distributions as sieve intervals with mass fractions, and a seeded size generator.
//
// Shared by lab/ (the sieve ingester reduces sieve masses to a Psd) and model/ (insertion factories draw
// particle diameters from it), which is why it lives in base: it is a sampling rule, not lab I/O.
//
// The generator follows the thesis (and EDEM's practice): inside each sieve interval, diameters are drawn
// from a number-weighted Gaussian with mean at the interval's midpoint and sigma/mu = 0.25, truncated to the
// interval; an interval keeps drawing until its target mass (fraction x total mass) is met, so the mass
// fractions are honoured whatever the shape of the Gaussian.
#pragma once

#include <cstdint>
#include <vector>

namespace pastemix {

struct PsdInterval {
  double d_min = 0.0;          // m, lower sieve
  double d_max = 0.0;          // m, upper sieve
  double mass_fraction = 0.0;  // of the total, in [0, 1]
};

struct Psd {
  std::vector<PsdInterval> intervals;  // ascending d_min, contiguous or not, fractions summing to 1

  // Throws std::invalid_argument when intervals are empty, inverted, overlapping, or fractions do not sum
  // to 1 within 1e-6.
  void check() const;
  // Drops the intervals whose upper sieve is <= d_cut (the "PSD cut") and renormalises the rest.
  Psd cut_below(double d_cut) const;
  double d_min() const;
  double d_max() const;
};

struct GeneratorOptions {
  double sigma_over_mu = 0.25;  // relative width of the Gaussian inside each interval
};

// Diameters (m) of spheres of `density` (kg/m3) whose total mass is `total_mass` (kg), sampled interval by
// interval. Deterministic for a given seed. The last particle of each interval is kept only if that brings
// the interval's mass closer to its target, so each interval ends within half a particle of its target.
std::vector<double> generate_diameters(const Psd& psd, double total_mass, double density, std::uint64_t seed,
                                       const GeneratorOptions& options = {});

}  // namespace pastemix
