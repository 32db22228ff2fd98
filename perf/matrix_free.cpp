// Matrix-free operator throughput (DoF/s) and its fraction of the memory-bandwidth bound.
//
// LaplaceDealii/p: the configuration of the deal.II 9.4 anchor in the issue: 3D Laplace on a
// refined unit cube (Cartesian cells), FE_Q(p), QGauss(p+1), homogeneous Dirichlet, 2–7 million
// DoFs; one operator application per iteration. Bound: STREAM triad / 16 bytes per DoF
// (read the source, write the destination once). vs_dealii_* divide by the anchor figures.
//
// LaplaceDealii, LaplaceLarge and BP run on any number of MPI ranks (the box split into slabs,
// mesh::hex::DistributedQkSpace; DoFs and the STREAM bound are totals over the ranks, STREAM
// measured on all ranks at once); GeometryModes and PoissonSolve on one.
//
// LaplaceLarge/p: the same operator on ~40 million DoFs (vectors of 320 MB, beyond the 300 MiB
// last-level cache): the memory-bound regime.
//
// BP/bp/p/e: the CEED bake-off problems (https://ceed.exascaleproject.org/bps/) on a unit cube
// of Cartesian cells with about 10^e DoFs: BP1/2 mass (scalar/3 components, Gauss p+2, no
// Dirichlet), BP3/4 Laplace (Gauss p+2), BP5/6 Laplace collocated on Gauss–Lobatto p+1, BP3-6
// Dirichlet; unpreconditioned CG, 50 iterations; MDoF/s = DoFs x iterations / CG time.
// Bound: STREAM / bytes per DoF per iteration of the CG as implemented: p = r + b p, q = A p
// and p.q in one sweep over the cells (MatrixFreeOperator::apply_direction: r and p read, p and
// q written, 32 bytes), x += a p and r -= a q with r.r in one pass (48): 80 bytes per component
// (unpreconditioned, z is r). In three passes they were 104 (24 + 16 + 16 + 48).
//
// BPOperator/bp/p: the bare operator of BP bp, y = A x, on ~4e7 DoFs (components counted;
// vectors of 320 MB, beyond the last-level cache). Bound: STREAM / 16 bytes per DoF.
//
// StoredGeometryLarge/op/p/team: LaplaceLarge's operator (op 0) and BP5's (op 5) on a curved box
// of ~4e7 DoFs with the geometry stored at the points: the memory-bound form, a cell per thread
// (team 0) or through the team schedule (team 1, Options::team_kernel). Bound: STREAM / (16 B
// + the stored geometry's bytes per DoF).
//
// GeometryModes/mode/p: Laplace (Gauss p+1) on ~2 million DoFs with each geometry mode (0
// cartesian, 1 affine, 2 stored at points, 3 on the fly; curved cells for 2 and 3; 4: stored
// through the team schedule): throughput against geometry bytes per DoF, the memory-for-flops
// trade. (Cartesian and affine boxes have equal cells, whose coefficients are kept once: their
// geometry bytes are ~0.)
//
// GenericKernel/p/generic: the run-time-size fallback against the compiled kernel (below).
//
// PoissonSolve/k/solver: -lap u = f on ~2 million DoFs (Q_k, unit cube, Dirichlet) to a
// relative residual of 1e-8, setup included: solver 0 = matrix-free multigrid-CG, 1 = hypre
// BoomerAMG-CG on the assembled operator of the same problem (assembly time reported apart).
#include <benchmark/benchmark.h>

#include <cmath>

#include <chrono>
#include <vector>

#include "kernels/blas1.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/hypre_boomeramg.hpp"
#include "solvers/matrix_free/assembly.hpp"
#include "solvers/matrix_free/distributed_operator.hpp"
#include "solvers/matrix_free/load_vector.hpp"
#include "solvers/matrix_free/multigrid.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "stream_bandwidth.hpp"
#include "time_applications.hpp"

// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace bench_matrix_free_cases {

using Exec = amphora::kernels::DefaultExecSpace;
using Op = amphora::solvers::matrix_free::MatrixFreeOperator<3, Exec>;
using Vector = Op::Vector;
using DistributedSpace = amphora::mesh::hex::DistributedQkSpace<3, Exec>;
using DistributedOp = amphora::solvers::matrix_free::DistributedOperator<3, Exec>;
namespace mesh = amphora::mesh;

/// Cells per direction giving 2–7 million Q_p DoFs (multiples of 8: full SIMD batches).
int dealii_cells(int p) {
  switch (p) {
    case 2: return 64;  // 129^3 = 2.15 M
    case 3: return 48;  // 145^3 = 3.05 M
    case 4: return 32;  // 129^3 = 2.15 M
    case 5: return 24;  // 121^3 = 1.77 M  -> 32: 161^3 = 4.17 M
    case 6: return 24;  // 145^3 = 3.05 M
    default: return 16;
  }
}

