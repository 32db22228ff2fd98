// The MAC pressure system split horizontally over ranks (x and z; columns stay whole): after a
// halo exchange of cell types and level set, each block's matrix equals the rows of the
// single-block matrix for its cells exactly, hypre PFMG-CG on the distributed system gives the
// single-block pressure to the solver tolerance, and the own multigrid on the blocks is the
// single block's (one V-cycle equal, CG in as many iterations to the same pressure), at 1 and 2
// ranks; and the tall-cell system likewise (rows of P^T A P; BoomerAMG-CG and the tall-cell
// multigrid-CG on the blocks).
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "kernels/host_vector.hpp"
#include "kernels/mac/poisson_stencil.hpp"
#include "mesh/box_decomposition.hpp"
#include "mesh/halo_exchange.hpp"
#include "mesh/mac/lattice_halo.hpp"
#include "solvers/hypre_struct_pfmg.hpp"
#include "solvers/mac/mac_multigrid.hpp"
#include "solvers/mac/pressure_solver.hpp"
#include "solvers/mac/tall_cell_matrix.hpp"
#include "solvers/mac/tall_cell_multigrid.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace {

using kernels::mac::MacCellType;
using kernels::mac::MacGrid;
using Mem = test::TestMemSpace;
using Exec = test::TestExecSpace;

constexpr int N = 32;
double sq(double a) { return a * a; }
/// The scene: a sphere of water resting on an undulating floor, in a box with walls.
double level_set(const std::array<double, 3>& x) {
  return std::sqrt(sq(x[0] - 0.5) + sq(x[1] - 0.45) + sq(x[2] - 0.5)) - 0.37;
}
bool solid(const std::array<double, 3>& x) {
  return x[1] < 0.15 + 0.07 * std::sin(9 * x[0]) * std::cos(7 * x[2]);
}
double source(const std::array<double, 3>& x) { return 1.0 + x[0] * x[2]; }

struct Block {
  MacGrid grid;
  kernels::mac::MacBoxBoundaries faces;
  kernels::mac::PoissonStencil<kernels::HostMemSpace> A;
  std::vector<double> b;
};

/// A padded lattice array through the exchange of its ghost layer (host data).
template <class T>
void exchange(const mesh::mac::LatticeGhostExchange& halo, const MacGrid& g, T* data) {
  Kokkos::View<T*, Mem> v("v", g.padded_size());
  Kokkos::deep_copy(
      v, Kokkos::View<T*, kernels::HostMemSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>(
             data, g.padded_size()));
  halo.exchange(Exec(), g, v);
  Kokkos::deep_copy(
      Kokkos::View<T*, kernels::HostMemSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>(
          data, g.padded_size()),
      v);
}

/// The block of `box` (global cell indices) with the given box faces; ghost types and phi come
/// from the neighbours by halo exchange when `halo` is given, else the block is the whole box.
Block make_block(const mesh::Box& box, const kernels::mac::MacBoxBoundaries& faces,
                 const mesh::mac::LatticeGhostExchange* halo) {
  Block B;
  const double h = 1.0 / N;
  B.grid = MacGrid{box.extent(0),
                   box.extent(1),
                   box.extent(2),
                   h,
                   {box.lo[0] * h, box.lo[1] * h, box.lo[2] * h}};
  B.faces = faces;
  const MacGrid& g = B.grid;
  std::vector<std::uint8_t> type(g.padded_size(), std::uint8_t(MacCellType::solid));
  std::vector<double> phi(g.padded_size(), 1.0);
  B.b.assign(g.padded_size(), 0.0);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const auto x = g.cell_centre(i, j, k);
        const int c = g.index(i, j, k);
        phi[c] = level_set(x);
        type[c] = std::uint8_t(solid(x)     ? MacCellType::solid
                               : phi[c] < 0 ? MacCellType::fluid
                                            : MacCellType::air);
      }
  if (halo) {
    exchange(*halo, g, type.data());
    exchange(*halo, g, phi.data());
  }
  std::vector<MacCellType> t(type.size());
  for (std::size_t c = 0; c < t.size(); ++c) t[c] = MacCellType(type[c]);
  B.A = kernels::mac::build_poisson_stencil<kernels::HostExecSpace, kernels::HostMemSpace>(
      kernels::HostExecSpace(), g, kernels::to_view<kernels::HostMemSpace>(t),
      kernels::to_view<kernels::HostMemSpace>(phi), faces);
  if (halo) {  // the ghost cells' + faces: this block's - faces
    exchange(*halo, g, B.A.cx.data());
    exchange(*halo, g, B.A.cy.data());
    exchange(*halo, g, B.A.cz.data());
  }
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const int c = g.index(i, j, k);
        if (B.A.diag(c) > 0) B.b[c] = h * h * source(g.cell_centre(i, j, k));
      }
  return B;
}

