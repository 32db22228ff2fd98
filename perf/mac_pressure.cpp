// MAC pressure solves: time to a relative residual of 1e-8, setup included, per back end.
//
// Uniform/backend/n: the 7-point Poisson problem of the anchors on an n^3 box of fluid
// cells, pressure zero on all six box faces, a smooth right-hand side; backend 0 = own
// multigrid-CG, 1 = hypre Struct PFMG-CG (both on 1 rank with OMP_NUM_THREADS threads, or on the
// ranks of mpiexec, each owning a z slab), 2 = MIC(0)-CG (sequential), 3 = multigrid-CG with the
// levels of at most 4096 cells smoothed by one team in one launch (MacMultigridOptions::
// team_smoothing_cells: a device schedule, measured beside 0 on a GPU). Counters: iterations,
// unknowns, unknowns per second (unknowns / time), setup seconds; for multigrid-CG also the solve's
// seconds without setup, the bytes one CG iteration moves by the streaming model of
// MacMultigrid::bytes_per_cg_iteration, and the rate a run at STREAM triad bandwidth would reach
// (bound_unknowns_per_s: unknowns over iterations x bytes / bandwidth; the measured rate, setup
// included, is the fraction of it reached). 256^3 runs multigrid-CG alone (the GPU size).
//
// TallCells/backend/n: the same footprint as deep water: an n^3 box with walls and an open top,
// water to 0.9 n over an undulating floor (0.1 +- 0.05), tall cells below an optical depth of
// n/8 cells; backend 0 = tall-cell multigrid-CG, 1 = BoomerAMG-CG, 2 = IC(0)-CG (the first two
// also on the ranks of mpiexec, z slabs). Setup includes building the tall-cell grid and
// assembling P^T A P. Counters as above, plus the uniform
// unknowns of the same water and their ratio to the tall-cell ones.
//
// Each benchmark's first solve in a process runs once untimed (first_call); setup stays in
// every timed solve.
//
// Anchors (issue 4, same machine kind, 128^3): PFMG-CG 1.9 s on 1 rank, 0.95 s on 2 (12
// iterations); BoomerAMG-CG 7.6 s / 4.6 s; MIC(0)-CG 3.0 s (61 iterations).
#include <benchmark/benchmark.h>
#include <mpi.h>

#include <chrono>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <cmath>
#include <vector>

#include "kernels/host_vector.hpp"
#include "mesh/mac/lattice_halo.hpp"
#include "solvers/hypre_struct_pfmg.hpp"
#include "solvers/mac/mac_multigrid.hpp"
#include "solvers/mac/pressure_solver.hpp"
#include "solvers/mac/tall_cell_matrix.hpp"
#include "stream_bandwidth.hpp"

namespace {

using Exec = amphora::kernels::DefaultExecSpace;
using Mem = Exec::memory_space;
using Vector = Kokkos::View<double*, Mem>;
using Stencil = amphora::kernels::mac::PoissonStencil<Mem>;
using kernels_mac_host_stencil_t =
    amphora::kernels::mac::PoissonStencil<amphora::kernels::HostMemSpace>;
namespace mesh = amphora::mesh;
namespace kernels = amphora::kernels;
namespace mac = amphora::solvers::mac;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// This rank's z slab of the fluid box [0,1]^3 with n^3 cells: its stencil (conductances
/// towards the neighbouring slabs in the ghost layer) and right-hand side h^2 f.
struct UniformBox {
  kernels::mac::MacGrid grid;
  int z0 = 0;
  mesh::mac::MacBlock block;
  Stencil A;
  Vector b;

