// The stabilised Q_k-Q_k Navier-Stokes solver against exact solutions: Kovasznay flow (steady,
// walls all round, Picard) and the 2D Taylor-Green vortex (periodic, BDF2): velocity errors
// converge at order k + 1 and pressure errors at order k or better (within 0.2), the divergence
// at order k; BDF2 converges at order 2 in time on a forced Taylor-Green flow. The coupled
// multigrid keeps GMRES's iterations bounded under refinement and gives Jacobi's solution.
#include <cmath>
#include <cstdio>
#include <vector>

#include "physics/ins_fem/flow_solutions.hpp"
#include "physics/ins_fem/ins_solver.hpp"
#include "solvers/matrix_free/error_norms.hpp"
#include "test_backend.hpp"

namespace amphora::physics::ins_fem {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_ins_fem_cases {

using test::TestExecSpace;
using Solver = InsSolver<2, TestExecSpace>;

/// L2 errors of velocity (both components together) and pressure (up to a constant), and the
/// divergence's rms.
struct FlowErrors {
  double u = 0.0, p = 0.0, div = 0.0;
};

template <class Exact>
FlowErrors errors(const Solver& s, Exact exact) {
  const TestExecSpace exec;
  const long n = s.n_dofs();
  FlowErrors e;
  for (int c = 0; c < 2; ++c) {
    exact.component = c;
    const typename Solver::Vector uc =
        Kokkos::subview(s.state(), Kokkos::make_pair(c * n, (c + 1) * n));
    const double l2 = solvers::matrix_free::error_norms(exec, s.space(), uc, exact).l2;
    e.u += l2 * l2;
  }
  e.u = std::sqrt(e.u);
  exact.component = 2;
  e.p = solvers::matrix_free::error_norms(exec, s.space(), s.pressure(), exact).l2_mean_free();
  e.div = s.divergence_rms();
  return e;
}

template <class Exact>
std::vector<double> interpolate(const Solver& s, Exact exact) {
  return s.space().interpolate(
      [&](const mesh::hex::Point3& x, int c) {
        exact.component = c;
        return exact.value(x.data());
      },
      3);
}

FlowErrors kovasznay(int k, int cells) {
  mesh::hex::StructuredHexMesh<2> m;
  m.cells = {cells, cells, 1};
  m.lower = {-0.5, 0.0, 0.0};
  m.upper = {1.5, 2.0, 0.0};
  InsOptions o;
  o.nu = 1.0 / 40.0;
  o.tolerance = 1e-11;
  Solver s(m, k, o);
  const Kovasznay exact{0, 40.0};
  std::vector<double> x = interpolate(s, exact);  // boundary values; interior: rest
  const auto cons =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.space().constrained_dofs());
  std::vector<double> start(x.size(), 0.0);
  for (int c = 0; c < 2; ++c)
    for (std::size_t i = 0; i < cons.extent(0); ++i)
      start[c * s.n_dofs() + cons(i)] = x[c * s.n_dofs() + cons(i)];
  s.set_state(start);
  int picard = 0;
  const InsStepReport r = s.solve_steady(1e-10, 60, &picard);
  EXPECT_TRUE(r.converged) << "k " << k << " cells " << cells << ": " << picard
                           << " Picard iterations, " << r.linear_iterations << " GMRES";
  return errors(s, exact);
}

/// The Taylor-Green vortex on [0, 2 pi]^2 (periodic), k and cells, from its state at g = 1;
/// with `forced`, amplitude g(t) = cos 2t driven by the force (g' + 2 nu g) u(0), else free
/// decay. Errors at t_end after `steps` BDF2 steps.
FlowErrors taylor_green(int k, int cells, double nu, double t_end, int steps, bool forced,
                        InsPreconditioner pc = InsPreconditioner::multigrid,
                        std::vector<int>* iterations = nullptr) {
  const double two_pi = 2.0 * kernels::math::pi;
  mesh::hex::StructuredHexMesh<2> m;
  m.cells = {cells, cells, 1};
  m.upper = {two_pi, two_pi, 0.0};
  for (int f = 0; f < 4; ++f) m.faces[f] = mesh::hex::FaceCondition::periodic;
  InsOptions o;
  o.nu = nu;
  o.tolerance = 1e-11;
  o.preconditioner = pc;
  Solver s(m, k, o);
  const std::vector<double> x0 = interpolate(s, TaylorGreen2D{0, 1.0});
  s.set_state(x0);
  if (forced) s.set_force(std::vector<double>(x0.begin(), x0.begin() + 2 * s.n_dofs()));
  const double dt = t_end / steps;
  for (int i = 1; i <= steps; ++i) {
    const double t = i * dt;
    const double force = forced ? -2.0 * std::sin(2.0 * t) + 2.0 * nu * std::cos(2.0 * t) : 0.0;
    const InsStepReport r = s.step(dt, force);
    EXPECT_TRUE(r.converged) << "step " << i << ": " << r.linear_iterations;
    if (iterations) iterations->push_back(r.fell_back ? -1 : r.linear_iterations);
  }
  const double g = forced ? std::cos(2.0 * t_end) : std::exp(-2.0 * nu * t_end);
  return errors(s, TaylorGreen2D{0, g});
}

/// Observed order between the last two of a sequence of errors at cell counts `cells`.
double order(double e0, double e1, int n0, int n1) {
  return std::log(e0 / e1) / std::log(static_cast<double>(n1) / n0);
}

template <class Run>
void check_space_orders(const char* name, int k, int n0, int n1, const Run& run) {
  const FlowErrors a = run(k, n0), b = run(k, n1);
  const double ou = order(a.u, b.u, n0, n1), op = order(a.p, b.p, n0, n1);
  const double od = order(a.div, b.div, n0, n1);
  std::printf(
      "%s k %d, %d -> %d cells: u %.3e -> %.3e (order %.2f), p %.3e -> %.3e (%.2f), "
      "div %.3e -> %.3e (%.2f)\n",
      name, k, n0, n1, a.u, b.u, ou, a.p, b.p, op, a.div, b.div, od);
  EXPECT_NEAR(ou, k + 1, 0.2) << name << " velocity, k " << k;
  EXPECT_GT(op, k - 0.2) << name << " pressure, k " << k;
  EXPECT_GT(od, k - 0.2) << name << " divergence, k " << k;
}

TEST(InsFem, KovasznayConvergesAtOrderKPlusOne) {
  check_space_orders("Kovasznay", 1, 16, 32, kovasznay);
  check_space_orders("Kovasznay", 2, 8, 16, kovasznay);
  check_space_orders("Kovasznay", 3, 6, 12, kovasznay);
  check_space_orders("Kovasznay", 4, 6, 12, kovasznay);
}

TEST(InsFem, TaylorGreen2DConvergesAtOrderKPlusOne) {
  auto run = [](int k, int n) { return taylor_green(k, n, 0.01, 0.2, 10, false); };
  check_space_orders("Taylor-Green", 1, 16, 32, run);
  check_space_orders("Taylor-Green", 2, 16, 32, run);
  check_space_orders("Taylor-Green", 3, 8, 16, run);
  check_space_orders("Taylor-Green", 4, 8, 16, run);
}

/// GMRES iterations per step with the multigrid stay bounded as the mesh is refined (the last
/// step's count grows by at most 3 per halving of h and stays under 30), are at least 5 times
/// fewer than with point Jacobi on the finest mesh, and the solutions agree to the solver
/// tolerance.
TEST(InsFem, MultigridIterationsStayBoundedUnderRefinement) {
  const int cells[3][2] = {{32, 64}, {16, 32}, {16, 32}};
  for (int k = 1; k <= 3; ++k) {
    int last = 0;
    for (int n : cells[k - 1]) {
      std::vector<int> mg, jacobi;
      const FlowErrors a =
          taylor_green(k, n, 0.01, 0.2, 4, false, InsPreconditioner::multigrid, &mg);
      const FlowErrors b =
          taylor_green(k, n, 0.01, 0.2, 4, false, InsPreconditioner::jacobi, &jacobi);
      std::printf("k %d, %d cells: GMRES iterations of the last step: multigrid %d, Jacobi %d\n", k,
                  n, mg.back(), jacobi.back());
      for (int its : mg) EXPECT_GT(its, 0) << "k " << k << ", " << n << " cells: fell back";
      EXPECT_LT(mg.back(), 30) << "k " << k << ", " << n << " cells";
      if (last > 0) {
        EXPECT_LE(mg.back(), last + 3) << "k " << k << ", " << n << " cells";
      }
      EXPECT_LT(5 * mg.back(), jacobi.back()) << "k " << k << ", " << n << " cells";
      EXPECT_NEAR(a.u, b.u, 1e-6 * b.u);
      EXPECT_NEAR(a.p, b.p, 1e-6 * b.p);
      last = mg.back();
    }
  }
}

}  // namespace test_ins_fem_cases
}  // namespace amphora::physics::ins_fem

namespace amphora::physics::ins_fem::test_ins_fem_cases {
TEST(InsFem, Bdf2ConvergesAtOrderTwoInTime) {
  const FlowErrors a = taylor_green(4, 12, 0.1, 1.0, 20, true);
  const FlowErrors b = taylor_green(4, 12, 0.1, 1.0, 40, true);
  const double ou = order(a.u, b.u, 20, 40), op = order(a.p, b.p, 20, 40);
  std::printf("BDF2, dt 0.05 -> 0.025: u %.3e -> %.3e (order %.2f), p %.3e -> %.3e (%.2f)\n", a.u,
              b.u, ou, a.p, b.p, op);
  EXPECT_NEAR(ou, 2.0, 0.2);
  EXPECT_NEAR(op, 2.0, 0.2);
}
}  // namespace amphora::physics::ins_fem::test_ins_fem_cases
