// GMRES on non-symmetric systems: a 1D convection-diffusion matrix against its direct (Thomas)
// solution, with and without Jacobi and restarts; unrestarted GMRES ends within n iterations
// (exact-arithmetic theory); and the stabilised Oseen operator of the matrix-free layer
// (velocity and pressure on curved Q2 cells) solved back to a known solution.
#include <cmath>
#include <random>
#include <vector>

#include "kernels/blas1.hpp"
#include "kernels/host_vector.hpp"
#include "mesh/hex/qk_space.hpp"
#include "solvers/gmres.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "deformed_box.hpp"
#include "test_backend.hpp"

namespace amphora::solvers {
namespace test_gmres_cases {  // named: CUDA takes no extended lambdas in anonymous namespaces

using test::TestExecSpace;
using View = Kokkos::View<double*, test::TestMemSpace>;

/// tridiag(-(1 + c), 2 + s, -(1 - c)) with zero Dirichlet ends: upwinded convection c.
struct ConvectionDiffusion1D {
  double s = 0.0, c = 0.5;
  View x, y;
  KOKKOS_INLINE_FUNCTION void operator()(int i) const {
    const int n = static_cast<int>(x.extent(0));
    const double left = i > 0 ? x(i - 1) : 0.0, right = i < n - 1 ? x(i + 1) : 0.0;
    y(i) = (2.0 + s) * x(i) - (1.0 + c) * left - (1.0 - c) * right;
  }
  void apply(const TestExecSpace& exec, const View& in, const View& out) const {
    ConvectionDiffusion1D f = *this;
    f.x = in, f.y = out;
    Kokkos::parallel_for("test::ConvectionDiffusion1D",
                         kernels::RangePolicy<TestExecSpace>(exec, 0, int(in.extent(0))), f);
  }
};

std::vector<double> thomas(const ConvectionDiffusion1D& A, const std::vector<double>& rhs) {
  const int n = static_cast<int>(rhs.size());
  const double a = -(1.0 + A.c), d = 2.0 + A.s, up = -(1.0 - A.c);
  std::vector<double> cp(n), dp(n), x(n);
  cp[0] = up / d, dp[0] = rhs[0] / d;
  for (int i = 1; i < n; ++i) {
    const double m = d - a * cp[i - 1];
    cp[i] = up / m;
    dp[i] = (rhs[i] - a * dp[i - 1]) / m;
  }
  x[n - 1] = dp[n - 1];
  for (int i = n - 2; i >= 0; --i) x[i] = dp[i] - cp[i] * x[i + 1];
  return x;
}

double max_error(const View& x, const std::vector<double>& ref) {
  const std::vector<double> h = kernels::to_std_vector(x);
  double e = 0.0, s = 0.0;
  for (std::size_t i = 0; i < ref.size(); ++i)
    e = std::max(e, std::abs(h[i] - ref[i])), s = std::max(s, std::abs(ref[i]));
  return e / s;
}

TEST(Gmres, MatchesTheDirectSolutionWithAndWithoutJacobi) {
  const TestExecSpace exec;
  const int n = 300;
  ConvectionDiffusion1D A;
  A.s = 0.01;
  std::vector<double> rhs(n);
  for (int i = 0; i < n; ++i) rhs[i] = std::sin(0.05 * i) + 0.3;
  const std::vector<double> ref = thomas(A, rhs);
  const View b = kernels::to_view<test::TestMemSpace>(rhs);
  SolverControl control;
  control.relative_tolerance = 1e-10;
  control.max_iterations = 5000;
  View x("x", n);
  const SolverResult plain = gmres(exec, A, b, x, control, 40);
  EXPECT_TRUE(plain.converged);
  EXPECT_LE(plain.final_residual, 1e-10 * plain.rhs_norm);
  EXPECT_LT(max_error(x, ref), 1e-7);  // the condition number of A times the tolerance
  View d("d", n), y("y", n);
  Kokkos::deep_copy(d, 1.0 / (2.0 + A.s));
  Kokkos::deep_copy(y, 0.0);
  const SolverResult jacobi = gmres(exec, A, b, y, control, 40, JacobiPreconditioner<View>{d});
  EXPECT_TRUE(jacobi.converged);
  EXPECT_LT(max_error(y, ref), 1e-7);
}

/// A kept workspace: the same bits as a solve that allocates, and a second solve of the same
/// size reuses its vectors (no allocation inside a time step).
TEST(Gmres, AKeptWorkspaceGivesTheSameBitsWithoutReallocating) {
  const TestExecSpace exec;
  const int n = 300;
  ConvectionDiffusion1D A;
  A.s = 0.01;
  std::vector<double> rhs(n);
  for (int i = 0; i < n; ++i) rhs[i] = std::cos(0.07 * i);
  const View b = kernels::to_view<test::TestMemSpace>(rhs);
  SolverControl control;
  control.relative_tolerance = 1e-10;
  control.max_iterations = 5000;
  View d("d", n), x("x", n), y("y", n);
  Kokkos::deep_copy(d, 1.0 / (2.0 + A.s));
  const JacobiPreconditioner<View> M{d};
  const SolverResult fresh = gmres(exec, A, b, x, control, 20, M);
  GmresWorkspace<View> ws;
  const SolverResult kept = gmres(exec, A, b, y, control, 20, M, LocalInnerProduct(), ws);
  EXPECT_TRUE(kept.converged);
  EXPECT_EQ(kept.iterations, fresh.iterations);
  EXPECT_EQ(kernels::to_std_vector(x), kernels::to_std_vector(y));
  const double* basis = ws.v[20].data();
  const double* w = ws.w.data();
  Kokkos::deep_copy(y, 0.0);
  gmres(exec, A, b, y, control, 20, M, LocalInnerProduct(), ws);
  EXPECT_EQ(ws.v[20].data(), basis);
  EXPECT_EQ(ws.w.data(), w);
  EXPECT_EQ(kernels::to_std_vector(x), kernels::to_std_vector(y));
}

TEST(Gmres, WithoutRestartEndsWithinNIterations) {
  const TestExecSpace exec;
  const int n = 40;
  ConvectionDiffusion1D A;
  A.c = 0.9;
  std::vector<double> rhs(n, 1.0);
  const View b = kernels::to_view<test::TestMemSpace>(rhs);
  View x("x", n);
  SolverControl control;
  control.relative_tolerance = 1e-10;
  const SolverResult r = gmres(exec, A, b, x, control, n);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.iterations, n);
  EXPECT_LT(max_error(x, thomas(A, rhs)), 1e-8);
}

TEST(Gmres, SolvesTheStabilisedOseenSystem) {
  const TestExecSpace exec;
  auto m = mesh::hex::unit_cube<2>(8);
  test::deform(m, "curved");
  const mesh::hex::QkSpace<2, TestExecSpace> space(m, 2);
  const long n = 3 * space.n_dofs();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> b(2 * space.n_dofs()), xs(n);
  for (double& e : b) e = u(rng);
  for (double& e : xs) e = u(rng);
  typename matrix_free::MatrixFreeOperator<2, TestExecSpace>::Options o;
  o.kind = matrix_free::OperatorKind::oseen;
  o.components = 3;
  o.field = kernels::to_view<test::TestMemSpace>(b);
  o.nu = 0.01, o.alpha = 10.0, o.grad_div = 0.1, o.dt_inverse = 10.0;
  const matrix_free::MatrixFreeOperator<2, TestExecSpace> A(space, o);
  const View exact = kernels::to_view<test::TestMemSpace>(xs), rhs("rhs", n), x("x", n);
  A.apply(exec, exact, rhs);
  View d("d", n);
  A.compute_diagonal(exec, d);
  kernels::blas1::reciprocal(exec, d);
  SolverControl control;
  control.relative_tolerance = 1e-11;
  control.max_iterations = 3000;
  const SolverResult r = gmres(exec, A, rhs, x, control, 60, JacobiPreconditioner<View>{d});
  EXPECT_TRUE(r.converged) << r.iterations << " iterations, residual " << r.final_residual;
  // Walls all round: the pressure is determined up to a constant (it has no Dirichlet rows).
  auto xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x);
  const long np = space.n_dofs();
  double shift = 0.0;
  for (long i = 2 * np; i < n; ++i) shift += (xh(i) - xs[i]) / np;
  double err = 0.0;
  for (long i = 0; i < n; ++i)
    err = std::max(err, std::abs(xh(i) - xs[i] - (i >= 2 * np ? shift : 0.0)));
  EXPECT_LT(err, 1e-6);
}

}  // namespace test_gmres_cases
}  // namespace amphora::solvers
