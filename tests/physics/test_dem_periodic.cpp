// Periodic DEM domains: particles leaving through a periodic face re-enter at the opposite one
// and meet the images of those there. At every step the contacts the force kernel sees equal a
// brute-force search over nearest images; momentum is conserved across the faces; a pair
// colliding across a face moves as the same pair inside the box; a short periodic box is refused.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "physics/dem/dem_system.hpp"
#include "physics/dem/insertion.hpp"
#include "shaken_packing.hpp"
#include "test_backend.hpp"

namespace amphora::physics::dem {
namespace test_dem_periodic {

using System = DemSystem<test::TestExecSpace>;
using Pairs = std::vector<std::pair<std::int64_t, std::int64_t>>;

constexpr double kRadius = 1e-3;

/// The shaken packing's box (shaken_packing.hpp) without gravity.
DemConfig periodic_config(double L, std::array<bool, 3> periodic) {
  DemConfig c = test_systems::shaken_config(L, periodic);
  c.gravity = {0, 0, 0};
  return c;
}

/// n^3 spheres (radius 1 mm +-30 %) on a jittered lattice of spacing L / n whose first layers lie
/// on the box's lower faces (half of them outside, to be wrapped in), with random velocities of
/// up to `speed` / 2. Directions with `inside` set keep their layers half a spacing off the faces.
std::vector<ParticleSpec> lattice(int n, double L, double speed,
                                  std::array<bool, 3> inside = {false, false, false}) {
  std::vector<ParticleSpec> out;
  const double a = L / n;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        ParticleSpec p;
        p.gid = static_cast<std::int64_t>(out.size());
        const int idx[3] = {i, j, k};
        for (int d = 0; d < 3; ++d) {
          p.x[d] = (idx[d] + (inside[d] ? 0.5 : 0.0)) * a +
                   0.3 * kRadius * (uniform01(3, d, p.gid) - 0.5);
          p.v[d] = speed * (uniform01(11, d, p.gid) - 0.5);
        }
        p.radius = kRadius * (1 + 0.3 * (2 * uniform01(5, 0, p.gid) - 1));
        out.push_back(p);
      }
  return out;
}

/// Pairs (gid order) of owned particles closer than their radii's sum through the nearest image.
Pairs brute_force(const System& s) {
  const auto& p = s.particles();
  auto x = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.x);
  auto r = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.radius);
  auto gid = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.gid);
  const DemConfig& c = s.config();
  Pairs out;
  for (int i = 0; i < p.n_owned; ++i)
    for (int j = 0; j < p.n_owned; ++j) {
      if (gid(i) >= gid(j)) continue;
      double d2 = 0;
      for (int d = 0; d < 3; ++d) {
        const double L = c.domain_hi[d] - c.domain_lo[d];
        double dx = x(i, d) - x(j, d);
        if (c.periodic[d]) dx -= L * std::round(dx / L);
        d2 += dx * dx;
      }
      if (d2 < (r(i) + r(j)) * (r(i) + r(j))) out.emplace_back(gid(i), gid(j));
    }
  std::sort(out.begin(), out.end());
  return out;
}

/// Owned particles' positions and velocities by gid (host).
std::map<std::int64_t, std::array<double, 6>> states(const System& s) {
  const auto& p = s.particles();
  auto x = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.x);
  auto v = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.v);
  auto gid = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.gid);
  std::map<std::int64_t, std::array<double, 6>> out;
  for (int i = 0; i < p.n_owned; ++i)
    out[gid(i)] = {x(i, 0), x(i, 1), x(i, 2), v(i, 0), v(i, 1), v(i, 2)};
  return out;
}

/// Steps s `steps` times; after each the Verlet list's contacts must be the nearest-image ones.
/// Returns how many particles crossed a face (their position jumped by over half the box).
int expect_image_contacts_at_every_step(System& s, int steps) {
  const double L = s.config().domain_hi[0];
  auto before = states(s);
  long long contacts = 0;
  int crossed = 0;
  for (int it = 0; it < steps; ++it) {
    s.step();
    auto seen = s.contact_pairs();
    std::sort(seen.begin(), seen.end());
    const auto truth = brute_force(s);
    EXPECT_EQ(seen, truth) << "step " << it;
    if (seen != truth) break;
    contacts += static_cast<long long>(truth.size());
    const auto now = states(s);
    for (const auto& [g, st] : now)
      for (int d = 0; d < 3; ++d) crossed += std::abs(st[d] - before.at(g)[d]) > 0.5 * L;
    before = now;
  }
  EXPECT_GT(contacts, 500) << "the packing must have contacts to check";
  EXPECT_GT(s.timers().rebuilds, 3) << "the lists must have been rebuilt along the way";
  return crossed;
}

TEST(DemPeriodic, ContactsEqualNearestImageSearchAtEveryStep) {
  const int n = 12;
  const double L = n * 2.4 * kRadius;  // spacing 2.4 mm: many contacts, also across the faces
  System s(periodic_config(L, {true, true, true}), Communicator());
  s.add_particles(lattice(n, L, 0.6));
  EXPECT_GT(expect_image_contacts_at_every_step(s, 60), 50) << "particles must cross the faces";
  EXPECT_EQ(s.global_count(), n * n * n) << "periodic faces lose no particle";
}

