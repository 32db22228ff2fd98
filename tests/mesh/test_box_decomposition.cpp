#include <set>

#include "mesh/box_decomposition.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace {

TEST(BoxDecomposition, BlocksTileTheBoxExactly) {
  for (int nranks : {1, 2, 3, 4, 6, 8, 12}) {
    mesh::BoxDecomposition dec({30, 20, 10}, {false, false, false}, nranks);
    EXPECT_EQ(dec.num_blocks(), nranks);
    long long cells = 0;
    std::set<long long> owned;
    for (int r = 0; r < nranks; ++r) {
      const mesh::Box b = dec.box(r);
      cells += b.cells();
      for (int d = 0; d < 3; ++d) {
        // Balanced: extents differ by at most one cell.
        EXPECT_LE(b.extent(d), dec.global_cells()[d] / dec.blocks()[d] + 1);
        EXPECT_GE(b.extent(d), dec.global_cells()[d] / dec.blocks()[d]);
      }
      for (int k = b.lo[2]; k < b.hi[2]; ++k)
        for (int j = b.lo[1]; j < b.hi[1]; ++j)
          for (int i = b.lo[0]; i < b.hi[0]; ++i) owned.insert(i + 30LL * (j + 20LL * k));
      EXPECT_EQ(dec.rank_of(dec.block_coords(r)), r);
    }
    EXPECT_EQ(cells, 30 * 20 * 10);
    EXPECT_EQ(owned.size(), size_t(30 * 20 * 10));
  }
}

TEST(BoxDecomposition, SplitsAlongTheLongDirectionFirst) {
  mesh::BoxDecomposition dec({64, 8, 8}, {false, false, false}, 2);
  EXPECT_EQ(dec.blocks()[0], 2);
  EXPECT_EQ(dec.blocks()[1], 1);
}

TEST(BoxDecomposition, NeighboursAndPeriodicImages) {
  mesh::BoxDecomposition dec({8, 8, 4}, {true, false, false}, 4);
  for (int r = 0; r < 4; ++r) {
    const mesh::Index3 c = dec.block_coords(r);
    for (int d = 0; d < 3; ++d) {
      for (int side = 0; side < 2; ++side) {
        const int nb = dec.neighbor(r, d, side);
        const bool at_edge = side == 0 ? c[d] == 0 : c[d] == dec.blocks()[d] - 1;
        if (at_edge && !dec.periodic(d)) {
          EXPECT_EQ(nb, -1);
        } else {
          ASSERT_GE(nb, 0);
          // The neighbour's opposite neighbour is this rank.
          EXPECT_EQ(dec.neighbor(nb, d, 1 - side), r);
        }
      }
    }
  }
}

TEST(BoxDecomposition, MoreRanksThanBlocksIsAClearError) {
  try {
    mesh::BoxDecomposition dec({4, 1, 1}, {false, false, false}, 3, 2);
    FAIL() << "expected DecompositionError";
  } catch (const mesh::DecompositionError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("more ranks (3) than blocks"), std::string::npos) << m;
    EXPECT_NE(m.find("4x1x1"), std::string::npos) << m;
  }
  EXPECT_THROW(mesh::BoxDecomposition({0, 4, 4}, {false, false, false}, 1),
               mesh::DecompositionError);
  EXPECT_NO_THROW(mesh::BoxDecomposition({4, 1, 1}, {false, false, false}, 2, 2));
}

}  // namespace
}  // namespace amphora
