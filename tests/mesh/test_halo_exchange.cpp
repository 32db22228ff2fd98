// Halo exchange at 1 and 2 ranks: every ghost holds the value of the global cell it images
// (periodic in x, walls in y and z), whatever the rank count.
#include "mesh/halo_exchange.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace {

double tag(int i, int j, int k) { return i + 100.0 * j + 10000.0 * k; }

TEST(HaloExchange, GhostsHoldTheirImagesAcrossRanks) {
  Communicator comm;
  const mesh::Index3 global{12, 6, 5};
  const int g = 2;
  mesh::BoxDecomposition dec(global, {true, false, false}, comm.size(), g);
  mesh::HaloExchange<test::TestMemSpace> halo(dec, comm, g);
  auto f = halo.allocate("f");
  const mesh::Box b = halo.box();
  auto h = Kokkos::create_mirror_view(f);
  Kokkos::deep_copy(h, -1.0);
  for (int k = 0; k < b.extent(2); ++k)
    for (int j = 0; j < b.extent(1); ++j)
      for (int i = 0; i < b.extent(0); ++i)
        h(i + g, j + g, k + g) = tag(b.lo[0] + i, b.lo[1] + j, b.lo[2] + k);
  Kokkos::deep_copy(f, h);

  halo.exchange(test::TestExecSpace(), f);
  Kokkos::deep_copy(h, f);

  int checked = 0;
  for (int k = 0; k < int(f.extent(2)); ++k) {
    for (int j = 0; j < int(f.extent(1)); ++j) {
      for (int i = 0; i < int(f.extent(0)); ++i) {
        int gi = b.lo[0] + i - g, gj = b.lo[1] + j - g, gk = b.lo[2] + k - g;
        gi = (gi + global[0]) % global[0];  // periodic in x
        const bool outside = gj < 0 || gj >= global[1] || gk < 0 || gk >= global[2];
        const double expected = outside ? -1.0 : tag(gi, gj, gk);
        ASSERT_EQ(h(i, j, k), expected)
            << "rank " << comm.rank() << " local " << i << "," << j << "," << k;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, int(f.size()));
}

TEST(HaloExchange, DecompositionMatchesRankCount) {
  Communicator comm;
  mesh::BoxDecomposition dec({12, 6, 5}, {true, false, false}, comm.size(), 2);
  EXPECT_EQ(dec.num_blocks(), comm.size());
}

}  // namespace
}  // namespace amphora