TEST(DemPeriodic, ContactsEqualNearestImageSearchWithWallsAcrossZ) {
  const int n = 10;
  const double L = n * 2.4 * kRadius;
  DemConfig c = periodic_config(L, {true, true, false});
  c.gravity = {0, 0, -9.81};
  System s(c, Communicator());
  s.add_particles(lattice(n, L, 0.6, {false, false, true}));
  EXPECT_GT(expect_image_contacts_at_every_step(s, 60), 30);
}

/// Total momentum sum m v (host), and the sum of |m v| as its scale.
std::array<double, 4> momentum(const System& s) {
  const auto& p = s.particles();
  auto v = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.v);
  auto m = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.mass);
  std::array<double, 4> out{0, 0, 0, 0};
  for (int i = 0; i < p.n_owned; ++i)
    for (int d = 0; d < 3; ++d) {
      out[d] += m(i) * v(i, d);
      out[3] += m(i) * std::abs(v(i, d));
    }
  return out;
}

// Each pair across a face is evaluated twice (by a particle and by its partner's image, each
// for its own particle): its two halves must still cancel, to round-off.
// Both force loops: by slabs (host spaces' default) and by particle (devices').
TEST(DemPeriodic, MomentumIsConservedAcrossTheFaces) {
  const int n = 10;
  const double L = n * 2.4 * kRadius;
  for (const bool by_particle : {false, true}) {
    System s(periodic_config(L, {true, true, true}), Communicator());
    s.set_forces_by_particle(by_particle);
    s.add_particles(lattice(n, L, 0.6));
    const auto p0 = momentum(s);
    for (int it = 0; it < 200; ++it) s.step();
    const auto p1 = momentum(s);
    for (int d = 0; d < 3; ++d)
      EXPECT_NEAR(p1[d], p0[d], 1e-12 * p0[3])
          << "momentum along "
          << "xyz"[d] << (by_particle ? ", by particle" : ", by slabs");
    EXPECT_GT(s.diagnostics().contacts, 100);
  }
}

/// Two spheres meeting off-centre (friction, spin, history), their midpoint at `centre`.
std::vector<ParticleSpec> glancing_pair(const std::array<double, 3>& centre) {
  std::vector<ParticleSpec> out(2);
  for (int k = 0; k < 2; ++k) {
    const double sign = k == 0 ? -1.0 : 1.0;
    ParticleSpec& p = out[k];
    p.gid = k;
    p.radius = kRadius;
    p.x[0] = centre[0] + sign * 1.05 * kRadius;
    p.x[1] = centre[1] + sign * 0.4 * kRadius;
    p.x[2] = centre[2] - sign * 0.2 * kRadius;
    p.v[0] = -sign * 0.2;
    p.omega[2] = sign * 30.0;
  }
  return out;
}

// The same glancing collision across the corner of a periodic box (x and y faces) and in the
// middle of it: the relative motion is the same to round-off of the positions' size.
TEST(DemPeriodic, PairAcrossACornerMovesAsThePairInside) {
  const double L = 0.012;
  const DemConfig c = periodic_config(L, {true, true, false});
  System across(c, Communicator()), inside(c, Communicator());
  across.add_particles(glancing_pair({0.0, L, 0.5 * L}));
  inside.add_particles(glancing_pair({0.5 * L, 0.5 * L, 0.5 * L}));
  double max_contacts = 0;
  for (int it = 0; it < 400; ++it) {
    across.step();
    inside.step();
    max_contacts = std::max<double>(max_contacts, across.diagnostics().contacts);
  }
  EXPECT_GE(max_contacts, 1) << "the spheres must have met across the corner";
  const auto a = states(across), b = states(inside);
  for (int d = 0; d < 3; ++d) {
    double rel_a = a.at(1)[d] - a.at(0)[d], rel_b = b.at(1)[d] - b.at(0)[d];
    if (c.periodic[d]) rel_a -= L * std::round(rel_a / L);
    EXPECT_NEAR(rel_a, rel_b, 1e-12) << "separation along "
                                     << "xyz"[d];
    for (int k = 0; k < 2; ++k)
      EXPECT_NEAR(a.at(k)[3 + d], b.at(k)[3 + d], 1e-9) << "velocity of " << k << " along " << d;
  }
  EXPECT_GT(std::abs(b.at(0)[4]), 1e-3) << "friction must have turned the velocities";
}

TEST(DemPeriodic, PeriodicBoxShorterThanTwoCutoffsIsRejected) {
  DemConfig c = periodic_config(0.012, {false, true, false});
  c.domain_hi[1] = 4.0 * kRadius;  // cutoff 2 x 1.3 + 0.3 = 2.9 mm: two of them are 5.8 mm
  try {
    System s(c, Communicator());
    FAIL() << "a short periodic box was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("periodic along y but 0.004 m long"), std::string::npos)
        << e.what();
  }
}

}  // namespace test_dem_periodic
}  // namespace amphora::physics::dem
