// Manufactured-solution Poisson problem -lap u = f on curved meshes of the unit square/cube
// (u = prod sin(pi x_d), homogeneous Dirichlet), matrix-free Laplace with Jacobi-CG: the
// observed orders of the L2 and H1-seminorm errors are k+1 and k within 0.2, k = 1..6.
#include <cmath>
#include <vector>

#include "kernels/blas1.hpp"
#include "kernels/host_vector.hpp"
#include "physics/poisson_fem/sine_error_norms.hpp"
#include "physics/poisson_fem/sine_solution.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/matrix_free/load_vector.hpp"
#include "solvers/matrix_free/error_norms.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "test_backend.hpp"

namespace amphora::solvers::matrix_free {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_poisson_convergence_cases {

using test::TestExecSpace;
using Vector = Kokkos::View<double*, test::TestMemSpace>;
using physics::poisson_fem::SineSolution;

template <int dim>
ErrorNorms solve(int k, int n) {
  const TestExecSpace exec;
  auto m = mesh::hex::unit_cube<dim>(n);
  m.deformation = mesh::hex::sinusoidal_deformation(dim, 0.05);
  const mesh::hex::QkSpace<dim, TestExecSpace> space(m, k);
  const long N = space.n_dofs();
  const SineSolution<dim> exact;
  const Vector f = kernels::to_view<test::TestMemSpace>(
      space.interpolate([&](const mesh::hex::Point3& x, int) { return exact.source(x); }));
  const Vector b = load_vector(exec, space, f, GeometryMode::stored, k + 2);
  Vector u("u", N), diag("diag", N);
  typename MatrixFreeOperator<dim, TestExecSpace>::Options o;
  o.kind = OperatorKind::laplace;
  o.n_q = k + 1;
  const MatrixFreeOperator<dim, TestExecSpace> A(space, o);
  A.compute_diagonal(exec, diag);
  kernels::blas1::reciprocal(exec, diag);
  SolverControl control;
  control.max_iterations = 5000;
  control.relative_tolerance = 1e-13;
  const auto r = conjugate_gradient(exec, A, b, u, control, JacobiPreconditioner<Vector>{diag});
  EXPECT_TRUE(r.converged) << r.iterations;
  return error_norms(exec, space, u, SineSolution<dim>{});
}

template <int dim>
void check_orders(int k, const std::vector<int>& sizes) {
  std::vector<ErrorNorms> e;
  for (int n : sizes) e.push_back(solve<dim>(k, n));
  const std::size_t last = e.size() - 1;
  const double r = static_cast<double>(sizes[last]) / sizes[last - 1];
  const double p0 = std::log(e[last - 1].l2 / e[last].l2) / std::log(r);
  const double p1 = std::log(e[last - 1].h1semi / e[last].h1semi) / std::log(r);
  std::printf("dim %d k %d: L2 %.3e -> %.3e (order %.3f), H1 %.3e -> %.3e (order %.3f)\n", dim, k,
              e[last - 1].l2, e[last].l2, p0, e[last - 1].h1semi, e[last].h1semi, p1);
  EXPECT_NEAR(p0, k + 1, 0.2) << "L2 order, dim " << dim << " k " << k;
  EXPECT_NEAR(p1, k, 0.2) << "H1 order, dim " << dim << " k " << k;
}

TEST(PoissonConvergence, CurvedSquareOrdersKPlus1InL2AndKInH1) {
  check_orders<2>(1, {16, 32});
  check_orders<2>(2, {8, 16});
  check_orders<2>(3, {8, 16});
  check_orders<2>(4, {8, 16});
  check_orders<2>(5, {8, 16});
  check_orders<2>(6, {8, 16});
}

TEST(PoissonConvergence, CurvedCubeOrdersKPlus1InL2AndKInH1) {
  check_orders<3>(1, {8, 16});
  check_orders<3>(2, {4, 8});
  check_orders<3>(3, {4, 8});
  check_orders<3>(4, {4, 8});
  check_orders<3>(5, {4, 8});
  check_orders<3>(6, {6, 12});
}

}  // namespace test_poisson_convergence_cases
using namespace test_poisson_convergence_cases;
}  // namespace amphora::solvers::matrix_free
