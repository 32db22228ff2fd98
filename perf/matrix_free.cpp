// Matrix-free operator throughput (DoF/s) and its fraction of the memory-bandwidth bound.
//
// LaplaceDealii/p: the configuration of the deal.II 9.4 anchor in the issue: 3D Laplace on a
// refined unit cube (Cartesian cells), FE_Q(p), QGauss(p+1), homogeneous Dirichlet, 2–7 million
// DoFs; one operator application per iteration. Bound: STREAM triad / 16 bytes per DoF
// (read the source, write the destination once).
#include <benchmark/benchmark.h>

#include <cmath>

#include "kernels/blas1.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "stream_bandwidth.hpp"

namespace {

using Exec = amphora::DefaultExecSpace;
using Op = amphora::solvers::MatrixFreeOperator<3, Exec>;
using Vector = Op::Vector;
namespace mesh = amphora::mesh;

/// Cells per direction giving 2–7 million Q_p DoFs (multiples of 8: full SIMD batches).
int dealii_cells(int p) {
  switch (p) {
    case 2: return 64;   // 129^3 = 2.15 M
    case 3: return 48;   // 145^3 = 3.05 M
    case 4: return 32;   // 129^3 = 2.15 M
    case 5: return 24;   // 121^3 = 1.77 M  -> 32: 161^3 = 4.17 M
    case 6: return 24;   // 145^3 = 3.05 M
    default: return 16;
  }
}

void report(benchmark::State& state, double dofs, double bytes_per_dof) {
  const double bw = amphora::perf::stream_triad_bandwidth();
  state.counters["MDoF/s"] = benchmark::Counter(dofs * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["DoFs"] = dofs;
  state.counters["bound_MDoF/s"] = bw / bytes_per_dof * 1e-6;
  state.counters["stream_GB/s"] = bw * 1e-9;
}

void LaplaceDealii(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  const int n = p == 5 ? 32 : dealii_cells(p);
  const mesh::QkSpace<3, Exec> space(mesh::unit_cube<3>(n), p);
  Op::Options o;
  o.kind = amphora::solvers::OperatorKind::laplace;
  o.geometry = amphora::solvers::GeometryMode::cartesian;
  const Op op(space, o);
  Vector x("x", space.n_dofs()), y("y", space.n_dofs());
  Kokkos::deep_copy(x, 1.0);
  const Exec exec;
  op.apply(exec, x, y);
  exec.fence();
  for (auto _ : state) {
    op.apply(exec, x, y);
    exec.fence();
  }
  report(state, static_cast<double>(space.n_dofs()), 16.0);
}
BENCHMARK(LaplaceDealii)->DenseRange(2, 6)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
