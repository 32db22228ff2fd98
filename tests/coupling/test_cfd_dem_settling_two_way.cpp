// A single sphere settling through water with the water solved (unresolved CFD-DEM, two way:
// CfdDemCoupling). The sphere drags the water near it along, so the slip the closure sees is
// smaller than its fall speed and it falls faster than the drag law's terminal velocity; the
// excess is the known self-induced velocity of unresolved coupling and shrinks as the cells
// grow against the sphere (docs/cfd_dem.md).
#include <cstdio>

#include "coupling/settling_two_way.hpp"

namespace amphora::coupling::cfd_dem {
// Named, not anonymous: CUDA's extended lambdas may not live in anonymous namespaces.
namespace test_cfd_dem_settling_two_way {

using namespace settling_two_way;

/// Re_p 1, 10 and 100 (the one-way test covers 0.1, whose fall through a few cells takes
/// thousands of steps), cells 5 and 10 diameters wide, smoothing over a cell. Checked: the sphere
/// is steady (its speed changes by under 0.5 % over its fourth cell); the slip the closure sees,
/// fall speed less the water's, is the drag law's terminal velocity (the balance); the fall
/// speed exceeds it by the self-induced velocity, under the 2 % with cells ten diameters
/// wide and shrinking like (d / h)^2 (the force spread over a cell of h^3, read back at the
/// sphere: the ratio from 5 to 10 diameters is about four).
TEST(CfdDemSettlingTwoWay, TerminalVelocityWithTheSelfInducedVelocityShrinkingWithTheCells) {
  for (const double re : {1.0, 10.0, 100.0}) {
    double excess[2];
    for (int c = 0; c < 2; ++c) {
      const double cells = 5.0 * (c + 1);
      const Settling r = settle(re, cells, cells);
      for (int k = 0; k < 2; ++k)
        std::printf(
            "Re %g, h = %g d, %d cells down: fall %.5e m/s (drag law %.5e, %+.3f %%), "
            "water at the sphere %.3e, slip / drag law - 1 %+.2e\n",
            re, cells, 3 + k, r.speed[k], r.terminal, 100 * (r.speed[k] / r.terminal - 1),
            r.fluid[k], (r.speed[k] - r.fluid[k]) / r.terminal - 1);
      EXPECT_NEAR(r.speed[1] / r.speed[0], 1.0, 5e-3) << "Re " << re << " h " << cells << " d";
      EXPECT_NEAR((r.speed[1] - r.fluid[1]) / r.terminal, 1.0, 5e-3)
          << "Re " << re << " h " << cells << " d";
      excess[c] = r.speed[1] / r.terminal - 1.0;
    }
    EXPECT_GT(excess[1], 0.0) << "Re " << re;
    EXPECT_LT(excess[1], 0.02) << "Re " << re;
    EXPECT_GT(excess[0] / excess[1], 3.0) << "Re " << re;
    EXPECT_LT(excess[0] / excess[1], 5.0) << "Re " << re;
  }
}

}  // namespace test_cfd_dem_settling_two_way
}  // namespace amphora::coupling::cfd_dem
