// The pair loops of kernels/particles with a toy pair law (linear springs between touching
// spheres, a pair state counting the evaluations): both schedules give the all-pairs forces,
// the slab schedule gives the same bits whatever the storage order, and each touching pair's
// state is advanced once per evaluation and reset when the pair parts.
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include "kernels/particles/pair_loop.hpp"
#include "kernels/particles/verlet_list.hpp"
#include "particles_fixture.hpp"
#include "test_backend.hpp"

namespace amphora::kernels::particles {
namespace {

using Exec = test::TestExecSpace;
using Mem = test::TestMemSpace;
using Vec = Kokkos::View<double* [3], Kokkos::LayoutRight, Mem>;

/// f_a = -k (r_a + r_b - |dx|) dx / |dx| on a, minus that on b; gravity-like body term g.
struct SpringLaw {
  struct Particle {
    double x[3], r;
  };
  struct Sum {
    double F[3];
  };
  struct State {
    double count;
  };
  struct Effect {
    double F[3];
  };
  Rows3<const double> x;
  Rows3<double> f;
  Kokkos::View<const double*, Mem> rad;
  Kokkos::View<const double*, Mem> state_in;
  Kokkos::View<double*, Mem> state_out;
  double k, g;

  KOKKOS_INLINE_FUNCTION Particle load(int i) const {
    return {{x(i, 0), x(i, 1), x(i, 2)}, rad(i)};
  }
  KOKKOS_INLINE_FUNCTION void body(int, const Particle&, Sum& s) const { s.F[2] = -g; }
  KOKKOS_INLINE_FUNCTION State state(int e) const { return {state_in(e)}; }
  KOKKOS_INLINE_FUNCTION void set_state(int e, const State& s) const { state_out(e) = s.count; }
  KOKKOS_INLINE_FUNCTION void prefetch(int, int) const {}
  KOKKOS_INLINE_FUNCTION Effect interact(const Particle&, int, double, const double dx[3],
                                         double d2, double rsum, State& s) const {
    const double d = kernels::math::sqrt(d2), push = k * (rsum - d) / d;
    s.count += 1.0;
    return {{-push * dx[0], -push * dx[1], -push * dx[2]}};
  }
  KOKKOS_INLINE_FUNCTION void add_first(const Effect& e, const Particle&, Sum& s) const {
    for (int d = 0; d < 3; ++d) s.F[d] += e.F[d];
  }
  KOKKOS_INLINE_FUNCTION void add_second(const Effect& e, double, Sum& s) const {
    for (int d = 0; d < 3; ++d) s.F[d] -= e.F[d];
  }
  KOKKOS_INLINE_FUNCTION void add_second_to(int b, const Effect& e, double) const {
    for (int d = 0; d < 3; ++d) f(b, d) -= e.F[d];
  }
  KOKKOS_INLINE_FUNCTION void add(int i, const Sum& s) const {
    for (int d = 0; d < 3; ++d) f(i, d) += s.F[d];
  }
  KOKKOS_INLINE_FUNCTION void store(int i, const Sum& s) const {
    for (int d = 0; d < 3; ++d) f(i, d) = s.F[d];
  }
};

/// The spheres on the device with their lists, schedule and a state per list entry.
struct Pairs : test::DeviceSpheres<Mem> {
  int n;
  Vec f;
  Kokkos::View<double*, Mem> state, state_next;
  NeighborList<Mem> list;
  Kokkos::View<int*, Mem> half;
  SlabSchedule<Mem> schedule;
  Kokkos::View<unsigned*, Mem> live;

