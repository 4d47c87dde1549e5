// SPDX-License-Identifier: MIT
#include "base/psd.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "base/rng.h"
#include "base/units.h"

namespace pastemix {

void Psd::check() const {
  if (intervals.empty()) throw std::invalid_argument("PSD has no intervals");
  double sum = 0.0;
  for (std::size_t k = 0; k < intervals.size(); ++k) {
    const auto& iv = intervals[k];
    if (!(iv.d_min > 0.0) || !(iv.d_max > iv.d_min))
      throw std::invalid_argument(fmt::format("PSD interval {}: need 0 < d_min < d_max (got {} .. {} m)", k + 1,
                                              iv.d_min, iv.d_max));
    if (!(iv.mass_fraction >= 0.0 && iv.mass_fraction <= 1.0))
      throw std::invalid_argument(fmt::format("PSD interval {}: mass fraction {} not in [0, 1]", k + 1,
                                              iv.mass_fraction));
    if (k > 0 && iv.d_min < intervals[k - 1].d_max - 1e-12)
      throw std::invalid_argument(fmt::format("PSD interval {} overlaps the one below it", k + 1));
    sum += iv.mass_fraction;
  }
  if (std::abs(sum - 1.0) > 1e-6)
    throw std::invalid_argument(fmt::format("PSD mass fractions sum to {}, not 1", sum));
}

Psd Psd::cut_below(double d_cut) const {
  Psd out;
  double kept = 0.0;
  for (const auto& iv : intervals)
    if (iv.d_max > d_cut * (1.0 + 1e-12)) {
      out.intervals.push_back(iv);
      kept += iv.mass_fraction;
    }
  if (out.intervals.empty() || kept <= 0.0)
    throw std::invalid_argument(fmt::format("PSD cut at {} m removes every interval", d_cut));
  for (auto& iv : out.intervals) iv.mass_fraction /= kept;
  return out;
}

double Psd::d_min() const { return intervals.front().d_min; }
double Psd::d_max() const { return intervals.back().d_max; }

std::vector<double> generate_diameters(const Psd& psd, double total_mass, double density, std::uint64_t seed,
                                       const GeneratorOptions& options) {
  psd.check();
  if (!(total_mass > 0.0) || !(density > 0.0))
    throw std::invalid_argument("generate_diameters: total mass and density must be positive");
  Rng rng(seed);
  std::vector<double> diameters;
  const double volume_factor = units::pi / 6.0 * density;  // mass of a sphere = factor * d^3
  for (const auto& iv : psd.intervals) {
    const double target = iv.mass_fraction * total_mass;
    const double mu = 0.5 * (iv.d_min + iv.d_max);
    const double sigma = options.sigma_over_mu * mu;
    double mass = 0.0;
    while (mass < target) {
      double d;
      do d = rng.normal(mu, sigma);  // truncation by rejection keeps the Gaussian's shape inside the interval
      while (d < iv.d_min || d > iv.d_max);
      const double m = volume_factor * d * d * d;
      // Keep the particle only if it brings the interval closer to its target mass.
      if (mass + m - target > target - mass) break;
      diameters.push_back(d);
      mass += m;
    }
  }
  return diameters;
}

}  // namespace pastemix
