// Chebyshev–Jacobi smoothing on the 1D Dirichlet Laplacian tridiag(-1, 2 + s, -1), whose
// eigenpairs are known: D^-1 A has eigenvalues 1 - 2 cos(k pi / (n + 1)) / (2 + s) with the sine
// modes as eigenvectors. Gershgorin's bound of lambda_max(D^-1 A) is exactly 1 + 2 / (2 + s)
// and lies above the true lambda_max and the Lanczos estimate; a smoothing pass from zero right-
// hand side multiplies each mode in the damped interval by at most 1 / T_d(theta / delta), with
// the interval ending at the estimate (x1.2) or at a given bound.
#include <cmath>
#include <vector>

#include "solvers/chebyshev.hpp"
#include "solvers/csr_matrix.hpp"
#include "laplacian_1d.hpp"
#include "test_backend.hpp"

namespace amphora::solvers {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_chebyshev_cases {

using test::TestExecSpace;
using View = Kokkos::View<double*, test::TestMemSpace>;

using kernels::math::pi;

using test::Laplacian1D;

CsrMatrix laplacian_csr(int n, double shift, long first_column = 0) {
  CsrMatrix A;
  A.n = n;
  A.row_ptr.push_back(0);
  for (int i = 0; i < n; ++i) {
    for (int j = i - 1; j <= i + 1; ++j) {
      if (j < 0 || j >= n) continue;
      A.cols.push_back(static_cast<int>(first_column + j));
      A.values.push_back(j == i ? 2.0 + shift : -1.0);
    }
    A.row_ptr.push_back(static_cast<long>(A.cols.size()));
  }
  return A;
}

/// Eigenvalue k (1..n) of D^-1 A.
double jacobi_eigenvalue(int k, int n, double shift) {
  return 1.0 - 2.0 * std::cos(k * pi / (n + 1)) / (2.0 + shift);
}

TEST(Chebyshev, GershgorinBoundIsExactForTheTridiagonalLaplacian) {
  for (const double shift : {0.0, 0.5, 4.0}) {
    const int n = 50;
    const double bound = jacobi_gershgorin_bound(laplacian_csr(n, shift));
    EXPECT_NEAR(bound, 1.0 + 2.0 / (2.0 + shift), 1e-15);
    EXPECT_GT(bound, jacobi_eigenvalue(n, n, shift));
    // a block's rows with global columns give the same bound
    EXPECT_EQ(jacobi_gershgorin_bound(laplacian_csr(n, shift, 1000), 1000), bound);
  }
}

/// ||p(D^-1 A) v|| / ||v|| for the sine mode k after one smoothing pass from b = 0.
double mode_reduction(const ChebyshevSmoother<TestExecSpace, Laplacian1D, View>& smoother, int n,
                      int k) {
  const TestExecSpace exec;
  View x("x", n), b("b", n);
  auto xh = Kokkos::create_mirror_view(x);
  for (int i = 0; i < n; ++i) xh(i) = std::sin(k * pi * (i + 1) / (n + 1));
  Kokkos::deep_copy(x, xh);
  const double before = std::sqrt(kernels::blas1::dot(exec, x, x));
  smoother.smooth(exec, b, x, false);
  return std::sqrt(kernels::blas1::dot(exec, x, x)) / before;
}

TEST(Chebyshev, DampsTheModesOfItsIntervalByTheChebyshevFactor) {
  const TestExecSpace exec;
  const int n = 64;
  const double shift = 0.5;
  View inv_diag("d", n);
  kernels::blas1::fill(exec, inv_diag, 1.0 / (2.0 + shift));
  const Laplacian1D A{shift};
  const double bound = jacobi_gershgorin_bound(laplacian_csr(n, shift));
  ChebyshevOptions estimated;
  estimated.degree = 3;
  estimated.smoothing_range = 8.0;
  ChebyshevOptions bounded = estimated;
  bounded.lambda_max_bound = bound;
  const ChebyshevSmoother<TestExecSpace, Laplacian1D, View> by_estimate(exec, A, inv_diag,
                                                                        estimated);
  const ChebyshevSmoother<TestExecSpace, Laplacian1D, View> by_bound(exec, A, inv_diag, bounded);
  // the estimate approaches the largest eigenvalue from below; the bound is the bound
  EXPECT_LE(by_estimate.lambda_max(), jacobi_eigenvalue(n, n, shift) * (1 + 1e-12));
  EXPECT_GT(by_estimate.lambda_max(), 0.95 * jacobi_eigenvalue(n, n, shift));
  EXPECT_EQ(by_bound.lambda_max(), bound);
  for (const auto* s : {&by_estimate, &by_bound}) {
    const double lambda = s->lambda_max(), hi = s == &by_bound ? lambda : 1.2 * lambda;
    const double lo = lambda / 8.0, sigma = (hi + lo) / (hi - lo);
    const double factor = 1.0 / std::cosh(3.0 * std::acosh(sigma));  // 1 / T_3(sigma)
    int damped = 0;
    for (int k = 1; k <= n; ++k) {
      const double mu = jacobi_eigenvalue(k, n, shift);
      if (mu < lo || mu > hi) continue;
      EXPECT_LE(mode_reduction(*s, n, k), factor * (1 + 1e-10)) << "mode " << k;
      ++damped;
    }
    EXPECT_GT(damped, n / 2);
  }
}

}  // namespace test_chebyshev_cases
using namespace test_chebyshev_cases;
}  // namespace amphora::solvers
