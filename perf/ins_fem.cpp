// One time step of the Navier-Stokes solver (physics/ins_fem) on the 3D Taylor-Green vortex at
// Re = 1600, the same scheme and linear system with two kinds of linear algebra, side by side:
// matrix-free (operator rebuilt, GMRES on the device vectors preconditioned by point Jacobi or
// by the coupled geometric multigrid) and assembled (the
// operator's element matrices into a CSR matrix every step, as the advecting velocity changes,
// then hypre's BoomerAMG-GMRES). Both to the same relative residual from the same state (two
// BDF2 steps in). Args: degree, cells per direction; solver 0 = matrix-free Jacobi,
// 1 = assembled, 2 = matrix-free multigrid.
//
// InsStepLevelResidual/k/cells/2/viscous: the multigrid's operators with (1) or without (0)
// -nu lap u in the SUPG/PSPG residual (GMRES applies the full operator either way).
//
// OseenOperator/k/cells/geometry: one application of the step's Oseen operator (4 components,
// the vortex's velocity advecting, SUPG/PSPG with the viscous residual, grad-div) on the same
// periodic box; geometry 2 = stored at the points, 3 = on the fly (solvers::matrix_free::
// GeometryMode). MDoF/s counts every component; coef_B/DoF is what the operator reads besides
// the vectors.
// OseenDiagonal/k/cells/curved: that operator's diagonal (stored geometry), as a multigrid
// refresh computes it: curved 0 probes the point functor (Cartesian cells), 1 takes unit
// vectors (the same box sinusoidally curved, where the viscous residual's Laplacian needs them).
// OseenTransfer/k/cells: restriction from Q_k to Q_k-1 then prolongation back, 4 components on
// that box, as a V-cycle's p-levels move a residual down and a correction up; MDoF/s counts the
// fine DoFs of all components.
#include <benchmark/benchmark.h>

#include <vector>

#include "physics/ins_fem/flow_solutions.hpp"
#include "physics/ins_fem/ins_solver.hpp"
#include "solvers/hypre_boomeramg.hpp"
#include "solvers/matrix_free/assembly.hpp"
#include "solvers/matrix_free/transfer.hpp"
#include "time_applications.hpp"

// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace bench_ins_fem_cases {

using namespace amphora;
using Exec = kernels::DefaultExecSpace;
using Solver = physics::ins_fem::InsSolver<3, Exec>;

/// hypre's BoomerAMG-GMRES on the step's assembled matrix.
physics::ins_fem::InsStepReport assembled_solve(const Exec& exec, const Solver::Operator& A,
                                                const Solver::Vector& r,
                                                const Solver::Vector& delta, double tol) {
  const solvers::CsrMatrix M = solvers::matrix_free::assemble(exec, A);
  auto rh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), r);
  std::vector<double> x(M.n, 0.0);
  const solvers::BoomerAMG amg(M);
  const auto res = amg.gmres(rh.data(), x.data(), tol, 2000, 60);
  Kokkos::deep_copy(delta, Kokkos::View<const double*, Kokkos::HostSpace>(x.data(), x.size()));
  return {res.iterations, res.final_relative_residual <= tol, res.final_relative_residual};
}

/// The vortex's periodic box (-pi, pi)^3 with `cells` cells per direction.
mesh::hex::StructuredHexMesh<3> periodic_box(int cells) {
  const double pi = kernels::math::pi;
  mesh::hex::StructuredHexMesh<3> m;
  m.cells = {cells, cells, cells};
  m.lower = {-pi, -pi, -pi};
  m.upper = {pi, pi, pi};
  for (int f = 0; f < 6; ++f) m.faces[f] = mesh::hex::FaceCondition::periodic;
  return m;
}

