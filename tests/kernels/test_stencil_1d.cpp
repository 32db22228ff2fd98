#include "kernels/stencil_1d.hpp"
#include "test_backend.hpp"

namespace amphora {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_stencil_1d_cases {

using test::TestExecSpace;
using View = Kokkos::View<double*, test::TestMemSpace>;

struct ConstantSource {
  double c;
  KOKKOS_INLINE_FUNCTION double operator()(double, double) const { return c; }
};

/// u(i) = p + q x + r x^2 at x = x0 + i dx (a free function: CUDA's extended lambdas may not
/// live in a test body, a private member).
View quadratic(const TestExecSpace& exec, int n, double x0, double dx, double p, double q,
               double r) {
  View u("u", n);
  Kokkos::parallel_for(
      "test::quadratic", kernels::RangePolicy<TestExecSpace>(exec, 0, n), KOKKOS_LAMBDA(int i) {
        const double x = x0 + i * dx;
        u(i) = p + q * x + r * x * x;
      });
  return u;
}

// D0 and D+D- are exact on quadratics, so one step of the scheme on u = p + q x + r x^2 gives
// u + dt (-a (q + 2 r x) + 2 nu r + f) to round-off.
TEST(Stencil1D, ExactOnQuadratics) {
  const TestExecSpace exec;
  const int n = 257;
  const double x0 = -0.3, dx = 1.0 / 256, a = 0.7, nu = 0.05, dt = 1e-3, f = 0.25;
  const double p = 0.5, q = -1.25, r = 2.0;
  View u = quadratic(exec, n, x0, dx, p, q, r), v("v", n);
  kernels::stencil::advection_diffusion_ftcs(exec, u, v, 1, n - 1, x0, dx, a, nu, 0.0, dt,
                                             ConstantSource{f});
  auto uh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), u);
  auto vh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), v);
  for (int i = 1; i < n - 1; ++i) {
    const double x = x0 + i * dx;
    const double expected = uh(i) + dt * (-a * (q + 2 * r * x) + 2 * nu * r + f);
    EXPECT_NEAR(vh(i), expected, 1e-13) << "i = " << i;
  }
  EXPECT_EQ(vh(0), 0.0);  // outside [first, last): untouched
  EXPECT_EQ(vh(n - 1), 0.0);
}

TEST(Stencil1D, StabilityLimit) {
  // Diffusion-limited and advection-limited regimes of dt <= min(h^2/(2 nu), 2 nu / a^2).
  EXPECT_DOUBLE_EQ(kernels::stencil::advection_diffusion_ftcs_dt_limit(1.0, 0.1, 0.01), 0.0005);
  EXPECT_DOUBLE_EQ(kernels::stencil::advection_diffusion_ftcs_dt_limit(10.0, 0.01, 0.1), 0.0002);
  EXPECT_DOUBLE_EQ(kernels::stencil::advection_diffusion_ftcs_dt_limit(0.0, 0.5, 0.1), 0.01);
}

}  // namespace test_stencil_1d_cases
using namespace test_stencil_1d_cases;
}  // namespace amphora