  explicit Pairs(const test::RandomSpheres& s) : test::DeviceSpheres<Mem>(s), n(s.n), f("f", s.n) {
    const double skin = 0.2 * s.r_max, lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const CellGrid cells = CellGrid::covering(lo, hi, 2 * s.r_max + skin);
    const auto bins = bin_points(Exec(), cells, x, n);
    list = build_verlet_list(Exec(), cells, bins, x, r, gid, n, skin);
    half = half_starts(Exec(), list, gid);
    schedule = slab_schedule(Exec(), cells, x, n, gid);
    state = Kokkos::View<double*, Mem>("state", list.neighbors.extent(0));
    state_next = Kokkos::View<double*, Mem>("state_next", list.neighbors.extent(0));
    live = Kokkos::View<unsigned*, Mem>("live", n);
  }
  SpringLaw law(bool by_particle) const {
    return {Rows3<const double>(x),
            Rows3<double>(f),
            r,
            state,
            by_particle ? state_next : state,
            100.0,
            1.0};
  }
  HalfPairList<Mem> pairs() const { return {list.offsets, list.neighbors, half}; }
  Spheres<Mem> spheres() const { return {Rows3<const double>(x), r}; }
  /// Forces by gid after one evaluation by slabs (by_particle = false) or by particle.
  std::map<std::int64_t, std::array<double, 3>> forces(bool by_particle) {
    Kokkos::deep_copy(f, 0.0);
    if (by_particle) {
      pair_sums_by_particle(Exec(), pairs(), spheres(), gid, n, n, law(true));
      std::swap(state, state_next);
    } else {
      pair_sums_by_slabs(Exec(), schedule, pairs(), spheres(), n, live, law(false));
    }
    auto hf = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), f);
    auto hg = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), gid);
    std::map<std::int64_t, std::array<double, 3>> out;
    for (int i = 0; i < n; ++i) out[hg(i)] = {hf(i, 0), hf(i, 1), hf(i, 2)};
    return out;
  }
};

/// All-pairs forces of the spring law, by gid.
std::map<std::int64_t, std::array<double, 3>> all_pairs(const test::RandomSpheres& s, double k,
                                                        double g, long long& touching) {
  std::map<std::int64_t, std::array<double, 3>> out;
  touching = 0;
  for (int i = 0; i < s.n; ++i) {
    std::array<double, 3> F{0, 0, -g};
    for (int j = 0; j < s.n; ++j) {
      if (j == i) continue;
      double dx[3], d2 = 0;
      for (int d = 0; d < 3; ++d) {
        dx[d] = s.x[3 * size_t(j) + d] - s.x[3 * size_t(i) + d];
        d2 += dx[d] * dx[d];
      }
      const double rsum = s.r[i] + s.r[j], dist = std::sqrt(d2);
      if (dist >= rsum) continue;
      touching += s.gid[i] < s.gid[j];
      for (int d = 0; d < 3; ++d) F[d] -= k * (rsum - dist) / dist * dx[d];
    }
    out[s.gid[i]] = F;
  }
  return out;
}

TEST(ParticlePairLoop, BothSchedulesGiveAllPairsForces) {
  const test::RandomSpheres s(3000, 0.02, 3);
  long long touching = 0;
  const auto truth = all_pairs(s, 100.0, 1.0, touching);
  ASSERT_GT(touching, 1000) << "the test needs touching pairs";
  for (const bool by_particle : {false, true}) {
    Pairs p(s);
    const auto got = p.forces(by_particle);
    double worst = 0;
    for (const auto& [g, F] : truth)
      for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(got.at(g)[d] - F[d]));
    EXPECT_LT(worst, 1e-13) << (by_particle ? "by particle" : "by slabs");
    // every touching pair's state counted one evaluation, in the entry of its smaller gid
    auto st = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.state);
    EXPECT_EQ(std::accumulate(st.data(), st.data() + st.extent(0), 0.0), double(touching));
  }
}

TEST(ParticlePairLoop, SlabSumsDoNotDependOnStorageOrder) {
  const test::RandomSpheres s(3000, 0.02, 5);
  std::vector<int> perm(s.n);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(1));
  Pairs a(s), b(s.permuted(perm));
  EXPECT_EQ(a.forces(false), b.forces(false)) << "the same bits for every particle";
  EXPECT_EQ(a.forces(true), b.forces(true)) << "by particle too";
}

TEST(ParticlePairLoop, StatesResetWhenPairsPart) {
  test::RandomSpheres s(2000, 0.02, 9);
  Pairs p(s);
  p.forces(false);
  p.forces(false);  // touching pairs now count 2
  auto st = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.state);
  double twos = 0;
  for (size_t e = 0; e < st.extent(0); ++e) twos += st(e) == 2.0;
  EXPECT_GT(twos, 100);
  // shrink every sphere so no pair touches (the lists stay): every state resets
  Kokkos::deep_copy(p.r, 1e-6);
  p.forces(false);
  Kokkos::deep_copy(st, p.state);
  for (size_t e = 0; e < st.extent(0); ++e) ASSERT_EQ(st(e), 0.0) << "entry " << e;
}

}  // namespace
}  // namespace amphora::kernels::particles
