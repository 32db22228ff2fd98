#include <cmath>
#include <limits>

#include "kernels/reductions.hpp"
#include "test_backend.hpp"

namespace amphora {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_reductions_cases {

using test::TestExecSpace;
using View = Kokkos::View<double*, test::TestMemSpace>;

View ramp(int n) {
  View x("x", n);
  Kokkos::parallel_for(
      "test::ramp", kernels::RangePolicy<TestExecSpace>(0, n),
      KOKKOS_LAMBDA(int i) { x(i) = double((i * 37) % n) - 0.5 * n; });
  Kokkos::fence();
  return x;
}

void set(const View& x, int i, double v) { Kokkos::deep_copy(Kokkos::subview(x, i), v); }

TEST(Reductions, MinMax) {
  const int n = 10007;  // prime, so (i * 37) % n is a permutation of 0..n-1
  const auto mm = kernels::reduce::min_max(TestExecSpace(), ramp(n));
  EXPECT_EQ(mm.min, -0.5 * n);
  EXPECT_EQ(mm.max, double(n - 1) - 0.5 * n);
}

TEST(Reductions, FirstNonFiniteFindsTheSmallestIndex) {
  const TestExecSpace exec;
  View x = ramp(50000);
  EXPECT_EQ(kernels::reduce::first_nonfinite(exec, x), -1);
  set(x, 41234, std::numeric_limits<double>::infinity());
  EXPECT_EQ(kernels::reduce::first_nonfinite(exec, x), 41234);
  set(x, 1234, std::nan(""));
  set(x, 30000, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(kernels::reduce::first_nonfinite(exec, x), 1234);
  set(x, 0, std::nan(""));
  EXPECT_EQ(kernels::reduce::first_nonfinite(exec, x), 0);
}

TEST(Reductions, FirstNonFiniteOfEmptyView) {
  EXPECT_EQ(kernels::reduce::first_nonfinite(TestExecSpace(), View("x", 0)), -1);
}

}  // namespace test_reductions_cases
using namespace test_reductions_cases;
}  // namespace amphora
