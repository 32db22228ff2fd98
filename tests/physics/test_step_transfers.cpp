// Host-device traffic of a time step, counted with the Kokkos Tools deep-copy hook
// (kernels/deep_copy_counter.hpp: host_device() counts what crosses on this build, or would on a
// device). On one rank a DEM step makes no host-device copy, list rebuilds included; a water step
// on the uniform grid makes two (the multigrid's coarsest grid, set up again each sub-step: its
// cell list to the device, its rows to the host); the tall-cell water step, which still rebuilds
// its grid on the host, is held at what it copies now, so a new copy in a step fails here.
#include <cstdio>
#include <type_traits>

#include "kernels/deep_copy_counter.hpp"
#include "physics/dem/dem_system.hpp"
#include "physics/water_mac/water_mac.hpp"
#include "shaken_packing.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace test_step_transfers_cases {

using System = physics::dem::DemSystem<test::TestExecSpace>;

TEST(StepTransfers, DemStepsStayOnTheDevice) {
  System s = physics::dem::test_systems::shaken_packing<test::TestExecSpace>(1000, 0.034);
  s.step();  // the first step builds the lists
  kernels::DeepCopyCounter counter;
  int quiet_steps = 0, rebuild_steps = 0;
  for (int it = 0; it < 60; ++it) {
    const long long rebuilds = s.timers().rebuilds;
    counter.reset();
    s.step();
    const kernels::DeepCopyCount c = counter.count();
    const bool rebuilt = s.timers().rebuilds != rebuilds;
    (rebuilt ? rebuild_steps : quiet_steps) += 1;
    // a rebuild keeps the positions it was built at: one copy within the device
    EXPECT_EQ(c.copies, rebuilt ? 1 : 0) << "step " << it;
    EXPECT_EQ(c.host_device(), 0) << "step " << it;
    EXPECT_EQ(c.scalar_reads, 0) << "step " << it;
  }
  ASSERT_GT(quiet_steps, 10);
  ASSERT_GT(rebuild_steps, 2);
}

kernels::DeepCopyCount water_step_copies(int optical_depth) {
  Parameters p(physics::water_mac::parameter_table());
  p.set("scene", std::string("splash"));
  p.set("cells_x", std::int64_t(16));
  p.set("cells_y", std::int64_t(32));
  p.set("cells_z", std::int64_t(16));
  p.set("optical_depth", std::int64_t(optical_depth));
  auto m = physics::water_mac::create(p, Communicator());
  const double dt = 0.25 * m->stable_dt();
  m->set_time_step(dt);
  m->advance(0.0, dt);  // the first step allocates what the later ones reuse
  kernels::DeepCopyCounter counter;
  const int steps = 3;
  for (int s = 1; s <= steps; ++s) m->advance(s * dt, dt);
  kernels::DeepCopyCount c = counter.count();
  std::printf(
      "[transfers] water step, optical depth %d: %.1f deep copies, %.0f B; host-device %.1f, %.0f "
      "B\n",
      optical_depth, double(c.copies) / steps, double(c.bytes) / steps,
      double(c.host_device()) / steps, double(c.host_device_bytes()) / steps);
  return c;
}

TEST(StepTransfers, UniformWaterStepCopiesOnlyTheCoarseGridSetup) {
  // Each sub-step sets the multigrid's coarsest grid up again: its 16 cells' list goes to the
  // device (int) and their matrix rows, packed there, to the host's direct solver (4 doubles a
  // cell). Measured on an H100 before the rows were packed: 5 copies a step, 1984 B.
  const kernels::DeepCopyCount c = water_step_copies(0);
  const int steps = 3, cells = 16;
  EXPECT_EQ(c.host_device(), 2 * steps);
  EXPECT_EQ(c.host_device_bytes(), steps * (cells * 4 + cells * 4 * 8));
}

TEST(StepTransfers, TallCellWaterStepCopiesAtMostItsHostRebuild) {
  // The tall-cell grid is built on the host every sub-step: the columns and the unknowns'
  // layout go back to the device (4 copies a step on a host build; a device build also copies
  // the stencil to the host, by create_mirror_view_and_copy, which a host build does not see:
  // 37.3 copies a step, 1.1 MB, on an H100).
  const kernels::DeepCopyCount c = water_step_copies(4);
  if (std::is_same_v<test::TestMemSpace, Kokkos::HostSpace>) {
    EXPECT_LE(c.host_device(), 3 * 4);
  }
  EXPECT_GT(c.host_device(), 0);
}

}  // namespace test_step_transfers_cases
}  // namespace amphora
