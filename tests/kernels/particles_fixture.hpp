#pragma once
// Random spheres in a unit box for the particle-library tests: positions, radii in [r0, 2 r0),
// global ids a shuffle of 0 .. n (so storage order and id order differ), all on the host.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

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

}  // namespace amphora::test
