// Host-device traffic of a time step, counted with the Kokkos Tools deep-copy hook
// (kernels/deep_copy_counter.hpp: host_device() counts what crosses on this build, or would on a
// device). On one rank a DEM step makes no host-device copy, list rebuilds included (periodic
// boxes' images too, also where only some directions are periodic); a water step on the uniform
// grid copies only the multigrid's coarsest grid (set up again each step: its cell list to the
// device, its rows to the host; each V-cycle its right-hand side to the host and its solution
// back); the tall-cell water step none that a host build sees (its hierarchy is built on the
// device; its coarsest level's rows go to the host by mirror-and-copy).
#include <algorithm>
#include <cstdio>
#include <vector>
#include <type_traits>

#include "kernels/deep_copy_counter.hpp"
#include "physics/dem/dem_system.hpp"
#include "physics/water_mac/water_mac.hpp"
#include "shaken_packing.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace test_step_transfers_cases {

using System = physics::dem::DemSystem<test::TestExecSpace>;

/// Steps s 60 times after its first: no step copies between host and device, and a rebuild
/// copies once within it (the positions it was built at).
void expect_steps_on_the_device(System& s) {
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
    EXPECT_EQ(c.copies, rebuilt ? 1 : 0) << "step " << it;
    EXPECT_EQ(c.host_device(), 0) << "step " << it;
    EXPECT_EQ(c.scalar_reads, 0) << "step " << it;
  }
  ASSERT_GT(quiet_steps, 10);
  ASSERT_GT(rebuild_steps, 2);
}

TEST(StepTransfers, DemStepsStayOnTheDevice) {
  System s = physics::dem::test_systems::shaken_packing<test::TestExecSpace>(1000, 0.034);
  expect_steps_on_the_device(s);
}

// A box periodic in x, y and z: the ghosts are the particles' own images, copied on the device
// (no message, no host copy), and crossing particles are wrapped there at the rebuilds.
TEST(StepTransfers, PeriodicDemStepsStayOnTheDevice) {
  using physics::dem::test_systems::shaken_packing;
  System s = shaken_packing<test::TestExecSpace>(1000, 0.03, {true, true, true}, 0.6);
  expect_steps_on_the_device(s);
  EXPECT_GT(s.particles().n_ghost, 100) << "the images must be there";
}

// Periodic in x alone (a bed or a channel): walls bound y and z, which have no ghosts to send,
// so their faces make no copy either (an empty copy fences the device like any other).
TEST(StepTransfers, PartlyPeriodicDemStepsStayOnTheDevice) {
  using physics::dem::test_systems::shaken_packing;
  System s = shaken_packing<test::TestExecSpace>(1000, 0.034, {true, false, false}, 0.6);
  expect_steps_on_the_device(s);
  EXPECT_GT(s.particles().n_ghost, 30) << "the images must be there";
}

/// Rows of spheres in free flight along +x, each row at its own speed (so no contacts), through
/// a domain open at x = L: a rebuild removes those that left, on the device (one rank: the plan
/// is a scan; no host copy), and keeps the others' states.
TEST(StepTransfers, DemRemovalsStayOnTheDevice) {
  const double r = 5e-4, L = 1e-2, dt = 1e-5;
  physics::dem::Material m;
  m.youngs_modulus = 1e7;
  physics::dem::DemConfig c;
  c.materials = {m};
  c.domain_lo = {0, 0, 0};
  c.domain_hi = {L, L, L};
  c.gravity = {0, 0, 0};
  c.max_radius = r;
  c.skin = 0.3 * r;
  c.dt = dt;
  System s(c, Communicator());
  std::vector<physics::dem::ParticleSpec> ps;
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        physics::dem::ParticleSpec p;
        p.x[0] = (2 * i + 1) * 1e-3, p.x[1] = (2 * j + 1) * 1e-3, p.x[2] = (2 * k + 1) * 1e-3;
        p.v[0] = 1.0 + 0.9 * ((j + 5 * k) % 5);  // 1 .. 4.6 m/s
        p.radius = r;
        p.gid = ps.size();
        ps.push_back(p);
      }
  s.add_particles(ps);
  s.step();
  kernels::DeepCopyCounter counter;
  const int steps = 150;  // 1.5 ms: rows travel 1.5 .. 6.9 mm
  int removals = 0;
  for (int it = 1; it < steps; ++it) {
    const long long rebuilds = s.timers().rebuilds, held = s.global_count();
    counter.reset();
    s.step();
    const kernels::DeepCopyCount cc = counter.count();
    // a rebuild, a removal's included: the build positions (the force and torque a removal
    // leaves are zeroed by a kernel, not filled)
    const bool removed = s.global_count() < held;
    removals += removed ? 1 : 0;
    EXPECT_EQ(cc.copies, s.timers().rebuilds != rebuilds ? 1 : 0) << "step " << it;
    EXPECT_EQ(cc.host_device(), 0) << "step " << it;
    EXPECT_EQ(cc.scalar_reads, 0) << "step " << it;
  }
  EXPECT_GT(removals, 3);
  // A centre past x = L is 0.5 mm or more past it, more than the skin a rebuild may lag behind.
  std::vector<std::int64_t> inside;
  for (const auto& p : ps)
    if (p.x[0] + p.v[0] * steps * dt < L) inside.push_back(p.gid);
  ASSERT_GT(inside.size(), 25u);
  ASSERT_LT(inside.size(), 100u);
  const auto& set = s.particles();
  auto gid = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), set.gid);
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), set.x);
  std::vector<std::int64_t> held;
  for (int i = 0; i < set.n_owned; ++i) {
    held.push_back(gid(i));
    const auto& p = ps[gid(i)];
    EXPECT_NEAR(x(i, 0), p.x[0] + p.v[0] * steps * dt, 1e-12) << "gid " << gid(i);
    EXPECT_EQ(x(i, 1), p.x[1]) << "gid " << gid(i);
  }
  std::sort(held.begin(), held.end());
  EXPECT_EQ(held, inside);
}

