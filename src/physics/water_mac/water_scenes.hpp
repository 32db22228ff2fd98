#pragma once
// The water module's initial states: a dam break (a column of width a and height 2a, or a
// reservoir behind a dam over still water), a ball of water over a pool, still water; terrain
// as a solid floor under the pool. Signed distances and velocities on a block's padded
// lattice, on the host.
#include <cstdint>
#include <string>
#include <vector>

#include "base/communicator.hpp"
#include "base/parameters.hpp"
#include "kernels/mac/mac_grid.hpp"

namespace amphora::physics::water_mac {

struct WaterScene {
  std::string name;  ///< dam_break, wet_dam_break, splash, still
  double column_width = 0, reservoir_depth = 0, tailwater_depth = 0;
};

struct InitialWater {
  std::vector<double> phi, v;       ///< level set; vertical velocity on the y faces
  std::vector<std::uint8_t> solid;  ///< 1: terrain
};

/// The initial state on block `g` of the whole grid `global`; throws std::invalid_argument
/// where the scene does not fit the box or leaves no water. Collective.
InitialWater initial_water(const Parameters& p, const WaterScene& scene,
                           const kernels::mac::MacGrid& g, const kernels::mac::MacGrid& global,
                           const Communicator& comm);

}  // namespace amphora::physics::water_mac
