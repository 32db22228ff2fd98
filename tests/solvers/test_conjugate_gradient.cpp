// CG on the 1D Dirichlet Laplacian (matrix-free): the result matches the direct tridiagonal
// (Thomas) solution, Jacobi preconditioning gives the same answer, and the iteration count is
// what CG's exact-arithmetic theory allows.
#include <cmath>
#include <vector>

#include "solvers/conjugate_gradient.hpp"
#include "laplacian_1d.hpp"
#include "test_backend.hpp"

namespace amphora::solvers {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_conjugate_gradient_cases {

using test::TestExecSpace;
using View = Kokkos::View<double*, test::TestMemSpace>;

using test::Laplacian1D;

std::vector<double> thomas(int n, double diag, const std::vector<double>& rhs) {
  std::vector<double> c(n), d(n), x(n);
  c[0] = -1.0 / diag;
  d[0] = rhs[0] / diag;
  for (int i = 1; i < n; ++i) {
    const double m = diag + c[i - 1];
    c[i] = -1.0 / m;
    d[i] = (rhs[i] + d[i - 1]) / m;
  }
  x[n - 1] = d[n - 1];
  for (int i = n - 2; i >= 0; --i) x[i] = d[i] - c[i] * x[i + 1];
  return x;
}

TEST(ConjugateGradient, MatchesTheDirectSolution) {
  const TestExecSpace exec;
  const int n = 400;
  View b("b", n), x("x", n);
  auto bh = Kokkos::create_mirror_view(b);
  std::vector<double> rhs(n);
  for (int i = 0; i < n; ++i) rhs[i] = bh(i) = std::sin(0.05 * i) + 0.1;
  Kokkos::deep_copy(b, bh);
  SolverControl control;
  control.max_iterations = n;
  control.relative_tolerance = 1e-12;
  const SolverResult r = conjugate_gradient(exec, Laplacian1D{}, b, x, control);
  EXPECT_TRUE(r.converged);
  // Exact arithmetic: at most n iterations; with a symmetric tridiagonal matrix with n distinct
  // eigenvalues, near n for a rough right-hand side. Round-off adds a few.
  EXPECT_LE(r.iterations, n);
  const auto exact = thomas(n, 2.0, rhs);
  auto xh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), x);
  double err = 0, mag = 0;
  for (int i = 0; i < n; ++i) {
    err = std::max(err, std::abs(xh(i) - exact[i]));
    mag = std::max(mag, std::abs(exact[i]));
  }
  // cond(A) ~ 4 n^2 / pi^2 ~ 6.5e4; relative residual 1e-12 bounds the error by ~1e-7.
  EXPECT_LT(err / mag, 1e-7);
}

/// A kept workspace: the same bits as a solve that allocates, and a second solve of the same
/// size reuses its vectors (no allocation inside a time step).
TEST(ConjugateGradient, AKeptWorkspaceGivesTheSameBitsWithoutReallocating) {
  const TestExecSpace exec;
  const int n = 200;
  View b("b", n), x("x", n), y("y", n), d("d", n);
  auto bh = Kokkos::create_mirror_view(b);
  for (int i = 0; i < n; ++i) bh(i) = std::sin(0.05 * i) + 0.1;
  Kokkos::deep_copy(b, bh);
  Kokkos::deep_copy(d, 0.5);
  SolverControl control;
  control.max_iterations = n;
  control.relative_tolerance = 1e-12;
  const JacobiPreconditioner<View> M{d};
  const SolverResult fresh = conjugate_gradient(exec, Laplacian1D{}, b, x, control, M);
  CgWorkspace<View> w;
  const SolverResult kept =
      conjugate_gradient(exec, Laplacian1D{}, b, y, control, M, LocalInnerProduct(), w);
  EXPECT_TRUE(kept.converged);
  EXPECT_EQ(kept.iterations, fresh.iterations);
  const auto same = [&] {
    auto xh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), x);
    auto yh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), y);
    for (int i = 0; i < n; ++i)
      if (xh(i) != yh(i)) return false;
    return true;
  };
  EXPECT_TRUE(same());
  const double *r = w.r.data(), *z = w.z.data(), *p = w.p.data(), *q = w.q.data();
  EXPECT_NE(z, r);  // preconditioned: z apart from r
  Kokkos::deep_copy(y, 0.0);
  conjugate_gradient(exec, Laplacian1D{}, b, y, control, M, LocalInnerProduct(), w);
  EXPECT_EQ(w.r.data(), r);
  EXPECT_EQ(w.z.data(), z);
  EXPECT_EQ(w.p.data(), p);
  EXPECT_EQ(w.q.data(), q);
  EXPECT_TRUE(same());
}

TEST(ConjugateGradient, JacobiOnAShiftedOperatorConvergesFast) {
  const TestExecSpace exec;
  const int n = 1000;
  View b("b", n), x("x", n), inv_diag("d", n);
  kernels::blas1::fill(exec, b, 1.0);
  kernels::blas1::fill(exec, inv_diag, 1.0 / 12.0);
  SolverControl control;
  control.relative_tolerance = 1e-10;
  // A = tridiag(-1, 12, -1): cond <= 14/10, so CG needs ~
  // log(2/1e-10)/log((sqrt(1.4)+1)/(sqrt(1.4)-1)) ~ 10 iterations.
  const SolverResult r = conjugate_gradient(exec, Laplacian1D{10.0}, b, x, control,
                                            JacobiPreconditioner<View>{inv_diag});
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 14);
  std::vector<double> rhs(n, 1.0);
  const auto exact = thomas(n, 12.0, rhs);
  auto xh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), x);
  for (int i = 0; i < n; i += 97) EXPECT_NEAR(xh(i), exact[i], 1e-10);
}

TEST(ConjugateGradient, ZeroRightHandSideConvergesAtOnce) {
  const TestExecSpace exec;
  View b("b", 10), x("x", 10);
  const SolverResult r = conjugate_gradient(exec, Laplacian1D{}, b, x, SolverControl{});
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 0);
}

}  // namespace test_conjugate_gradient_cases
using namespace test_conjugate_gradient_cases;
}  // namespace amphora::solvers