/// A water step's copies, and the pressure iterations it took (one solve per step here).
struct WaterSteps {
  kernels::DeepCopyCount copies;
  int steps = 0, iterations = 0;
};

/// Steps a small splash 3 times, counting their copies, after 8 steps that set the water moving
/// (the first ones' pressure solves need no iteration: the drop falls freely).
WaterSteps water_step_copies(int optical_depth) {
  Parameters p(physics::water_mac::parameter_table());
  p.set("scene", std::string("splash"));
  p.set("cells_x", std::int64_t(16));
  p.set("cells_y", std::int64_t(32));
  p.set("cells_z", std::int64_t(16));
  p.set("optical_depth", std::int64_t(optical_depth));
  auto m = physics::water_mac::create(p, Communicator());
  const double dt = 0.25 * m->stable_dt();
  m->set_time_step(dt);
  int s = 0;
  for (; s < 8; ++s) m->advance(s * dt, dt);  // the first step allocates what later ones reuse
  WaterSteps w;
  kernels::DeepCopyCounter counter;
  for (w.steps = 0; w.steps < 3; ++w.steps, ++s) {
    counter.reset();
    m->advance(s * dt, dt);
    w.copies = w.copies + counter.count();
    for (const auto& [name, value] : m->diagnostics((s + 1) * dt))
      if (name == "pressure_iterations") w.iterations += static_cast<int>(value);
  }
  const kernels::DeepCopyCount& c = w.copies;
  std::printf(
      "[transfers] water step, optical depth %d: %.1f deep copies, %.0f B; host-device %.1f, %.0f "
      "B; %.1f pressure iterations\n",
      optical_depth, double(c.copies) / w.steps, double(c.bytes) / w.steps,
      double(c.host_device()) / w.steps, double(c.host_device_bytes()) / w.steps,
      double(w.iterations) / w.steps);
  return w;
}

TEST(StepTransfers, UniformWaterStepCopiesOnlyTheCoarsestGrid) {
  // Each step sets the multigrid's coarsest grid up again: its 16 cells' list goes to the
  // device (int) and their matrix rows, packed there, to the host's direct solver (4 doubles a
  // cell). Each V-cycle (one per CG iteration: none where the step's residual already meets
  // the tolerance, as in the first steps of the drop's free fall) sends the coarsest grid's
  // right-hand side to the host and its solution back (16 floats each way). Measured on an
  // H100 before the rows were packed: 5 copies a step, 1984 B.
  const WaterSteps w = water_step_copies(0);
  const int cells = 16, vcycles = w.iterations;
  ASSERT_GT(w.iterations, 0);
  EXPECT_EQ(w.copies.host_device(), 2 * w.steps + 2 * vcycles);
  EXPECT_EQ(w.copies.host_device_bytes(),
            w.steps * (cells * 4 + cells * 4 * 8) + vcycles * 2 * cells * 4);
}

TEST(StepTransfers, TallCellWaterStepMakesNoExplicitCopy) {
  // The tall-cell grid, every level's matrix and the level transfers are built on the device.
  // What still crosses on a device is the coarsest level's: its rows to the host's Cholesky
  // (mirror-and-copy, 3 arrays a sub-step, which a host build does not see) and its right-hand
  // side and solution each V-cycle (between a device vector and the host's, which on a host
  // build are two host arrays). Before the hierarchy moved (2026-12-07) a host build counted 4
  // copies a step here, 47 kB: the grid's layout going back to the device.
  const WaterSteps w = water_step_copies(4);
  ASSERT_GT(w.iterations, 0);
  if (std::is_same_v<test::TestMemSpace, Kokkos::HostSpace>) {
    EXPECT_EQ(w.copies.host_device(), 0);
  } else {
    EXPECT_GT(w.copies.host_device(), 0);  // the coarsest level's, still
  }
}

}  // namespace test_step_transfers_cases
}  // namespace amphora
