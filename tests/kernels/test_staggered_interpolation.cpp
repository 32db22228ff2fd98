// The velocity at a MAC sample from the neighbouring samples (velocity_at_sample, the first step
// of every semi-Lagrangian trace) equals trilinear interpolation at that sample's position bit
// for bit, for every staggering, at every sample including those on the box faces, also for a
// grid one cell thick.
#include <random>
#include <vector>

#include "kernels/host_vector.hpp"
#include "kernels/mac/staggered_interpolation.hpp"
#include "test_backend.hpp"

namespace amphora::kernels::mac {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_staggered_interpolation_cases {

using Exec = test::TestExecSpace;
using Mem = test::TestMemSpace;

/// Samples of staggering s where velocity_at_sample differs from trilinear interpolation (a
/// free function: CUDA's extended lambdas may not live in a test body, a private member).
template <class V>
int samples_differing(const kernels::mac::MacGrid& g, Staggering s, const V& u, const V& v,
                      const V& w) {
  const int st = static_cast<int>(s);
  const int ex = g.nx + (st == 0), ey = g.ny + (st == 1), ez = g.nz + (st == 2);
  Kokkos::View<int*, Mem> differ("differ", 1);
  Kokkos::parallel_for(
      "test::velocity_at_sample",
      Kokkos::MDRangePolicy<Exec, Kokkos::Rank<3>>({0, 0, 0}, {ez, ey, ex}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        const double q[3] = {i + (st == 0 ? 0.0 : 0.5), j + (st == 1 ? 0.0 : 0.5),
                             k + (st == 2 ? 0.0 : 0.5)};
        double a[3], b[3];
        velocity_at_cells(g, u, v, w, q, a);
        velocity_at_sample(g, s, i, j, k, u, v, w, b);
        for (int e = 0; e < 3; ++e)
          if (a[e] != b[e]) Kokkos::atomic_add(&differ(0), 1);
      });
  return Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), differ)(0);
}

TEST(StaggeredInterpolation, VelocityAtASampleIsTrilinearInterpolationThere) {
  for (const kernels::mac::MacGrid g : {kernels::mac::MacGrid{5, 4, 3, 0.1, {0, 0, 0}},
                                        kernels::mac::MacGrid{1, 3, 2, 0.2, {0.5, 0, 0}}}) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::vector<double> f[3];
    for (auto& c : f) {
      c.resize(g.padded_size());
      for (auto& x : c) x = U(rng);
    }
    const auto u = kernels::to_view<Mem>(f[0]), v = kernels::to_view<Mem>(f[1]),
               w = kernels::to_view<Mem>(f[2]);
    for (int st = -1; st < 3; ++st) {
      const auto s = static_cast<Staggering>(st);
      const int differ = samples_differing(g, s, u, v, w);
      EXPECT_EQ(differ, 0) << "staggering " << st << " on " << g.nx << "x" << g.ny << "x" << g.nz;
    }
  }
}

}  // namespace test_staggered_interpolation_cases
using namespace test_staggered_interpolation_cases;
}  // namespace amphora::kernels::mac