/// One step as InsStep's; `smoother_degree` > 0 sets the multigrid's Chebyshev degree,
/// `by_one` its p-coarsening (k to k - 1, or to k / 2) and `level_viscous` whether its
/// operators keep -nu lap u in the stabilisation.
void run_step(benchmark::State& state, int smoother_degree = 0, bool by_one = true,
              bool level_viscous = true) {
  const int k = static_cast<int>(state.range(0)), cells = static_cast<int>(state.range(1));
  const bool assembled = state.range(2) == 1, multigrid = state.range(2) == 2;
  const double pi = kernels::math::pi;
  const auto m = periodic_box(cells);
  physics::ins_fem::InsOptions o;
  o.nu = 1.0 / 1600.0;
  o.tolerance = 1e-8;
  o.preconditioner = multigrid ? physics::ins_fem::InsPreconditioner::multigrid
                               : physics::ins_fem::InsPreconditioner::jacobi;
  if (smoother_degree > 0) o.multigrid.smoother.degree = smoother_degree;
  o.multigrid.degree_by_one = by_one;
  o.multigrid.viscous_residual = level_viscous;
  Solver s(m, k, o);
  s.set_state(s.space().interpolate(
      [](const mesh::hex::Point3& x, int c) {
        return physics::ins_fem::TaylorGreen3D{c}.value(x.data());
      },
      4));
  const double dt = 0.5 * (2.0 * pi / cells) / k;  // CFL 0.5 at |u| = 1
  s.step(dt);
  s.step(dt);
  auto state0 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.state());
  auto old0 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.previous_velocity());
  const std::vector<double> x0(state0.data(), state0.data() + state0.extent(0));
  const std::vector<double> u0(old0.data(), old0.data() + old0.extent(0));
  if (assembled)
    s.set_linear_solver([&](const Exec& exec, const Solver::Operator& A, const Solver::Vector& r,
                            const Solver::Vector& delta) {
      return assembled_solve(exec, A, r, delta, o.tolerance);
    });
  physics::PhaseTimes times(physics::ins_fem::ins_phase_names());
  s.set_phase_times(&times);
  int iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    s.set_state(x0);
    s.set_history(u0, dt, 2);
    state.ResumeTiming();
    const auto r = s.step(dt);
    iterations = r.linear_iterations;
    if (!r.converged) state.SkipWithError("linear solve did not converge");
    if (r.fell_back) state.SkipWithError("the multigrid fell back to Jacobi");
  }
  state.counters["dofs"] = 4.0 * s.n_dofs();
  state.counters["iterations"] = iterations;
  // Shares of the step (setup: operators, multigrid levels, smoother set-up; smoother: the
  // V-cycles less their coarse solves, or Jacobi; coarse solve: the multigrid's coarsest level;
  // other: GMRES's orthogonalisation and vector updates).
  double total = 0.0;
  for (const auto& [name, sec] : times.seconds()) total += sec;
  for (const auto& [name, sec] : times.seconds()) state.counters[name] = sec / total;
}

