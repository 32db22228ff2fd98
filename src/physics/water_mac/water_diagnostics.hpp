#pragma once
// The water module's surface diagnostics and the measurements they are checked against: the
// dam-break front (Martin & Moyce 1952), the wet-bed bore (Stoker 1957), the mean surface.
#include <array>
#include <vector>

#include "base/communicator.hpp"
#include "kernels/mac/mac_grid.hpp"

namespace amphora::physics::water_mac {

/// Martin & Moyce (1952), fig. 3, n^2 = 2, a = 2.25 in: front position Z = x/a against
/// T = t sqrt(2 g / a), linearly interpolated (T within the measured 0.832 .. 9.237).
double martin_moyce_front(double T);

/// A block's level set on the host (padded lattice; its ghost cells hold the neighbours') and
/// where the block lies in the whole grid.
struct LevelSetBlock {
  std::vector<double> phi;
  kernels::mac::MacGrid grid, global;
  std::array<int, 3> lower;  ///< the block's first cell in the whole grid
  bool upper_x_is_box;       ///< the block's +x face is the box's
  const Communicator& comm;
};

/// The dam-break front: the largest x where the bottom row's level set crosses zero (linear
/// between cell centres), averaged over z. Collective.
double dam_break_front(const LevelSetBlock& b);
/// The wet dam break's bore: the largest x where the water depth (the lowest zero crossing of
/// the level set in a column, averaged over z) reaches `half_depth`, linear between cell
/// centres. Collective.
double bore_position(const LevelSetBlock& b, double half_depth);
/// Mean height of the highest zero crossing of the level set over the columns. Collective.
double mean_surface_height(const LevelSetBlock& b);

}  // namespace amphora::physics::water_mac