  UniformBox(int n, int rank, int ranks) {
    // z slabs (a horizontal split), block faces between ranks coupled through the ghost layer
    const amphora::mesh::BoxDecomposition dec({n, n, n}, {false, false, false}, ranks, 1,
                                              {false, false, true});
    const amphora::mesh::Box box = dec.box(rank);
    const int nz = box.extent(2);
    z0 = box.lo[2];
    grid = kernels::mac::MacGrid{n, n, nz, 1.0 / n, {0.0, 0.0, z0 / double(n)}};
    const Exec exec;
    Kokkos::View<kernels::mac::MacCellType*, Mem> type("type", grid.padded_size());
    Kokkos::deep_copy(
        type, kernels::mac::MacCellType::fluid);  // ghosts too: the neighbours are all fluid
    block = mesh::mac::MacBlock::of(dec, MPI_COMM_WORLD, rank);
    kernels::mac::MacBoxBoundaries open;
    open.fill(kernels::mac::MacBoundary::open);
    A = amphora::kernels::mac::build_poisson_stencil<Exec, Mem>(exec, grid, type, Vector(),
                                                                block.faces(open));
    mesh::mac::LatticeGhostExchange(block).exchange(exec, grid, A.cz);  // the ghost cells' + faces
    std::vector<double> f(grid.padded_size(), 0.0);
    const double h = grid.h, pi = amphora::kernels::math::pi;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const auto x = grid.cell_centre(i, j, k);
          f[grid.index(i, j, k)] =
              h * h * (1.0 + std::sin(pi * x[0]) * std::sin(2 * pi * x[1]) * std::cos(pi * x[2]));
        }
    b = amphora::kernels::to_view<Mem>(f, "b");
  }
};

/// This process's rank and the number of ranks; false (the run skipped, saying why) when the
/// sequential back end 2 is asked to run on several.
bool ranks_of(benchmark::State& state, int backend, int& rank, int& ranks) {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (ranks > 1 && backend == 2) {
    state.SkipWithError("back end 2 (MIC(0) / IC(0)) runs on one rank");
    return false;
  }
  return true;
}

/// Whether this benchmark (name and arguments) runs for the first time in this process: its
/// first solve then runs once untimed. The first solves of a process are slower than the rest,
/// most likely because they are the first to touch the memory the solvers allocate: 64^3
/// multigrid-CG, five repetitions, gave 56.3, 52.5, 39.3, 28.4, 29.0 ms without the untimed
/// solve and 40.4, 29.2, 28.9, 28.3, 28.6 ms with it.
bool first_call(const char* name, const benchmark::State& state) {
  static std::set<std::tuple<std::string, long, long>> seen;
  return seen.insert({name, static_cast<long>(state.range(0)), static_cast<long>(state.range(1))})
      .second;
}

