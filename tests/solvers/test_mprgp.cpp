// MPRGP (solvers/mprgp.hpp) on the 1D obstacle problem with both bounds active: it matches
// projected Gauss-Seidel iterated to convergence (a different method with the same unique
// minimiser), meets the KKT conditions, and leaves a feasible unconstrained solution as it is.
#include <algorithm>
#include <cmath>
#include <vector>

#include "solvers/conjugate_gradient.hpp"
#include "solvers/mprgp.hpp"
#include "laplacian_1d.hpp"
#include "test_backend.hpp"

namespace amphora::solvers {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_mprgp_cases {

using test::TestExecSpace;
using View = Kokkos::View<double*, test::TestMemSpace>;

constexpr int n = 60;
constexpr double shift = 0.2;

View device(const std::vector<double>& v) {
  View d("v", v.size());
  auto h = Kokkos::create_mirror_view(d);
  for (std::size_t i = 0; i < v.size(); ++i) h(i) = v[i];
  Kokkos::deep_copy(d, h);
  return d;
}

std::vector<double> host(const View& v) {
  auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), v);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

/// A load that pushes the unconstrained solution past both bounds.
std::vector<double> load(double amplitude) {
  std::vector<double> b(n);
  for (int i = 0; i < n; ++i) b[i] = amplitude * std::sin(2.0 * M_PI * (i + 0.5) / n);
  return b;
}

/// The minimiser by projected Gauss-Seidel (Cryer 1971): x_i = clamp of its row's solution.
std::vector<double> projected_gauss_seidel(const std::vector<double>& b, double lo, double hi) {
  std::vector<double> x(n, 0.0);
  for (int sweep = 0; sweep < 2000; ++sweep) {
    for (int i = 0; i < n; ++i) {
      const double left = i > 0 ? x[i - 1] : 0.0, right = i < n - 1 ? x[i + 1] : 0.0;
      x[i] = std::clamp((b[i] + left + right) / (2.0 + shift), lo, hi);
    }
  }
  return x;
}

struct Solved {
  BoxResult result;
  std::vector<double> x, unconstrained;
};

Solved solve(const std::vector<double>& rhs, const BoxControl& control) {
  const TestExecSpace exec;
  const test::Laplacian1D A{shift};
  const View b = device(rhs), x("x", n);
  SolverControl cg;
  cg.relative_tolerance = 1e-14;
  cg.max_iterations = 10 * n;
  EXPECT_TRUE(conjugate_gradient(exec, A, b, x, cg).converged);
  Solved s;
  s.unconstrained = host(x);
  BoxWorkspace<View> work;
  s.result = mprgp(exec, A, b, x, control, OneRank{n}, work);
  s.x = host(x);
  return s;
}

BoxControl control(double lo, double hi) {
  BoxControl c;
  c.lower = lo;
  c.upper = hi;
  c.relative_tolerance = 1e-12;  // the unconstrained solve's is 1e-14
  c.step = 1.9 / (4.0 + shift);  // lambda_max < 4 + shift (Gershgorin)
  return c;
}

TEST(Mprgp, MatchesProjectedGaussSeidelWithBothBoundsActive) {
  const auto b = load(0.5);
  const Solved s = solve(b, control(-0.9, 0.6));
  ASSERT_TRUE(s.result.converged) << s.result.iterations;
  const auto [lo, hi] = std::minmax_element(s.unconstrained.begin(), s.unconstrained.end());
  ASSERT_LT(*lo, -0.9);  // the bounds bind
  ASSERT_GT(*hi, 0.6);
  EXPECT_GT(s.result.at_lower, 0);
  EXPECT_GT(s.result.at_upper, 0);
  const auto reference = projected_gauss_seidel(b, -0.9, 0.6);
  // cond(A) <= 4.2 / 0.2: a projected gradient of 1e-12 |b| bounds the error near 1e-10.
  for (int i = 0; i < n; ++i) EXPECT_NEAR(s.x[i], reference[i], 1e-10) << i;
}

TEST(Mprgp, MeetsTheKktConditions) {
  const auto b = load(0.5);
  const Solved s = solve(b, control(-0.9, 0.6));
  // g = A x - b: zero where x is free, >= 0 at the lower bound, <= 0 at the upper one.
  long lower = 0, upper = 0;
  for (int i = 0; i < n; ++i) {
    const double left = i > 0 ? s.x[i - 1] : 0.0, right = i < n - 1 ? s.x[i + 1] : 0.0;
    const double g = (2.0 + shift) * s.x[i] - left - right - b[i];
    EXPECT_GE(s.x[i], -0.9 - 1e-12);
    EXPECT_LE(s.x[i], 0.6 + 1e-12);
    if (s.x[i] == -0.9) {
      EXPECT_GE(g, -1e-12) << i;
      ++lower;
    } else if (s.x[i] == 0.6) {
      EXPECT_LE(g, 1e-12) << i;
      ++upper;
    } else {
      EXPECT_NEAR(g, 0.0, 1e-12) << i;
    }
  }
  EXPECT_EQ(lower, s.result.at_lower);
  EXPECT_EQ(upper, s.result.at_upper);
}

TEST(Mprgp, LeavesAFeasibleSolutionAsItIs) {
  const Solved s = solve(load(0.05), control(-0.9, 0.6));
  ASSERT_TRUE(s.result.converged);
  EXPECT_EQ(s.result.iterations, 0);
  EXPECT_EQ(s.result.at_lower + s.result.at_upper, 0);
  EXPECT_EQ(s.x, s.unconstrained);
}

}  // namespace test_mprgp_cases
}  // namespace amphora::solvers
