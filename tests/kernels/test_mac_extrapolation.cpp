// Velocity extrapolation into the air (kernels/mac/projection.hpp): layers fill only faces
// between two air cells, so starting them at the lowest air row changes nothing.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "kernels/host_vector.hpp"
#include "kernels/mac/projection.hpp"
#include "test_backend.hpp"

namespace amphora::kernels::mac {
namespace {

using Exec = test::TestExecSpace;
using Mem = test::TestMemSpace;
using kernels::mac::MacCellType;

TEST(MacExtrapolation, LayersFromTheLowestAirRowEqualLayersOverTheWholeGrid) {
  const kernels::mac::MacGrid g{20, 24, 12, 1.0 / 20, {0.0, 0.0, 0.0}};
  // a solid floor, water up to a wavy surface between rows 9 and 17, air above
  std::vector<MacCellType> type(g.padded_size(), MacCellType::solid);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const double surface = 13.0 + 4.0 * std::sin(0.5 * i) * std::cos(0.7 * k);
        type[g.index(i, j, k)] = j < 2 + (i + k) % 3 ? MacCellType::solid
                                 : j < surface       ? MacCellType::fluid
                                                     : MacCellType::air;
      }
  const auto types = kernels::to_view<Mem>(type);
  const Exec exec;
  const int first = lowest_air_row(exec, g, types);
  int expected = g.ny;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (type[g.index(i, j, k)] == MacCellType::air) expected = std::min(expected, j);
  EXPECT_EQ(first, expected);
  EXPECT_GT(first, 5);  // the test means something: rows below are skipped
  for (int d = 0; d < 3; ++d) {
    std::vector<double> face(g.padded_size());
    for (std::size_t c = 0; c < face.size(); ++c) face[c] = std::sin(0.37 * double(c)) + d;
    std::vector<double> results[2];
    std::vector<std::uint8_t> marks[2];
    for (int variant = 0; variant < 2; ++variant) {
      Kokkos::View<double*, Mem> f = kernels::to_view<Mem>(face);
      Kokkos::View<std::uint8_t*, Mem> mark("mark", g.padded_size());
      mark_fluid_faces(exec, g, d, types, mark);
      for (int layer = 2; layer < 5; ++layer)
        extrapolate_layer(exec, g, d, types, f, mark, layer, kernels::mac::box_edges(),
                          variant == 0 ? 0 : first);
      results[variant] = kernels::to_std_vector(f);
      const auto host_mark = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), mark);
      marks[variant].assign(host_mark.data(), host_mark.data() + host_mark.extent(0));
    }
    long filled = 0;
    for (std::size_t c = 0; c < face.size(); ++c) {
      ASSERT_EQ(results[1][c], results[0][c]) << "component " << d << ", padded index " << c;
      ASSERT_EQ(marks[1][c], marks[0][c]) << "component " << d << ", padded index " << c;
      filled += marks[0][c] >= 2;
    }
    EXPECT_GT(filled, 0) << "component " << d;
  }
}

}  // namespace
}  // namespace amphora::kernels::mac
