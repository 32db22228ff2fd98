#include "physics/water_mac/water_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kernels/kokkos_compat.hpp"

namespace amphora::physics::water_mac {

InitialWater initial_water(const Parameters& p, const WaterScene& scene,
                           const kernels::mac::MacGrid& g, const kernels::mac::MacGrid& global,
                           const Communicator& comm) {
  // ghost entries are never read; zero in every buffer, so a restart restores them exactly
  std::vector<double> phi(g.padded_size(), 0.0), v(g.padded_size(), 0.0);
  std::vector<std::uint8_t> solid(g.padded_size(), 0);
  const double lx = global.nx * g.h, ly = global.ny * g.h, lz = global.nz * g.h;
  const double amp = p.real("terrain_amplitude"), base = p.real("terrain_base");
  auto floor = [&](double x, double z) {
    return base + amp * std::sin(2 * kernels::math::pi * x / lx) *
                      std::cos(2 * kernels::math::pi * z / lz + 0.3);
  };
  const double a = scene.column_width, pool = p.real("pool_depth"), r = p.real("drop_radius"),
               hc = p.real("drop_height");
  const bool dam = scene.name == "dam_break" || scene.name == "wet_dam_break";
  const double column_height = scene.name == "wet_dam_break" ? scene.reservoir_depth : 2 * a;
  if (dam && (a >= lx || column_height >= ly))
    throw std::invalid_argument("water_mac: the dam-break column (" + std::to_string(a) + " x " +
                                std::to_string(column_height) + " m) must fit in the box (" +
                                std::to_string(lx) + " x " + std::to_string(ly) + " m)");
  bool water_above_terrain = false;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const auto x = g.cell_centre(i, j, k);
        const int c = g.index(i, j, k);
        double d;
        if (dam) {
          // outside distance to the column [0, a] x [0, height] (the box walls are not surface),
          // with the still water ahead of the dam on a wet bed
          const double dx = x[0] - a, dy = x[1] - column_height;
          d = (dx > 0 || dy > 0) ? std::hypot(std::max(dx, 0.0), std::max(dy, 0.0))
                                 : std::max(dx, dy);
          if (scene.name == "wet_dam_break") d = std::min(d, x[1] - scene.tailwater_depth);
        } else {
          d = x[1] - pool;
          if (scene.name == "splash") {
            const double ball =
                std::sqrt((x[0] - 0.5 * lx) * (x[0] - 0.5 * lx) + (x[1] - hc) * (x[1] - hc) +
                          (x[2] - 0.5 * lz) * (x[2] - 0.5 * lz)) -
                r;
            d = std::min(d, ball);
            if (ball < 0) v[c] = -p.real("drop_speed");
          }
          solid[c] = x[1] < floor(x[0], x[2]);
          if (!solid[c] && d < 0) water_above_terrain = true;
        }
        phi[c] = d;
      }
  water_above_terrain = comm.any(water_above_terrain);
  if (!dam && !water_above_terrain)
    throw std::invalid_argument("water_mac: the terrain (terrain_base = " + std::to_string(base) +
                                " m, amplitude " + std::to_string(amp) +
                                " m) is above the water (pool_depth = " + std::to_string(pool) +
                                " m) everywhere: no water to simulate");
  return {phi, v, solid};
}

}  // namespace amphora::physics::water_mac
