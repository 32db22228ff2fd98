// Issue 4's iteration-count check at its own sizes: MG-CG iterations to 1e-8 over 64^3, 128^3
// and 192^3 within +-2 (16 s on one thread; test_mac_pressure checks the same problems at 16^3 to
// 64^3): without a free surface (the benchmark's open box, a bottom wall, a tank: 7, 7, 7), with a
// flat one at y = 0.63 (open box 7, 7, 7; tank 7, 8, 7) and with a wavy one, 0.63 + 0.15
// sin(2 pi x) cos(2 pi z) (open box 7, 7, 7; tank 8, 8, 8).
//
// The free-surface cases grew by two per refinement (flat: open box 8, 10, 12, tank 9, 11, 13)
// while a coarse cell kept half its children's free-surface terms; they are flat since the coarse
// levels form them from a coarsened level set (kernels/mac/grid_transfer.hpp).
#include "mac_box_iterations.hpp"

namespace amphora::solvers::mac {
namespace {

TEST(MacMultigrid, IterationsOver64To192) {
  const test_problems::BoxFaces f;
  const test_problems::IterationCase cases[] = {
      {"open box", f.open, 2.0, 2, 7},
      {"bottom wall", f.bottom, 2.0, 2, 7},
      {"tank", f.tank, 2.0, 2, 7},
      {"open box, free surface", f.open, 0.63, 2, 8},
      {"tank, free surface", f.tank, 0.63, 2, 9},
      {"open box, wavy surface", f.open, 0.63, 2, 8, 0.15},
      {"tank, wavy surface", f.tank, 0.63, 2, 9, 0.15}};
  for (const auto& c : cases) {
    const auto r = test_problems::iteration_counts({64, 128, 192}, c);
    EXPECT_LE(r.spread(), c.spread) << c.name;
    EXPECT_LE(r.last(), c.most) << c.name;
  }
}

}  // namespace
}  // namespace amphora::solvers::mac
