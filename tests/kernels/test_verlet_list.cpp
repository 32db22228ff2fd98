// Binning and Verlet lists (kernels/particles): every point lies in the cell bin_points puts it
// in, a cell's points are in key order; a Verlet row holds exactly the points within
// r_i + r_j + skin (an all-pairs search), sorted by key, and half_starts splits it at the key.
#include <algorithm>
#include <vector>

#include "kernels/particles/verlet_list.hpp"
#include "particles_fixture.hpp"
#include "test_backend.hpp"

namespace amphora::kernels::particles {
namespace {

using Exec = test::TestExecSpace;
using Mem = test::TestMemSpace;

using Device = test::DeviceSpheres<Mem>;

TEST(ParticleBinning, EveryPointInItsCellCellsInKeyOrder) {
  const test::RandomSpheres s(3000, 0.01, 7);
  const Device dev(s);
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  const CellGrid grid = CellGrid::covering(lo, hi, 0.07);
  const auto bins = bin_points(Exec(), grid, dev.x, s.n, dev.gid);
  auto off = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), bins.offsets);
  auto perm = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), bins.permutation);
  ASSERT_EQ(off(grid.num_cells()), s.n);
  std::vector<int> seen(s.n, 0);
  for (int c = 0; c < grid.num_cells(); ++c)
    for (int a = off(c); a < off(c + 1); ++a) {
      const int p = perm(a);
      ++seen[p];
      const double* xp = &s.x[3 * size_t(p)];
      EXPECT_EQ(grid.cell_of(xp[0], xp[1], xp[2]), c);
      if (a > off(c)) {
        EXPECT_LT(s.gid[perm(a - 1)], s.gid[p]) << "cell " << c;
      }
    }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), s.n);
}

TEST(ParticleVerletList, RowsEqualAllPairsSortedAndSplit) {
  const test::RandomSpheres s(2000, 0.03, 11);
  const Device dev(s);
  const double skin = 0.01, lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  const CellGrid grid = CellGrid::covering(lo, hi, 2 * s.r_max + skin);
  const auto bins = bin_points(Exec(), grid, dev.x, s.n);
  const auto list = build_verlet_list(Exec(), grid, bins, dev.x, dev.r, dev.gid, s.n, skin);
  const auto half = half_starts(Exec(), list, dev.gid);
  auto off = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), list.offsets);
  auto nbr = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), list.neighbors);
  auto hh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), half);
  long long entries = 0;
  for (int i = 0; i < s.n; ++i) {
    std::vector<int> truth;
    for (int j = 0; j < s.n; ++j) {
      if (j == i) continue;
      double d2 = 0;
      for (int d = 0; d < 3; ++d) {
        const double dd = s.x[3 * size_t(j) + d] - s.x[3 * size_t(i) + d];
        d2 += dd * dd;
      }
      const double cut = s.r[i] + s.r[j] + skin;
      if (d2 < cut * cut) truth.push_back(j);
    }
    std::sort(truth.begin(), truth.end(), [&](int a, int b) { return s.gid[a] < s.gid[b]; });
    const std::vector<int> row(nbr.data() + off(i), nbr.data() + off(i + 1));
    ASSERT_EQ(row, truth) << "row " << i;
    for (int k = off(i); k < off(i + 1); ++k)
      EXPECT_EQ(k >= hh(i), s.gid[nbr(k)] > s.gid[i]) << "row " << i << " entry " << k;
    entries += off(i + 1) - off(i);
  }
  EXPECT_GT(entries, 4 * s.n) << "the test needs neighbours";
}

/// Rows 0 .. n of a list, as host vectors.
std::vector<std::vector<int>> rows_of(const NeighborList<Mem>& list) {
  auto off = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), list.offsets);
  auto nbr = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), list.neighbors);
  std::vector<std::vector<int>> rows(list.rows());
  for (int i = 0; i < list.rows(); ++i)
    rows[i].assign(nbr.data() + off(i), nbr.data() + off(i + 1));
  EXPECT_EQ(list.rows() > 0 ? off(list.rows()) : 0, list.entries());
  return rows;
}

/// A list kept across rebuilds (rebuilt in its own arrays, as the DEM does) holds what a new
/// list holds, whether the points grow or shrink, and keeps its arrays while they suffice.
TEST(ParticleVerletList, AKeptListRebuildsToWhatANewListHolds) {
  const double skin = 0.01, lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  NeighborList<Mem> kept;
  const int* kept_neighbors = nullptr;
  for (const int n : {1500, 2500, 800, 2400}) {
    const test::RandomSpheres s(n, 0.03, 5 + n);
    const Device dev(s);
    const CellGrid grid = CellGrid::covering(lo, hi, 2 * s.r_max + skin);
    const auto bins = bin_points(Exec(), grid, dev.x, s.n);
    const auto fresh = build_verlet_list(Exec(), grid, bins, dev.x, dev.r, dev.gid, s.n, skin);
    const bool fits = kept.neighbors.extent(0) >= size_t(fresh.entries());
    build_verlet_list(Exec(), grid, bins, dev.x, dev.r, dev.gid, s.n, skin, kept);
    ASSERT_EQ(kept.rows(), n);
    ASSERT_EQ(kept.entries(), fresh.entries());
    EXPECT_EQ(rows_of(kept), rows_of(fresh)) << n << " points";
    if (fits) {
      EXPECT_EQ(kept.neighbors.data(), kept_neighbors) << n << " points: reallocated";
    }
    kept_neighbors = kept.neighbors.data();
  }
}

}  // namespace
}  // namespace amphora::kernels::particles
