// The column structure of a tall-cell grid (kernels/mac/tall_cell_columns.hpp): the lowest band,
// below which the water module's level-set kernels skip every row, must leave no cell there that
// is neither solid nor in a tall cell, and must be as high as that allows.
#include <algorithm>
#include <vector>

#include "kernels/host_vector.hpp"
#include "kernels/mac/tall_cell_columns.hpp"
#include "test_backend.hpp"

namespace amphora::kernels::mac {
namespace {

using Exec = test::TestExecSpace;
using Mem = test::TestMemSpace;

/// A pool over uneven terrain: solid rows [0, floor), fluid up to `surface`, air above, per
/// column; `cave` puts an air pocket under the solid of column (0, 1) (floor 4).
struct Pool {
  MacGrid g{7, 24, 5, 0.1, {0, 0, 0}};
  std::vector<MacCellType> type;
  int floor(int i, int k) const { return 1 + (2 * i + 3 * k) % 4; }
  Pool(int surface_lo, int surface_hi, bool cave) {
    type.assign(g.padded_size(), MacCellType::solid);
    for (int k = 0; k < g.nz; ++k)
      for (int i = 0; i < g.nx; ++i) {
        const int surface = surface_lo + (i * 5 + k) % (surface_hi - surface_lo + 1);
        for (int j = 0; j < g.ny; ++j)
          type[g.index(i, j, k)] = j < floor(i, k) ? MacCellType::solid
                                   : j < surface   ? MacCellType::fluid
                                                   : MacCellType::air;
      }
    if (cave) type[g.index(0, 0, 1)] = MacCellType::air;
  }
};

/// lowest_band of the pool's columns at optical depth D, and whether every cell below it is
/// solid or in a tall cell, and whether the row it names holds a cell that is neither.
void check(const Pool& p, int D, int expected) {
  const MacGrid& g = p.g;
  const auto type = kernels::to_view<Mem>(p.type);
  TallCellColumns<Mem> T(g);
  find_tall_cell_columns(Exec(), type, D, T);
  const int lowest = lowest_band(Exec(), T, type);
  EXPECT_EQ(lowest, expected) << "optical depth " << D;
  const auto terrain = kernels::to_std_vector(T.terrain), band = kernels::to_std_vector(T.band);
  bool bound_is_tight = lowest == 0;
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) {
      const int col = T.column(i, k);
      for (int j = 0; j <= std::min(lowest, g.ny - 1); ++j) {
        const bool tall = band[col] > terrain[col] && j >= terrain[col] && j < band[col];
        const bool skipped = tall || p.type[g.index(i, j, k)] == MacCellType::solid;
        if (j < lowest) {
          EXPECT_TRUE(skipped) << "cell (" << i << ", " << j << ", " << k << ") below row "
                               << lowest;
        }
        if (j == lowest && !skipped) bound_is_tight = true;
      }
    }
  EXPECT_TRUE(bound_is_tight) << "row " << lowest << " could be skipped too";
}

TEST(TallCellColumns, LowestBandLeavesOnlyTallCellsAndSolidsBelowIt) {
  // surface rows 18..21, the band D rows below it: the lowest band is the lowest surface - D
  check(Pool(18, 21, false), 6, 12);
  check(Pool(18, 21, false), 10, 8);
  // every column uniform (optical depth 0: no tall cells) or a tall cell under D = 16 missing
  // where it would be shorter than two rows (floor up to 4, surface 18): nothing to skip
  check(Pool(18, 21, false), 0, 0);
  check(Pool(18, 21, false), 16, 0);
  // a cell under a column's terrain that is not solid: no row can be skipped
  check(Pool(18, 21, true), 6, 0);
}

}  // namespace
}  // namespace amphora::kernels::mac