void Uniform(benchmark::State& state) {
  const int backend = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  int rank = 0, ranks = 1;
  if (!ranks_of(state, backend, rank, ranks)) return;
  const UniformBox box(n, rank, ranks);
  const Exec exec;
  amphora::solvers::SolverControl control;
  control.relative_tolerance = 1e-8;
  control.max_iterations = 2000;
  Vector x("x", box.grid.padded_size());
  int iterations = 0;
  double setup = 0.0, rel = 0.0, solve_s = 0.0, bytes_per_iteration = 0.0;
  const auto solve = [&] {
    Kokkos::deep_copy(x, 0.0);
    exec.fence();
    MPI_Barrier(MPI_COMM_WORLD);
    const auto t0 = Clock::now();
    if (backend == 1) {
      // hypre directly, so several ranks can share the problem
      const auto d =
          Kokkos::create_mirror_view_and_copy(amphora::kernels::HostMemSpace(), box.A.diag);
      const auto cx =
          Kokkos::create_mirror_view_and_copy(amphora::kernels::HostMemSpace(), box.A.cx);
      const auto cy =
          Kokkos::create_mirror_view_and_copy(amphora::kernels::HostMemSpace(), box.A.cy);
      const auto cz =
          Kokkos::create_mirror_view_and_copy(amphora::kernels::HostMemSpace(), box.A.cz);
      const auto bh = Kokkos::create_mirror_view_and_copy(amphora::kernels::HostMemSpace(), box.b);
      auto xh = Kokkos::create_mirror_view_and_copy(amphora::kernels::HostMemSpace(), x);
      amphora::solvers::StructPfmgCG pfmg(MPI_COMM_WORLD, box.grid, {0, 0, box.z0}, d.data(),
                                          cx.data(), cy.data(), cz.data());
      setup = seconds_since(t0);
      const auto r =
          pfmg.solve(bh.data(), xh.data(), control.relative_tolerance, control.max_iterations);
      iterations = r.iterations;
      rel = r.final_relative_residual;
      Kokkos::deep_copy(x, xh);
    } else if (backend == 3) {
      mac::MacMultigridOptions options;
      options.team_smoothing_cells = 4096;
      const mac::MacMultigrid<Exec> mg(exec, box.A, options, box.block);
      exec.fence();
      setup = seconds_since(t0);
      const auto r = mg.solve(exec, box.b, x, control);
      exec.fence();
      solve_s = seconds_since(t0) - setup;
      bytes_per_iteration = mg.bytes_per_cg_iteration();
      iterations = r.iterations;
      rel = r.final_residual / r.rhs_norm;
    } else {
      auto solver = mac::make_pressure_solver(
          backend == 0 ? mac::PressureBackend::multigrid : mac::PressureBackend::mic0, exec, box.A,
          box.block);
      exec.fence();
      setup = seconds_since(t0);
      const auto r = solver->solve(exec, box.b, x, control);
      exec.fence();
      solve_s = seconds_since(t0) - setup;
      bytes_per_iteration = solver->bytes_per_iteration();
      iterations = r.iterations;
      rel = r.final_residual / r.rhs_norm;
    }
    exec.fence();
    MPI_Barrier(MPI_COMM_WORLD);
    return seconds_since(t0);
  };
  if (first_call("Uniform", state))
    solve();  // untimed: the process's first touch of this much memory
  for (auto _ : state) state.SetIterationTime(solve());
  const double unknowns = double(n) * n * n;
  state.counters["iterations"] = iterations;
  state.counters["unknowns"] = unknowns;
  state.counters["setup_s"] = setup;
  state.counters["relative_residual"] = rel;
  state.counters["unknowns_per_s"] =
      benchmark::Counter(unknowns, benchmark::Counter::kIsIterationInvariantRate);
  if (bytes_per_iteration > 0) {
    // the bandwidth of every rank's triad at once, summed, as the ranks share the problem
    MPI_Barrier(MPI_COMM_WORLD);
    double bw = amphora::perf::stream_triad_bandwidth(), total_bw = 0;
    MPI_Allreduce(&bw, &total_bw, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    double bytes = bytes_per_iteration, total_bytes = 0;
    MPI_Allreduce(&bytes, &total_bytes, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    state.counters["solve_s"] = solve_s;
    state.counters["bytes_per_iteration"] = total_bytes;
    state.counters["stream_GB/s"] = total_bw * 1e-9;
    state.counters["bound_unknowns_per_s"] = unknowns * total_bw / (iterations * total_bytes);
    state.counters["solve_GB/s"] = iterations * total_bytes / solve_s * 1e-9;
  }
  static const char* names[] = {"multigrid-CG", "hypre PFMG-CG", "MIC(0)-CG",
                                "multigrid-CG, one-team coarse smoothing"};
  state.SetLabel(names[backend]);
}
BENCHMARK(Uniform)
    ->ArgsProduct({{0, 1, 2}, {64, 128, 192}})
    ->Args({3, 64})
    ->Args({0, 256})
    ->Args({3, 256})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(1);

/// Deep water over an undulating floor, on the host (the tall-cell grid is built there): this
/// rank's z slab, its ghost cells (the neighbouring slabs' cells) from the same formulas.
struct DeepWater {
  mesh::mac::MacBlock block;
  kernels_mac_host_stencil_t A;
  long fluid_cells = 0;  ///< over all ranks: the uniform grid's unknowns
};
DeepWater deep_water(int n, int rank, int ranks) {
  DeepWater w;
  const amphora::mesh::BoxDecomposition dec({n, n, n}, {false, false, false}, ranks, 1,
                                            {false, false, true});
  const amphora::mesh::Box box = dec.box(rank);
  w.block = mesh::mac::MacBlock::of(dec, MPI_COMM_WORLD, rank);
  const kernels::mac::MacGrid g{n, n, box.extent(2), 1.0 / n, {0, 0, box.lo[2] / double(n)}};
  std::vector<kernels::mac::MacCellType> type(g.padded_size(), kernels::mac::MacCellType::solid);
  std::vector<double> phi(g.padded_size(), 1.0);
  const int k_lo = w.block.neighbours[4] >= 0 ? -1 : 0,
            k_hi = g.nz + (w.block.neighbours[5] >= 0 ? 1 : 0);
  for (int k = k_lo; k < k_hi; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto x = g.cell_centre(i, j, k);
        const int c = g.index(i, j, k);
        phi[c] = x[1] - 0.9;
        const double floor = 0.1 + 0.05 * std::sin(6 * x[0]) * std::cos(4 * x[2]);
        type[c] = x[1] < floor ? kernels::mac::MacCellType::solid
                               : (phi[c] < 0 ? kernels::mac::MacCellType::fluid
                                             : kernels::mac::MacCellType::air);
        if (k >= 0 && k < g.nz) w.fluid_cells += type[c] == kernels::mac::MacCellType::fluid;
      }
  long total = 0;
  MPI_Allreduce(&w.fluid_cells, &total, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  w.fluid_cells = total;
  kernels::mac::MacBoxBoundaries faces;
  faces.fill(kernels::mac::MacBoundary::wall);
  faces[3] = kernels::mac::MacBoundary::open;
  w.A = amphora::kernels::mac::build_poisson_stencil<amphora::kernels::HostExecSpace,
                                                     amphora::kernels::HostMemSpace>(
      amphora::kernels::HostExecSpace(), g,
      amphora::kernels::to_view<amphora::kernels::HostMemSpace>(type),
      amphora::kernels::to_view<amphora::kernels::HostMemSpace>(phi), w.block.faces(faces));
  mesh::mac::LatticeGhostExchange(w.block).exchange(amphora::kernels::HostExecSpace(), g,
                                                    w.A.cz);  // the ghost cells' + faces
  return w;
}

void TallCells(benchmark::State& state) {
  const int backend = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  int rank = 0, ranks = 1;
  if (!ranks_of(state, backend, rank, ranks)) return;
  const DeepWater water = deep_water(n, rank, ranks);
  const auto& host_A = water.A;
  // the same stencil in the execution space's memory
  const Stencil A = amphora::kernels::mac::copy_stencil<Mem>(host_A);
  const Exec exec;
  amphora::solvers::SolverControl control;
  control.relative_tolerance = 1e-8;
  control.max_iterations = 3000;
  int iterations = 0;
  double setup = 0.0, rel = 0.0;
  long unknowns = 0;
  const kernels::mac::MacGrid g = host_A.grid;
  const auto solve = [&] {
    exec.fence();
    MPI_Barrier(MPI_COMM_WORLD);
    const auto t0 = Clock::now();
    const mesh::mac::TallCellGrid T(exec, A, n / 8, water.block);
    unknowns = T.global_unknowns();
    // right-hand side: P^T (h^2 f) for a smooth f
    std::vector<double> f(g.padded_size(), 0.0), bt(T.unknowns());
    for (int k = 0; k < g.nz; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const auto x = g.cell_centre(i, j, k);
          f[g.index(i, j, k)] =
              g.h * g.h *
              (1.0 + std::sin(amphora::kernels::math::pi * x[0]) * std::cos(2 * x[2]) * x[1]);
        }
    T.restrict_to_unknowns(f.data(), bt.data());
    const Vector b = amphora::kernels::to_view<Mem>(bt, "b");
    Vector x("x", T.unknowns());
    static const mac::PressureBackend backends[] = {
        mac::PressureBackend::multigrid, mac::PressureBackend::hypre, mac::PressureBackend::mic0};
    auto solver = mac::make_tall_cell_pressure_solver(backends[backend], exec, T, A);
    exec.fence();
    setup = seconds_since(t0);
    const auto r = solver->solve(exec, b, x, control);
    exec.fence();
    MPI_Barrier(MPI_COMM_WORLD);
    iterations = r.iterations;
    rel = r.final_residual / r.rhs_norm;
    return seconds_since(t0);
  };
  if (first_call("TallCells", state)) solve();  // untimed, as in Uniform
  for (auto _ : state) state.SetIterationTime(solve());
  state.counters["iterations"] = iterations;
  state.counters["unknowns"] = double(unknowns);
  state.counters["uniform_unknowns"] = double(water.fluid_cells);
  state.counters["reduction"] = double(water.fluid_cells) / double(unknowns);
  state.counters["setup_s"] = setup;
  state.counters["relative_residual"] = rel;
  state.counters["unknowns_per_s"] =
      benchmark::Counter(double(unknowns), benchmark::Counter::kIsIterationInvariantRate);
  static const char* names[] = {"tall-cell multigrid-CG", "BoomerAMG-CG", "IC(0)-CG"};
  state.SetLabel(names[backend]);
}
BENCHMARK(TallCells)
    ->ArgsProduct({{0, 1, 2}, {64, 128, 192}})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(1);

/// The hot kernels on the fine 128^3 (or n^3) level: cells per second and bytes moved per second
/// (the bytes a kernel must move at least: its reads and writes of doubles and floats).
/// kind 0 = apply (y = A x), 1 = residual, 2 = one red-black Gauss–Seidel sweep (both
/// colours), 3 = restriction, 4 = prolongation, 5 = one V-cycle.
void Kernels(benchmark::State& state) {
  const int kind = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  const UniformBox box(n, 0, 1);
  const Exec exec;
  const long size = box.grid.padded_size();
  Vector x("x", size), y("y", size);
  Kokkos::deep_copy(x, box.b);
  const Stencil coarse = amphora::kernels::mac::coarsen_stencil(exec, box.A);
  Vector xc("xc", coarse.grid.padded_size());
  std::unique_ptr<mac::MacMultigrid<Exec>> mg;
  if (kind == 5) mg = std::make_unique<mac::MacMultigrid<Exec>>(exec, box.A);
  for (auto _ : state) {
    switch (kind) {
      case 0: amphora::kernels::mac::apply(exec, box.A, x, y); break;
      case 1: amphora::kernels::mac::residual(exec, box.A, box.b, x, y); break;
      case 2:
        amphora::kernels::mac::red_black_gauss_seidel(exec, box.A, box.b, x, 0);
        amphora::kernels::mac::red_black_gauss_seidel(exec, box.A, box.b, x, 1);
        break;
      case 3: amphora::kernels::mac::restrict_to_coarse(exec, box.A, coarse, x, xc); break;
      case 4: amphora::kernels::mac::prolongate_add(exec, coarse, box.A, xc, x); break;
      case 5: mg->apply(exec, box.b, x); break;
    }
    exec.fence();
  }
  const double cells = double(n) * n * n;
  // doubles and floats each kernel must touch per fine cell
  const double bytes[] = {8 + 8 + 8 + 12, 8 + 8 + 8 + 8 + 12, 2 * (8 + 8 + 8 + 12) + 8,
                          8 + 8.0 / 8,    8 + 8 + 8.0 / 8,    0};
  state.counters["cells_per_s"] =
      benchmark::Counter(cells, benchmark::Counter::kIsIterationInvariantRate);
  if (bytes[kind] > 0)
    state.counters["bytes_per_s"] =
        benchmark::Counter(cells * bytes[kind], benchmark::Counter::kIsIterationInvariantRate);
  static const char* names[] = {"apply",    "residual",   "red-black GS sweep",
                                "restrict", "prolongate", "V-cycle"};
  state.SetLabel(names[kind]);
}
BENCHMARK(Kernels)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5}, {128}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
