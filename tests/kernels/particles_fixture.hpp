#pragma once
// Random spheres in a unit box for the particle-library tests: positions, radii in [r0, 2 r0),
// global ids a shuffle of 0 .. n (so storage order and id order differ), on the host, and their
// copies in a memory space.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include <Kokkos_Core.hpp>

namespace amphora::test {

struct RandomSpheres {
  std::vector<double> x;  ///< n x 3
  std::vector<double> r;
  std::vector<std::int64_t> gid;
  int n = 0;
  double r_max = 0;

  RandomSpheres(int count, double r0, unsigned seed) : n(count), r_max(2 * r0) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    x.resize(3 * size_t(n));
    r.resize(n);
    gid.resize(n);
    for (auto& c : x) c = u(rng);
    for (auto& s : r) s = r0 * (1.0 + u(rng));
    std::iota(gid.begin(), gid.end(), 0);
    std::shuffle(gid.begin(), gid.end(), rng);
  }
  /// The same spheres stored in another order: storage slot i holds old particle perm[i].
  RandomSpheres permuted(const std::vector<int>& perm) const {
    RandomSpheres p = *this;
    for (int i = 0; i < n; ++i) {
      for (int d = 0; d < 3; ++d) p.x[3 * size_t(i) + d] = x[3 * size_t(perm[i]) + d];
      p.r[i] = r[perm[i]];
      p.gid[i] = gid[perm[i]];
    }
    return p;
  }
};

/// The spheres' centres, radii and ids in a memory space.
template <class Mem>
struct DeviceSpheres {
  Kokkos::View<double* [3], Kokkos::LayoutRight, Mem> x;
  Kokkos::View<double*, Mem> r;
  Kokkos::View<std::int64_t*, Mem> gid;
  explicit DeviceSpheres(const RandomSpheres& s) : x("x", s.n), r("r", s.n), gid("gid", s.n) {
    auto hx = Kokkos::create_mirror_view(x);
    auto hr = Kokkos::create_mirror_view(r);
    auto hg = Kokkos::create_mirror_view(gid);
    for (int i = 0; i < s.n; ++i) {
      for (int d = 0; d < 3; ++d) hx(i, d) = s.x[3 * size_t(i) + d];
      hr(i) = s.r[i];
      hg(i) = s.gid[i];
    }
    Kokkos::deep_copy(x, hx);
    Kokkos::deep_copy(r, hr);
    Kokkos::deep_copy(gid, hg);
  }
};

}  // namespace amphora::test