// deal.II 9.4 MatrixFree anchor (MDoF/s, issue 6), by degree
constexpr double dealii_1core[] = {0, 0, 69, 73, 88, 79, 83};
constexpr double dealii_2ranks[] = {0, 0, 112, 136, 150, 160, 182};

/// STREAM triad bandwidth summed over the ranks, measured on all of them at once.
double total_stream_bandwidth() {
  const amphora::Communicator comm;
  comm.barrier();
  return comm.sum(amphora::perf::stream_triad_bandwidth());
}

/// The timed loop (perf/time_applications.hpp) on this file's execution space.
template <class Operator>
void time_applications(benchmark::State& state, const Operator& op, const Vector& x,
                       const Vector& y) {
  amphora::perf::time_applications<Exec>(state, op, x, y);
}

void report(benchmark::State& state, double dofs, double bytes_per_dof) {
  const double bw = total_stream_bandwidth();
  state.counters["MDoF/s"] =
      benchmark::Counter(dofs * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["DoFs"] = dofs;
  state.counters["bound_MDoF/s"] = bw / bytes_per_dof * 1e-6;
  state.counters["stream_GB/s"] = bw * 1e-9;
}

void LaplaceDealii(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  const int n = p == 5 ? 32 : dealii_cells(p);
  const DistributedSpace space(mesh::hex::unit_cube<3>(n), p, amphora::Communicator());
  Op::Options o;
  o.kind = amphora::solvers::matrix_free::OperatorKind::laplace;
  o.geometry = amphora::solvers::matrix_free::GeometryMode::cartesian;
  const DistributedOp op(space, o);
  Vector x("x", op.size()), y("y", op.size());
  Kokkos::deep_copy(x, 1.0);
  time_applications(state, op, x, y);
  const double dofs = static_cast<double>(space.n_global());
  report(state, dofs, 16.0);
  state.counters["ranks"] = space.communicator().size();
  state.counters["vs_dealii_1core"] = benchmark::Counter(
      dofs * 1e-6 / dealii_1core[p], benchmark::Counter::kIsIterationInvariantRate);
  state.counters["vs_dealii_2ranks"] = benchmark::Counter(
      dofs * 1e-6 / dealii_2ranks[p], benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(LaplaceDealii)->DenseRange(2, 6)->Unit(benchmark::kMillisecond)->UseRealTime();

Vector random_vector(long n, unsigned seed) {
  Vector v("v", n);
  Kokkos::parallel_for(
      "amphora::bench::random", amphora::kernels::RangePolicy<Exec>(0, static_cast<int>(n)),
      KOKKOS_LAMBDA(int i) {
        const unsigned h = (static_cast<unsigned>(i) + seed) * 2654435761u;
        v(i) = static_cast<double>(h % 1000003u) / 1000003.0 - 0.5;
      });
  return v;
}

/// Cells per direction for about `target` Q_p DoFs, a multiple of 8 once above 8.
int cells_for(double target, int p) {
  int n = static_cast<int>(std::lround((std::cbrt(target) - 1.0) / p));
  if (n > 8) n = (n + 4) / 8 * 8;
  return std::max(n, 1);
}

void LaplaceLarge(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  const int n = cells_for(4e7, p);
  const DistributedSpace space(mesh::hex::unit_cube<3>(n), p, amphora::Communicator());
  Op::Options o;
  o.geometry = amphora::solvers::matrix_free::GeometryMode::cartesian;
  const DistributedOp op(space, o);
  Vector x = random_vector(op.size(), 1), y("y", op.size());
  time_applications(state, op, x, y);
  report(state, static_cast<double>(space.n_global()), 16.0);
  state.counters["ranks"] = space.communicator().size();
}
BENCHMARK(LaplaceLarge)->DenseRange(2, 6)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The operator of CEED bake-off problem bp (1-6) at degree p (see the top of this file).
Op::Options bp_options(int bp, int p) {
  Op::Options o;
  o.kind = bp <= 2 ? amphora::solvers::matrix_free::OperatorKind::mass
                   : amphora::solvers::matrix_free::OperatorKind::laplace;
  o.geometry = amphora::solvers::matrix_free::GeometryMode::cartesian;
  o.components = bp % 2 == 0 ? 3 : 1;
  o.n_q = bp >= 5 ? p + 1 : p + 2;
  o.quadrature = bp >= 5 ? amphora::kernels::sumfac::QuadratureKind::gauss_lobatto
                         : amphora::kernels::sumfac::QuadratureKind::gauss;
  return o;
}
/// The unit cube of BP bp: no Dirichlet faces for the mass BPs, Dirichlet all round otherwise.
DistributedSpace bp_space(int bp, int p, int cells) {
  const auto faces =
      bp <= 2 ? mesh::hex::FaceCondition::neumann : mesh::hex::FaceCondition::dirichlet;
  return DistributedSpace(mesh::hex::unit_cube<3>(cells, faces), p, amphora::Communicator());
}

void BP(benchmark::State& state) {
  const int bp = static_cast<int>(state.range(0)), p = static_cast<int>(state.range(1));
  const double target = std::pow(10.0, static_cast<double>(state.range(2)));
  const DistributedSpace space = bp_space(bp, p, cells_for(target, p));
  const Op::Options o = bp_options(bp, p);
  const DistributedOp op(space, o);
  const long N = space.n_global() * o.components;
  Vector b = random_vector(op.size(), 7), x("x", op.size());
  amphora::solvers::SolverControl control;
  control.max_iterations = 50;
  control.relative_tolerance = 0.0;
  const Exec exec;
  int iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Kokkos::deep_copy(x, 0.0);
    exec.fence();
    state.ResumeTiming();
    iterations = amphora::solvers::conjugate_gradient(exec, op, b, x, control,
                                                      amphora::solvers::IdentityPreconditioner(),
                                                      space.inner_product(o.components))
                     .iterations;
    exec.fence();
  }
  state.counters["MDoF/s"] =
      benchmark::Counter(N * iterations * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["DoFs"] = static_cast<double>(N);
  state.counters["iterations"] = iterations;
  const double bw = total_stream_bandwidth();
  state.counters["bound_MDoF/s"] = bw / 80.0 * 1e-6;
  state.counters["ranks"] = space.communicator().size();
}
void bp_args(benchmark::internal::Benchmark* b) {
  for (int bp = 1; bp <= 6; ++bp)
    for (int p = 1; p <= 8; ++p)
      for (int e = 4; e <= 7; ++e) b->Args({bp, p, e});
}
BENCHMARK(BP)->Apply(bp_args)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

void BPOperator(benchmark::State& state) {
  const int bp = static_cast<int>(state.range(0)), p = static_cast<int>(state.range(1));
  const Op::Options o = bp_options(bp, p);
  const DistributedSpace space = bp_space(bp, p, cells_for(4e7 / o.components, p));
  const DistributedOp op(space, o);
  Vector x = random_vector(op.size(), 1), y("y", op.size());
  time_applications(state, op, x, y);
  report(state, static_cast<double>(space.n_global() * o.components), 16.0);
  state.counters["ranks"] = space.communicator().size();
}
BENCHMARK(BPOperator)
    ->ArgsProduct({{1, 2, 3, 4, 5, 6}, {1, 2, 3, 4, 5, 6, 7, 8}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The bare operator with the geometry stored at the points (CEED's "qdata": the 6 entries of
/// the symmetric metric per point) on a curved box, ~4e7 DoFs: the memory-bound form of the
/// same operators. op 0: Laplace with Gauss p+1 (LaplaceLarge's); op 5: BP5 (Gauss–Lobatto p+1,
/// collocated). Bound: STREAM / (16 B + the stored geometry's bytes per DoF). From p = 2: at
/// p = 1 the geometry of 4e7 DoFs would take 15 GB (384 B/DoF).
void StoredGeometryLarge(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0)), p = static_cast<int>(state.range(1));
  Op::Options o = which == 5 ? bp_options(5, p) : Op::Options{};
  o.kind = amphora::solvers::matrix_free::OperatorKind::laplace;
  o.geometry = amphora::solvers::matrix_free::GeometryMode::stored;
  o.team_kernel = state.range(2) == 1;
  auto m = mesh::hex::unit_cube<3>(cells_for(4e7, p));
  m.deformation = mesh::hex::sinusoidal_deformation(3, 0.05);
  const DistributedSpace space(m, p, amphora::Communicator());
  const DistributedOp op(space, o);
  Vector x = random_vector(op.size(), 1), y("y", op.size());
  time_applications(state, op, x, y);
  const double n = static_cast<double>(space.n_global());
  const double geometry =
      space.communicator().sum(static_cast<double>(op.local().geometry_bytes()));
  report(state, n, 16.0 + geometry / n);
  state.counters["geometry_B/DoF"] = geometry / n;
  state.counters["ranks"] = space.communicator().size();
}
BENCHMARK(StoredGeometryLarge)
    ->ArgsProduct({{0, 5}, {2, 3, 4, 5, 6, 7, 8}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void GeometryModes(benchmark::State& state) {
  using amphora::solvers::matrix_free::GeometryMode;
  const bool team = state.range(0) == 4;
  const auto mode = team ? GeometryMode::stored : static_cast<GeometryMode>(state.range(0));
  const int p = static_cast<int>(state.range(1));
  auto m = mesh::hex::unit_cube<3>(cells_for(2e6, p));
  if (mode == GeometryMode::stored || mode == GeometryMode::on_the_fly)
    m.deformation = mesh::hex::sinusoidal_deformation(3, 0.05);
  const mesh::hex::QkSpace<3, Exec> space(m, p);
  Op::Options o;
  o.geometry = mode;
  o.team_kernel = team;
  const Op op(space, o);
  Vector x = random_vector(space.n_dofs(), 3), y("y", space.n_dofs());
  time_applications(state, op, x, y);
  const double n = static_cast<double>(space.n_dofs());
  report(state, n, 16.0 + op.geometry_bytes() / n);
  state.counters["geometry_B/DoF"] = op.geometry_bytes() / n;
}
BENCHMARK(GeometryModes)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {2, 4, 6}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// GenericKernel/p/generic: the run-time-size fallback (1) against the compiled kernel (0) for
// the same operator (Laplace, QGauss(p+1), curved cells, ~1e6 DoFs): what leaving the table
// costs.
void GenericKernel(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  auto m = mesh::hex::unit_cube<3>(cells_for(1e6, p));
  m.deformation = mesh::hex::sinusoidal_deformation(3, 0.05);
  const mesh::hex::QkSpace<3, Exec> space(m, p);
  Op::Options o;
  o.geometry = amphora::solvers::matrix_free::GeometryMode::on_the_fly;
  o.generic_kernel = state.range(1) == 1;
  const Op op(space, o);
  Vector x = random_vector(space.n_dofs(), 3), y("y", space.n_dofs());
  time_applications(state, op, x, y);
  report(state, static_cast<double>(space.n_dofs()), 16.0);
}
BENCHMARK(GenericKernel)
    ->ArgsProduct({{2, 4, 6}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void PoissonSolve(benchmark::State& state) {
  using namespace amphora::solvers;
  using namespace amphora::solvers::matrix_free;
  const int k = static_cast<int>(state.range(0));
  const bool amg = state.range(1) == 1;
  const mesh::hex::QkSpace<3, Exec> space(mesh::hex::unit_cube<3>(cells_for(2e6, k)), k);
  const long N = space.n_dofs();
  Op::Options o;
  o.geometry = GeometryMode::cartesian;
  const Exec exec;
  // right-hand side: M f for a smooth f, zero on the Dirichlet DoFs
  Vector f = random_vector(N, 5), x("x", N);
  Kokkos::parallel_for(
      "amphora::bench::smooth_f", amphora::kernels::RangePolicy<Exec>(0, static_cast<int>(N)),
      KOKKOS_LAMBDA(int i) { f(i) = 1.0 + 0.1 * f(i); });
  const Vector b = load_vector(exec, space, f, GeometryMode::cartesian, k + 1);
  const Op A(space, o);
  // One rank's view of the same problem (no communication): the multigrid's operator type.
  const DistributedSpace distributed_space(space.mesh(), k, amphora::Communicator(MPI_COMM_SELF));
  const DistributedOp distributed_A(distributed_space, o);
  SolverControl control;
  control.relative_tolerance = 1e-8;
  control.max_iterations = 500;
  int iterations = 0;
  double assembly_s = 0.0, setup_s = 0.0, total_s = 0.0;
  CsrMatrix csr;
  if (amg) {
    const auto t0 = std::chrono::steady_clock::now();
    csr = assemble(exec, A);
    assembly_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  for (auto _ : state) {
    Kokkos::deep_copy(x, 0.0);
    exec.fence();
    const auto t0 = std::chrono::steady_clock::now();
    if (!amg) {
      const MatrixFreeMultigrid<3, Exec> mg(exec, distributed_A);
      exec.fence();
      setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      iterations = conjugate_gradient(exec, distributed_A, b, x, control, mg).iterations;
      exec.fence();
      state.SetLabel(mg.describe());
    } else {
      auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b);
      std::vector<double> xh(N, 0.0);
      const BoomerAMG solver(csr);
      iterations = solver.pcg(bh.data(), xh.data(), 1e-8, 500).iterations;  // setup inside
    }
    total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  state.counters["DoFs"] = static_cast<double>(N);
  state.counters["iterations"] = iterations;
  state.counters["ns/DoF"] = benchmark::Counter(
      N * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["total_s"] = total_s;
  if (!amg) state.counters["setup_s"] = setup_s;
  if (amg) {
    state.counters["assembly_s"] = assembly_s;
    state.counters["nnz"] = static_cast<double>(csr.nnz());
  }
}
BENCHMARK(PoissonSolve)
    ->ArgsProduct({{2, 4}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1)
    ->Repetitions(1);

}  // namespace bench_matrix_free_cases
using namespace bench_matrix_free_cases;
