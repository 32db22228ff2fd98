// The void fraction on the slabs of a DistributedQkSpace (1 and 2 ranks) against the same
// projection on one rank's whole box: each rank deposits the particles whose centres lie in its
// slab (PCM) or takes every particle near it, the others' as ghost rows (QCM, whose reference
// spheres reach across the slab boundary), and the projection is a CG over the ranks. eps
// agrees to the CG tolerance and holds the particles' volume to round-off; bounded, the same
// nodes bind.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "base/communicator.hpp"
#include "coupling/cfd_dem/void_fraction.hpp"
#include "test_backend.hpp"

namespace amphora::coupling::cfd_dem {
namespace test_void_fraction_ranks {  // named: CUDA's extended lambdas

using Exec = test::TestExecSpace;
using Fraction = VoidFraction<3, Exec>;
using Slabs = mesh::hex::DistributedQkSpace<3, Exec>;
using mesh::hex::FaceCondition;

mesh::hex::StructuredHexMesh<3> column(bool periodic_z) {
  mesh::hex::StructuredHexMesh<3> m;
  m.cells = {4, 4, 12};
  m.upper = {1.0, 1.0, 3.0};
  for (int f = 0; f < 6; ++f)
    m.faces[f] = (f < 4 || periodic_z) ? FaceCondition::periodic : FaceCondition::dirichlet;
  return m;
}

/// Centres (host, rows of 3) as device points.
Fraction::Points points(const std::vector<double>& c) {
  const int n = int(c.size() / 3);
  Fraction::Points x("x", n);
  auto h = Kokkos::create_mirror_view(x);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) h(i, d) = c[3 * i + d];
  Kokkos::deep_copy(x, h);
  return x;
}

void compare(const VoidFractionOptions& o, int degree, bool periodic_z) {
  const Communicator comm;
  const auto m = column(periodic_z);
  const int n = 400;
  const double r = 0.06;
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> all(3 * n);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) all[3 * i + d] = u(gen) * m.upper[d];
  const Exec exec;

  const mesh::hex::QkSpace<3, Exec> whole(m, degree);
  const Fraction one(whole, o);
  Fraction::Vector radius("r", n), eps_one("eps_one", whole.n_dofs());
  Kokkos::deep_copy(radius, r);
  ASSERT_TRUE(one.compute(exec, points(all), radius, n, eps_one).converged);

  // This rank's particles first, then the others as ghosts.
  const Slabs slabs(m, degree, comm);
  const double h = m.upper[2] / m.cells[2];
  const double lo = h * slabs.first_cell(), hi = h * slabs.end_cell();
  std::vector<double> mine, ghosts;
  for (int i = 0; i < n; ++i) {
    const double z = all[3 * i + 2];
    auto& to = z >= lo && z < hi ? mine : ghosts;
    to.insert(to.end(), all.begin() + 3 * i, all.begin() + 3 * i + 3);
  }
  const int owned = int(mine.size() / 3);
  mine.insert(mine.end(), ghosts.begin(), ghosts.end());
  const Fraction many(slabs, o);
  Fraction::Vector eps("eps", slabs.n_local());
  const auto res = many.compute(exec, points(mine), radius, owned, eps, n, {true, true, false});
  ASSERT_TRUE(res.converged);

  const std::vector<double> gathered = slabs.gather(eps);
  const auto ho = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), eps_one);
  ASSERT_EQ(gathered.size(), ho.extent(0));
  double err = 0.0;
  for (std::size_t i = 0; i < gathered.size(); ++i)
    err = std::max(err, std::abs(gathered[i] - ho(i)));
  EXPECT_LE(err, 1e-10) << "degree " << degree;
  // The ghost layer holds the owners' values.
  const std::vector<double> local = slabs.local_entries(gathered);
  const auto he = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), eps);
  double ghost = 0.0;
  for (std::size_t i = 0; i < local.size(); ++i)
    ghost = std::max(ghost, std::abs(local[i] - he(i)));
  EXPECT_EQ(ghost, 0.0);
  const double volume = n * 4.0 / 3.0 * M_PI * r * r * r,
               box = m.upper[0] * m.upper[1] * m.upper[2];
  const double held = box - many.integral(exec, eps);
  if (o.bounded) {  // active bounds give up the volume; the same nodes bind on every split
    EXPECT_GT(one.bounds().at_lower, 0);
    EXPECT_GT(one.bounds().at_upper, 0);
    EXPECT_EQ(many.bounds().at_lower, one.bounds().at_lower);
    EXPECT_EQ(many.bounds().at_upper, one.bounds().at_upper);
  } else {
    EXPECT_NEAR(held, volume, 1e-10 * volume);
  }
  if (comm.is_root())
    std::printf(
        "%s Q%d %s z: eps differs by %.2e from one rank's; volume held to %.2e (%d ranks)\n",
        o.method == VoidFractionMethod::qcm ? "QCM" : "PCM", degree,
        periodic_z ? "periodic" : "closed", err, std::abs(held - volume) / volume, comm.size());
}

TEST(VoidFractionRanks, PcmSmoothedMatchesOneRank) {
  VoidFractionOptions o;
  o.smoothing_length = 0.2;
  for (int k : {1, 2})
    for (bool periodic_z : {false, true}) compare(o, k, periodic_z);
}

TEST(VoidFractionRanks, QcmMatchesOneRank) {
  VoidFractionOptions o;
  o.method = VoidFractionMethod::qcm;
  for (int k : {1, 2})
    for (bool periodic_z : {false, true}) compare(o, k, periodic_z);
}

TEST(VoidFractionRanks, BoundedMatchesOneRank) {
  VoidFractionOptions o;
  o.bounded = true;                           // no smoothing: eps varies most
  o.lower_bound = 0.8, o.upper_bound = 0.95;  // tight, so that both bind
  for (int k : {1, 2})
    for (bool periodic_z : {false, true}) compare(o, k, periodic_z);
}

}  // namespace test_void_fraction_ranks
}  // namespace amphora::coupling::cfd_dem