void InsStep(benchmark::State& state) { run_step(state); }
BENCHMARK(InsStep)
    ->ArgsProduct({{2}, {8, 12, 16}, {0, 1}})
    ->ArgsProduct({{3}, {8, 12, 16}, {0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);
// The multigrid refreshes its smoothers' diagonals every 10 steps: 10 steps give the mean.
BENCHMARK(InsStep)
    ->ArgsProduct({{2, 3}, {8, 12, 16}, {2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(10);

void InsStepLevelResidual(benchmark::State& state) {
  run_step(state, 0, true, state.range(3) == 1);
}
BENCHMARK(InsStepLevelResidual)
    ->ArgsProduct({{2, 3}, {16}, {2}, {1, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(10);

/// The multigrid's V-cycle, cheaper or stronger: Args degree, cells, 2 (multigrid), Chebyshev
/// degree of every level's smoother, p-coarsening by one degree (1) or by halves (0).
void InsStepSmoother(benchmark::State& state) {
  run_step(state, static_cast<int>(state.range(3)), state.range(4) == 1);
}
BENCHMARK(InsStepSmoother)
    ->ArgsProduct({{3}, {12}, {2}, {2, 3, 4, 6}, {1, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(10);

using Op = solvers::matrix_free::MatrixFreeOperator<3, Exec>;

/// The step's Oseen operator at Q_k on the periodic box, the vortex advecting, with the given
/// geometry mode; `x` gets the vortex's velocity and pressure.
Op oseen_operator(const mesh::hex::QkSpace<3, Exec>& space, int cells, int geometry,
                  Op::Vector& x) {
  const int k = space.degree();
  const double pi = kernels::math::pi;
  const auto tg = [](const mesh::hex::Point3& p, int c) {
    return physics::ins_fem::TaylorGreen3D{c}.value(p.data());
  };
  const std::vector<double> b = space.interpolate(tg, 3), x4 = space.interpolate(tg, 4);
  Op::Options o;
  o.kind = solvers::matrix_free::OperatorKind::oseen;
  o.geometry = static_cast<solvers::matrix_free::GeometryMode>(geometry);
  o.components = 4;
  o.nu = 1.0 / 1600.0;
  const double dt = 0.5 * (2.0 * pi / cells) / k;
  o.alpha = 1.5 / dt, o.grad_div = 0.1, o.dt_inverse = 1.0 / dt;
  o.field = Op::Vector("field", b.size());
  Kokkos::deep_copy(o.field, Kokkos::View<const double*, Kokkos::HostSpace>(b.data(), b.size()));
  x = Op::Vector("x", x4.size());
  Kokkos::deep_copy(x, Kokkos::View<const double*, Kokkos::HostSpace>(x4.data(), x4.size()));
  return Op(space, o);
}

void OseenOperator(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0)), cells = static_cast<int>(state.range(1));
  const mesh::hex::QkSpace<3, Exec> space(periodic_box(cells), k);
  Op::Vector x;
  const Op op = oseen_operator(space, cells, static_cast<int>(state.range(2)), x);
  Op::Vector y("y", x.extent(0));
  perf::time_applications<Exec>(state, op, x, y);
  const double n = static_cast<double>(x.extent(0));
  state.counters["MDoF/s"] =
      benchmark::Counter(n * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["DoFs"] = n;
  state.counters["coef_B/DoF"] = static_cast<double>(op.geometry_bytes()) / n;
}
BENCHMARK(OseenOperator)
    ->ArgsProduct({{2, 3}, {16, 24}, {2, 3}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void OseenDiagonal(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0)), cells = static_cast<int>(state.range(1));
  auto m = periodic_box(cells);
  if (state.range(2) == 1)  // curved: the kernel takes unit vectors (same stored-geometry reads)
    m.deformation = mesh::hex::sinusoidal_deformation(3, 0.05, m.lower, m.upper);
  const mesh::hex::QkSpace<3, Exec> space(m, k);
  Op::Vector x;
  const Op op = oseen_operator(space, cells, 2, x);
  Op::Vector d("d", x.extent(0));
  const Exec exec;
  op.compute_diagonal(exec, d);
  exec.fence();
  for (auto _ : state) {
    op.compute_diagonal(exec, d);
    exec.fence();
  }
  const double n = static_cast<double>(x.extent(0));
  state.counters["MDoF/s"] =
      benchmark::Counter(n * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["DoFs"] = n;
}
BENCHMARK(OseenDiagonal)
    ->ArgsProduct({{2, 3}, {16}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

using Transfer = solvers::matrix_free::MatrixFreeTransfer<3, Exec>;

/// P^T, then P: the fine vector down to `coarse` and back.
struct TransferPair {
  const Transfer* transfer;
  Op::Vector coarse;
  void apply(const Exec& exec, const Op::Vector& x, const Op::Vector& y) const {
    transfer->restrict_to_coarse(exec, x, coarse);
    transfer->prolongate(exec, coarse, y);
  }
};

void OseenTransfer(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0)), cells = static_cast<int>(state.range(1));
  const mesh::hex::QkSpace<3, Exec> fine(periodic_box(cells), k),
      coarse(periodic_box(cells), k - 1);
  const Transfer transfer(coarse, fine, 4, 3);
  Op::Vector x("x", 4 * fine.n_dofs()), y("y", 4 * fine.n_dofs());
  Kokkos::deep_copy(x, 1.0);
  const TransferPair pair{&transfer, Op::Vector("coarse", 4 * coarse.n_dofs())};
  perf::time_applications<Exec>(state, pair, x, y);
  const double n = static_cast<double>(x.extent(0));
  state.counters["MDoF/s"] =
      benchmark::Counter(n * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["DoFs"] = n;
}
BENCHMARK(OseenTransfer)
    ->ArgsProduct({{2, 3}, {16, 24}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace bench_ins_fem_cases