std::vector<double> solve(MPI_Comm comm, const Block& B, const mesh::Index3& lower) {
  solvers::StructPfmgCG pfmg(comm, B.grid, {lower[0], lower[1], lower[2]}, B.A.diag.data(),
                             B.A.cx.data(), B.A.cy.data(), B.A.cz.data());
  std::vector<double> x(B.grid.padded_size(), 0.0);
  const auto r = pfmg.solve(B.b.data(), x.data(), 1e-11, 200);
  EXPECT_LE(r.final_relative_residual, 1e-11);
  return x;
}

/// The scene split horizontally over the ranks of comm (this rank's block) and whole.
struct SplitScene {
  mesh::Box box;
  mesh::mac::MacBlock block;
  Block local, whole;
};
/// Split along x (direction 0) or z (2). Both are tested: the lattice's x ghost columns sit
/// beside the row below's in memory, which a flat loop over the cells meets only in an x split.
SplitScene split_scene(const Communicator& comm, int direction) {
  SplitScene S;
  const mesh::Index3 global{N, N, N};
  // horizontal only: the vertical (y) is never split
  const mesh::BoxDecomposition dec(global, {false, false, false}, comm.size(), 4,
                                   {direction == 0, false, direction == 2});
  EXPECT_EQ(dec.blocks()[1], 1);
  EXPECT_EQ(dec.blocks()[direction], comm.size());
  S.box = dec.box(comm.rank());
  kernels::mac::MacBoxBoundaries faces;
  for (int d = 0; d < 3; ++d)
    for (int side = 0; side < 2; ++side)
      faces[2 * d + side] = dec.neighbor(comm.rank(), d, side) >= 0
                                ? kernels::mac::MacBoundary::neighbour
                                : kernels::mac::MacBoundary::wall;
  S.block = mesh::mac::MacBlock::of(dec, comm.get(), comm.rank());
  const mesh::mac::LatticeGhostExchange halo(S.block);
  S.local = make_block(S.box, faces, &halo);
  kernels::mac::MacBoxBoundaries walls;
  walls.fill(kernels::mac::MacBoundary::wall);
  S.whole = make_block(mesh::Box{{0, 0, 0}, global}, walls, nullptr);
  return S;
}

/// Largest |block - whole| over this block's cells and largest |whole| there, over all ranks.
struct Difference {
  double max = 0, scale = 0;
};
Difference block_difference(const Communicator& comm, const SplitScene& S,
                            const std::vector<double>& block, const std::vector<double>& whole) {
  Difference d;
  const MacGrid &g = S.local.grid, &w = S.whole.grid;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const double v = whole[w.index(S.box.lo[0] + i, S.box.lo[1] + j, S.box.lo[2] + k)];
        d.max = std::max(d.max, std::abs(block[g.index(i, j, k)] - v));
        d.scale = std::max(d.scale, std::abs(v));
      }
  MPI_Allreduce(MPI_IN_PLACE, &d.max, 1, MPI_DOUBLE, MPI_MAX, comm.get());
  MPI_Allreduce(MPI_IN_PLACE, &d.scale, 1, MPI_DOUBLE, MPI_MAX, comm.get());
  return d;
}

class MacDecomposition : public ::testing::TestWithParam<int> {};

