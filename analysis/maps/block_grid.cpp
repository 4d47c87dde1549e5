// SPDX-License-Identifier: MIT
#include "analysis/maps/block_grid.h"

#include <algorithm>
#include <cmath>

#include "analysis/geometry/sphere_box.h"
#include "base/units.h"

namespace pastemix::analysis {

BlockMasses rock_in_blocks(const BlockLayout& grid, double surface_z, const ParticleView& particles) {
  BlockMasses out;
  const std::size_t nb = grid.block_count();
  out.rock_mass.assign(nb, 0.0);
  out.rock_volume.assign(nb, 0.0);
  out.rock_volume_submerged.assign(nb, 0.0);
  out.block_volume.assign(nb, grid.size[0] * grid.size[1] * grid.layer_thickness);
  const double x_end = grid.origin[0] + grid.count[0] * grid.size[0];
  const double y_end = grid.origin[1] + grid.count[1] * grid.size[1];
  const double z_bottom = surface_z - grid.layers * grid.layer_thickness;
  const double big = 1e3;  // m: "infinite" for box faces, far beyond any scene
  for (std::size_t p = 0; p < particles.radius.size(); ++p) {
    const auto& c = particles.position[p];
    const double r = particles.radius[p], rho = particles.density[p];
    const double v_sphere = 4.0 / 3.0 * units::pi * r * r * r;
    out.total += rho * v_sphere;
    // Above the surface.
    const double v_above = sphere_box_volume(c, r, Box3{{-big, -big, surface_z}, {big, big, big}});
    out.above_surface += rho * v_above;
    out.submerged += rho * sphere_box_volume(c, r, Box3{{-big, -big, -big}, {big, big, surface_z}});
    // Inside the footprint, below the grid.
    const double v_below =
        sphere_box_volume(c, r, Box3{{grid.origin[0], grid.origin[1], -big}, {x_end, y_end, z_bottom}});
    out.below_grid += rho * v_below;
    // Blocks the sphere can touch (index ranges from its bounding box).
    double v_blocks = 0.0;
    auto range = [](double lo, double hi, double origin, double size, int n) {
      int a = static_cast<int>(std::floor((lo - origin) / size));
      int b = static_cast<int>(std::floor((hi - origin) / size));
      return std::pair<int, int>{std::max(a, 0), std::min(b, n - 1)};
    };
    auto [i0, i1] = range(c.x - r, c.x + r, grid.origin[0], grid.size[0], grid.count[0]);
    auto [j0, j1] = range(c.y - r, c.y + r, grid.origin[1], grid.size[1], grid.count[1]);
    // Layer k spans depth [k t, (k+1) t] below the surface.
    auto [k0, k1] = range(surface_z - (c.z + r), surface_z - (c.z - r), 0.0, grid.layer_thickness, grid.layers);
    if (grid.top_open && k1 < 0) k1 = 0;  // wholly above the surface: layer 1 reaches up to it
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          Box3 b{{grid.origin[0] + i * grid.size[0], grid.origin[1] + j * grid.size[1],
                  surface_z - (k + 1) * grid.layer_thickness},
                 {grid.origin[0] + (i + 1) * grid.size[0], grid.origin[1] + (j + 1) * grid.size[1],
                  surface_z - k * grid.layer_thickness}};
          const double v_sub = sphere_box_volume(c, r, b);
          double v = v_sub;
          if (k == 0 && grid.top_open) {  // the same footprint above the surface
            Box3 top = b;
            top.lo.z = surface_z;
            top.hi.z = big;
            v += sphere_box_volume(c, r, top);
          }
          if (v <= 0.0) continue;
          const std::size_t idx = grid.index(i + 1, j + 1, k + 1);  // loops are 0-based
          out.rock_volume[idx] += v;
          out.rock_volume_submerged[idx] += v_sub;
          out.rock_mass[idx] += rho * v;
          v_blocks += v;
        }
    // Below the surface and outside the footprint: four slabs that tile the rest of the half-space. Computed
    // on their own (not as a remainder) so that mass conservation is a real check of the whole accounting.
    const double zs = surface_z;
    const double v_beside = sphere_box_volume(c, r, Box3{{-big, -big, -big}, {grid.origin[0], big, zs}}) +
                            sphere_box_volume(c, r, Box3{{x_end, -big, -big}, {big, big, zs}}) +
                            sphere_box_volume(c, r, Box3{{grid.origin[0], -big, -big}, {x_end, grid.origin[1], zs}}) +
                            sphere_box_volume(c, r, Box3{{grid.origin[0], y_end, -big}, {x_end, big, zs}});
    out.beside_grid += rho * v_beside;
    // Above the surface and in no block: beside the footprint (top open), or all of it (top closed).
    const double v_uncounted =
        grid.top_open ? sphere_box_volume(c, r, Box3{{-big, -big, zs}, {grid.origin[0], big, big}}) +
                            sphere_box_volume(c, r, Box3{{x_end, -big, zs}, {big, big, big}}) +
                            sphere_box_volume(c, r, Box3{{grid.origin[0], -big, zs}, {x_end, grid.origin[1], big}}) +
                            sphere_box_volume(c, r, Box3{{grid.origin[0], y_end, zs}, {x_end, big, big}})
                      : v_above;
    out.above_uncounted += rho * v_uncounted;
    out.in_blocks += rho * v_blocks;
  }
  return out;
}

}  // namespace pastemix::analysis
