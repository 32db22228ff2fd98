// Contact detection: at every step of a 10^4-particle polydisperse packing in motion, the
// contacts the force kernel sees through the Verlet list are exactly those of a brute-force
// all-pairs search; and tangential history survives list rebuilds.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "physics/dem/dem_system.hpp"
#include "physics/dem/insertion.hpp"
#include "shaken_packing.hpp"
#include "test_backend.hpp"

namespace amphora::physics::dem {
namespace {

using System = DemSystem<test::TestExecSpace>;

std::vector<std::pair<std::int64_t, std::int64_t>> brute_force(const System& s) {
  const auto& p = s.particles();
  auto x = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.x);
  auto r = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.radius);
  auto gid = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.gid);
  std::vector<std::pair<std::int64_t, std::int64_t>> out;
  for (int i = 0; i < p.n_owned; ++i)
    for (int j = 0; j < p.n_owned; ++j) {
      if (gid(i) >= gid(j)) continue;
      double d2 = 0;
      for (int d = 0; d < 3; ++d) d2 += (x(i, d) - x(j, d)) * (x(i, d) - x(j, d));
      if (d2 < (r(i) + r(j)) * (r(i) + r(j))) out.emplace_back(gid(i), gid(j));
    }
  std::sort(out.begin(), out.end());
  return out;
}

/// 10^4 particles shaken in a walled box (tests/physics/shaken_packing.hpp).
System shaken_packing() { return test_systems::shaken_packing<test::TestExecSpace>(10000, 0.066); }

/// Steps s 60 times; after each step the Verlet list's contacts must be the all-pairs ones.
void expect_all_pairs_contacts_at_every_step(System& s) {
  long long contacts = 0;
  for (int it = 0; it < 60; ++it) {
    s.step();
    auto seen = s.contact_pairs();
    std::sort(seen.begin(), seen.end());
    const auto truth = brute_force(s);
    ASSERT_EQ(seen, truth) << "step " << it;
    contacts += static_cast<long long>(truth.size());
  }
  EXPECT_GT(contacts, 1000) << "the packing must have contacts to check";
  EXPECT_GT(s.timers().rebuilds, 3) << "the lists must have been rebuilt along the way";
}

TEST(DemContactDetection, VerletContactsEqualAllPairsAtEveryStep) {
  System s = shaken_packing();
  expect_all_pairs_contacts_at_every_step(s);
}

// CFD-DEM holds the fluid's force on each particle over N DEM sub-steps (CfdDemCoupling): under
// held forces of up to three times each particle's weight in random directions, the contacts
// seen through the Verlet list still equal the all-pairs search at every sub-step.
TEST(DemContactDetection, HeldForcesOverSubstepsMissNoContact) {
  System s = shaken_packing();
  const int n = s.particles().n_owned;
  auto f = s.external_force();
  auto h = Kokkos::create_mirror_view(f);
  auto r = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), s.particles().radius);
  const double rho = s.config().materials[0].density;
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      h(i, c) = u(gen) * rho * 4.0 / 3.0 * M_PI * std::pow(r(i), 3) * 9.81;
  Kokkos::deep_copy(f, h);
  expect_all_pairs_contacts_at_every_step(s);
}

/// The owned particles' positions by global id.
std::map<std::int64_t, std::array<double, 3>> positions_by_gid(const System& s) {
  const auto x = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), s.particles().x);
  const auto g = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), s.particles().gid);
  std::map<std::int64_t, std::array<double, 3>> out;
  for (int i = 0; i < s.particles().n_owned; ++i) out[g(i)] = {x(i, 0), x(i, 1), x(i, 2)};
  return out;
}

// The devices' schedule (one work item per particle, each pair evaluated by both) against the
// host's (slabs of rows): the same contacts at every step and the same trajectories to
// round-off (the force sums run in another order), springs and rebuilds included.
TEST(DemContactDetection, ParticleScheduleEqualsSlabScheduleToRoundOff) {
  System slabs = shaken_packing(), particles = shaken_packing(), switched = shaken_packing();
  slabs.set_forces_by_particle(false);
  particles.set_forces_by_particle(true);
  switched.set_forces_by_particle(true);  // to slabs half way: it orders its rows then
  double worst = 0;
  for (int it = 0; it < 60; ++it) {
    if (it == 31) switched.set_forces_by_particle(false);
    slabs.step();
    particles.step();
    switched.step();
    auto a = slabs.contact_pairs(), b = particles.contact_pairs(), c = switched.contact_pairs();
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    std::sort(c.begin(), c.end());
    ASSERT_EQ(a, b) << "step " << it;
    ASSERT_EQ(a, c) << "step " << it;
  }
  const auto xa = positions_by_gid(slabs), xb = positions_by_gid(particles),
             xc = positions_by_gid(switched);
  ASSERT_EQ(xa.size(), xb.size());
  ASSERT_EQ(xa.size(), xc.size());
  for (const auto& [gid, x] : xa)
    for (int d = 0; d < 3; ++d) {
      worst = std::max(worst, std::abs(x[d] - xb.at(gid)[d]));
      worst = std::max(worst, std::abs(x[d] - xc.at(gid)[d]));
    }
  // positions of order 1e-2 m: 60 steps of round-off stay far below 1e-12 m; a wrong sign or a
  // missing pair in either schedule moves a particle by ~1e-7 m or more within these steps
  EXPECT_LT(worst, 1e-12);
  EXPECT_GT(particles.timers().rebuilds, 3);
}

TEST(DemContactDetection, TangentialHistorySurvivesRebuilds) {
  // Two identical runs of a sheared pair, one forcing a list rebuild (sort, records) at every
  // step: the trajectories must agree to the last bit.
  auto run = [](bool rebuild_every_step) {
    Material m;
    m.youngs_modulus = 1e6;
    m.friction = 0.5;
    DemConfig c;
    c.materials = {m};
    c.gravity = {0, 0, 0};
    c.domain_lo = {-0.01, -0.01, -0.01};
    c.domain_hi = {0.01, 0.01, 0.01};
    c.max_radius = 1e-3;
    c.skin = 2e-4;
    c.dt = 1e-6;
    System s(c, Communicator());
    ParticleSpec a, b, d;
    a.radius = b.radius = d.radius = 1e-3;
    a.x[0] = -0.99e-3;
    b.x[0] = 0.99e-3;
    b.gid = 1;
    a.v[1] = 0.05;
    b.v[1] = -0.05;
    d.x[2] = 5e-3;  // a third, free particle so sorting has something to reorder
    d.gid = 2;
    s.add_particles({d, b, a});
    for (int i = 0; i < 400; ++i) {
      if (rebuild_every_step) s.invalidate();
      s.step();
    }
    auto v = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), s.particles().v);
    auto g = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), s.particles().gid);
    std::vector<double> out(9);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) out[3 * g(i) + k] = v(i, k);
    return out;
  };
  const auto plain = run(false), rebuilt = run(true);
  EXPECT_EQ(plain, rebuilt);
  EXPECT_NE(plain[1], 0.05) << "friction must have acted";
}

TEST(DemContactDetection, ParticleOutsideAWallIsRejected) {
  DemConfig c;
  c.materials = {Material{}};
  c.max_radius = 1e-3;
  c.skin = 2e-4;
  Wall floor;
  c.walls = {floor};
  System s(c, Communicator());
  ParticleSpec p;
  p.radius = 1e-3;
  p.x[2] = -0.01;  // below the floor z = 0
  try {
    s.add_particles({p});
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lies outside wall 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace amphora::physics::dem