TEST_P(MacDecomposition, BlockMatricesAndDistributedPressureMatchTheSingleBlock) {
  Communicator comm;
  const SplitScene S = split_scene(comm, GetParam());
  const mesh::Box& box = S.box;
  const mesh::mac::MacBlock& block = S.block;
  const Block &local = S.local, &whole = S.whole;

  // every coefficient of this block's cells equals the single block's
  long compared = 0, differ = 0;
  const int sy = local.grid.stride_y(), sz = local.grid.stride_z();
  const int wy = whole.grid.stride_y(), wz = whole.grid.stride_z();
  for (int k = 0; k < local.grid.nz; ++k)
    for (int j = 0; j < local.grid.ny; ++j)
      for (int i = 0; i < local.grid.nx; ++i) {
        const int c = local.grid.index(i, j, k);
        const int w = whole.grid.index(box.lo[0] + i, box.lo[1] + j, box.lo[2] + k);
        const double a[7] = {local.A.diag(c), local.A.cx(c - 1),  local.A.cx(c), local.A.cy(c - sy),
                             local.A.cy(c),   local.A.cz(c - sz), local.A.cz(c)};
        const double e[7] = {whole.A.diag(w), whole.A.cx(w - 1),  whole.A.cx(w), whole.A.cy(w - wy),
                             whole.A.cy(w),   whole.A.cz(w - wz), whole.A.cz(w)};
        for (int m = 0; m < 7; ++m, ++compared) differ += a[m] != e[m];
      }
  EXPECT_EQ(differ, 0) << "of " << compared << " coefficients on rank " << comm.rank();

  // the distributed pressure equals the single-block one (solved on this rank alone)
  const std::vector<double> p = solve(comm.get(), local, box.lo);
  const std::vector<double> q = solve(MPI_COMM_SELF, whole, {0, 0, 0});
  const Difference pq = block_difference(comm, S, p, q);
  const double scale = pq.scale;
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(pq.max, 1e-8 * scale) << "ranks " << comm.size();

  // the same through the pressure-solver interface; MIC(0) refuses a block
  const auto A = kernels::mac::copy_stencil<Mem>(local.A);
  auto hypre =
      solvers::mac::make_pressure_solver(solvers::mac::PressureBackend::hypre, Exec(), A, block);
  Kokkos::View<double*, Mem> x("x", local.grid.padded_size());
  solvers::SolverControl control;
  control.relative_tolerance = 1e-11;
  EXPECT_TRUE(hypre->solve(Exec(), kernels::to_view<Mem>(local.b), x, control).converged);
  const auto xh = kernels::to_std_vector(x);
  double d2 = 0;
  for (std::size_t c = 0; c < xh.size(); ++c) d2 = std::max(d2, std::abs(xh[c] - p[c]));
  EXPECT_LT(d2, 1e-12 * scale);
  if (comm.size() > 1) {
    EXPECT_THROW(
        solvers::mac::make_pressure_solver(solvers::mac::PressureBackend::mic0, Exec(), A, block),
        std::invalid_argument);
  }

  // multigrid-CG on the blocks takes the single block's V-cycle: the same iterations and pressure
  const auto solve_mg = [&](const Block& B, const mesh::mac::MacBlock& where,
                            std::vector<double>& out) {
    auto mg = solvers::mac::make_pressure_solver(solvers::mac::PressureBackend::multigrid, Exec(),
                                                 kernels::mac::copy_stencil<Mem>(B.A), where);
    Kokkos::View<double*, Mem> xm("x", B.grid.padded_size());
    const auto r = mg->solve(Exec(), kernels::to_view<Mem>(B.b), xm, control);
    EXPECT_TRUE(r.converged);
    out = kernels::to_std_vector(xm);
    return r.iterations;
  };
  std::vector<double> pm, qm;
  const int split_iterations = solve_mg(local, block, pm);
  const int whole_iterations = solve_mg(whole, mesh::mac::MacBlock{}, qm);
  EXPECT_EQ(split_iterations, whole_iterations) << "ranks " << comm.size();
  const double d3 = block_difference(comm, S, pm, qm).max;
  EXPECT_LT(d3, 1e-9 * scale) << "multigrid on " << comm.size() << " ranks, " << split_iterations
                              << " iterations";
  // and one V-cycle on the blocks is the single block's V-cycle, to single-precision round-off
  using MG = solvers::mac::MacMultigrid<Exec>;
  const MG split_mg(Exec(), kernels::mac::copy_stencil<Mem>(local.A), {}, block);
  const MG whole_mg(Exec(), kernels::mac::copy_stencil<Mem>(whole.A));
  EXPECT_EQ(split_mg.levels(), whole_mg.levels());
  Kokkos::View<double*, Mem> zs("zs", local.grid.padded_size()), zw("zw", whole.grid.padded_size());
  split_mg.apply(Exec(), kernels::to_view<Mem>(local.b), zs);
  whole_mg.apply(Exec(), kernels::to_view<Mem>(whole.b), zw);
  const Difference z =
      block_difference(comm, S, kernels::to_std_vector(zs), kernels::to_std_vector(zw));
  const double d4 = z.max, zmax = z.scale;
  EXPECT_LT(d4, 1e-6 * zmax) << "V-cycle on " << comm.size() << " ranks";
  if (comm.rank() == 0) std::printf("V-cycle: max difference %.3g of %.3g\n", d4, zmax);
  if (comm.rank() == 0)
    std::printf(
        "multigrid-CG: %d iterations on %d rank(s), %d on one block; max difference %.3g of %.3g\n",
        split_iterations, comm.size(), whole_iterations, d3, scale);
}

// The tall-cell system on the blocks: each block's rows of P^T A P equal the single block's
// rows for the same unknowns (to round-off: the face terms are summed in another order), and
// BoomerAMG-CG on the distributed rows gives the single block's lattice pressure.
TEST_P(MacDecomposition, TallCellSystemOnBlocksMatchesTheSingleBlock) {
  Communicator comm;
  const SplitScene S = split_scene(comm, GetParam());
  const mesh::Box& box = S.box;
  const Block &local = S.local, &whole = S.whole;
  const int depth = 4;
  const mesh::mac::TallCellGrid T(local.A, depth, S.block), W(whole.A, depth);
  ASSERT_GT(W.tall_cells(), 0);
  EXPECT_EQ(comm.sum(static_cast<long long>(T.unknowns())), static_cast<long long>(W.unknowns()));
  EXPECT_EQ(T.global_unknowns(), W.unknowns());
  // the single block's number of each of this block's unknowns, then of every block's
  std::vector<std::int64_t> mine(T.unknowns());
  for (int k = 0; k < local.grid.nz; ++k)
    for (int i = 0; i < local.grid.nx; ++i) {
      const mesh::mac::TallCellColumn& c = T.column(i, k);
      const mesh::mac::TallCellColumn& w = W.column(box.lo[0] + i, box.lo[2] + k);
      ASSERT_EQ(c.terrain, w.terrain);
      ASSERT_EQ(c.band, w.band);
      if (c.has_tall_cell())
        mine[c.first_unknown] = w.first_unknown, mine[c.first_unknown + 1] = w.first_unknown + 1;
      for (int j = c.band; j < local.grid.ny; ++j) {
        const int u = T.cell_unknown()(local.grid.index(i, j, k));
        if (u >= 0) mine[u] = W.cell_unknown()(whole.grid.index(box.lo[0] + i, j, box.lo[2] + k));
      }
    }
  const std::vector<std::int64_t> to_whole = comm.allgatherv(mine);
  const solvers::CsrMatrix M = solvers::mac::assemble_tall_cell_matrix(T, local.A);
  const solvers::CsrMatrix Mw = solvers::mac::assemble_tall_cell_matrix(W, whole.A);
  ASSERT_EQ(M.n, T.unknowns());
  long rows_compared = 0, differ = 0;
  for (long r = 0; r < M.n; ++r) {
    const long wr = mine[r];
    std::vector<std::pair<long, double>> a, e;
    for (long m = M.row_ptr[r]; m < M.row_ptr[r + 1]; ++m)
      a.emplace_back(to_whole.at(M.cols[m]), M.values[m]);
    for (long m = Mw.row_ptr[wr]; m < Mw.row_ptr[wr + 1]; ++m)
      e.emplace_back(Mw.cols[m], Mw.values[m]);
    std::sort(a.begin(), a.end());
    double diagonal = 0;
    for (const auto& [c, v] : e) diagonal = c == wr ? v : diagonal;
    bool same = a.size() == e.size();
    for (std::size_t m = 0; same && m < a.size(); ++m)
      same = a[m].first == e[m].first && std::abs(a[m].second - e[m].second) <= 1e-12 * diagonal;
    differ += !same;
    ++rows_compared;
  }
  EXPECT_EQ(differ, 0) << "of " << rows_compared << " rows on rank " << comm.rank();

  // BoomerAMG-CG on the blocks' rows: the single block's lattice pressure
  solvers::SolverControl control;
  control.relative_tolerance = 1e-11;
  using solvers::mac::PressureBackend;
  int iterations[2] = {0, 0};
  const auto solve_tall = [&](PressureBackend backend, const mesh::mac::TallCellGrid& grid,
                              const Block& B, int& its) {
    std::vector<double> bt(grid.unknowns()), lattice(B.grid.padded_size());
    grid.restrict_to_unknowns(B.b.data(), bt.data());
    auto solver = solvers::mac::make_tall_cell_pressure_solver(
        backend, Exec(), grid, kernels::mac::copy_stencil<Mem>(B.A));
    Kokkos::View<double*, Mem> y("y", grid.unknowns());
    const auto r = solver->solve(Exec(), kernels::to_view<Mem>(bt), y, control);
    EXPECT_TRUE(r.converged);
    its = r.iterations;
    grid.prolongate(kernels::to_std_vector(y).data(), lattice.data());
    return lattice;
  };
  // BoomerAMG-CG and the own tall-cell multigrid-CG on the blocks: the single block's pressure
  for (const auto backend : {PressureBackend::hypre, PressureBackend::multigrid}) {
    const Difference pq = block_difference(comm, S, solve_tall(backend, T, local, iterations[0]),
                                           solve_tall(backend, W, whole, iterations[1]));
    const double diff = pq.max, scale = pq.scale;
    EXPECT_GT(scale, 0.0);
    EXPECT_LT(diff, 1e-8 * scale) << solvers::mac::to_string(backend) << " on " << comm.size()
                                  << " ranks";
    // the V-cycle on the blocks is the single block's up to the eigenvalue estimates' start
    // vectors: as many iterations within 2
    EXPECT_LE(std::abs(iterations[0] - iterations[1]), 2) << solvers::mac::to_string(backend);
    if (comm.rank() == 0)
      std::printf(
          "tall cells (depth %d): %ld unknowns, %ld rows compared on rank 0; %s-CG on %d rank(s): "
          "%d "
          "iterations (%d on one block), max difference %.3g of %.3g\n",
          depth, W.unknowns(), rows_compared, solvers::mac::to_string(backend), comm.size(),
          iterations[0], iterations[1], diff, scale);
  }
  // one V-cycle of the tall-cell multigrid on the blocks is the single block's, to round-off
  using TallMG = solvers::mac::TallCellMultigrid<Exec>;
  solvers::mac::TallCellMultigridOptions deep;
  deep.max_coarse_cells = 64;  // down to 4^3: every transfer crosses the block faces
  const TallMG split_mg(Exec(), T, kernels::mac::copy_stencil<Mem>(local.A), deep);
  const TallMG whole_mg(Exec(), W, kernels::mac::copy_stencil<Mem>(whole.A), deep);
  EXPECT_EQ(split_mg.levels(), whole_mg.levels());
  const auto vcycle = [&](const TallMG& mg, const mesh::mac::TallCellGrid& grid, const Block& B) {
    std::vector<double> bt(grid.unknowns()), lattice(B.grid.padded_size());
    grid.restrict_to_unknowns(B.b.data(), bt.data());
    Kokkos::View<double*, Mem> z("z", grid.unknowns());
    mg.apply(Exec(), kernels::to_view<Mem>(bt), z);
    grid.prolongate(kernels::to_std_vector(z).data(), lattice.data());
    return lattice;
  };
  const Difference z =
      block_difference(comm, S, vcycle(split_mg, T, local), vcycle(whole_mg, W, whole));
  const double dz = z.max, zmax = z.scale;
  EXPECT_LT(dz, 1e-10 * zmax) << "tall-cell V-cycle on " << comm.size() << " ranks";
  if (comm.rank() == 0)
    std::printf("tall-cell V-cycle (%d levels): max difference %.3g of %.3g\n", split_mg.levels(),
                dz, zmax);
  if (comm.size() > 1) {  // MIC(0) solves one block only
    EXPECT_THROW(solvers::mac::make_tall_cell_pressure_solver(
                     PressureBackend::mic0, Exec(), T, kernels::mac::copy_stencil<Mem>(local.A)),
                 std::invalid_argument);
  }
}

INSTANTIATE_TEST_SUITE_P(SplitDirection, MacDecomposition, ::testing::Values(0, 2),
                         [](const ::testing::TestParamInfo<int>& direction) {
                           return direction.param == 0 ? "x" : "z";
                         });

}  // namespace
}  // namespace amphora
