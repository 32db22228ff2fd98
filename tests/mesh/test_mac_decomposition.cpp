// The MAC pressure system split horizontally over ranks (x and z; columns stay whole): after a
// halo exchange of cell types and level set, each block's matrix equals the rows of the
// single-block matrix for its cells exactly, hypre PFMG-CG on the distributed system gives the
// single-block pressure to the solver tolerance, and the own multigrid on the blocks is the
// single block's (one V-cycle equal, CG in as many iterations to the same pressure), at 1 and 2
// ranks.
#include <mpi.h>

#include <cmath>
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
#include "test_backend.hpp"

namespace amphora {
namespace {

using mesh::MacCellType;
using mesh::MacGrid;
using Mem = test::TestMemSpace;
using Exec = test::TestExecSpace;

constexpr int N = 32;
double sq(double a) { return a * a; }
/// The scene: a sphere of water resting on an undulating floor, in a box with walls.
double level_set(const std::array<double, 3>& x) {
  return std::sqrt(sq(x[0] - 0.5) + sq(x[1] - 0.45) + sq(x[2] - 0.5)) - 0.37;
}
bool solid(const std::array<double, 3>& x) { return x[1] < 0.15 + 0.07 * std::sin(9 * x[0]) * std::cos(7 * x[2]); }
double source(const std::array<double, 3>& x) { return 1.0 + x[0] * x[2]; }

struct Block {
  MacGrid grid;
  mesh::MacBoxBoundaries faces;
  kernels::mac::PoissonStencil<HostMemSpace> A;
  std::vector<double> b;
};

/// A padded lattice array through the exchange of its ghost layer (host data).
template <class T>
void exchange(const mesh::LatticeGhostExchange& halo, const MacGrid& g, T* data) {
  Kokkos::View<T*, Mem> v("v", g.padded_size());
  Kokkos::deep_copy(v, Kokkos::View<T*, HostMemSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>(data, g.padded_size()));
  halo.exchange(Exec(), g, v);
  Kokkos::deep_copy(Kokkos::View<T*, HostMemSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>(data, g.padded_size()), v);
}

/// The block of `box` (global cell indices) with the given box faces; ghost types and phi come
/// from the neighbours by halo exchange when `halo` is given, else the block is the whole box.
Block make_block(const Box& box, const mesh::MacBoxBoundaries& faces, const mesh::LatticeGhostExchange* halo) {
  Block B;
  const double h = 1.0 / N;
  B.grid = MacGrid{box.extent(0), box.extent(1), box.extent(2), h, {box.lo[0] * h, box.lo[1] * h, box.lo[2] * h}};
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
        type[c] = std::uint8_t(solid(x) ? MacCellType::solid : phi[c] < 0 ? MacCellType::fluid : MacCellType::air);
      }
  if (halo) {
    exchange(*halo, g, type.data());
    exchange(*halo, g, phi.data());
  }
  std::vector<MacCellType> t(type.size());
  for (std::size_t c = 0; c < t.size(); ++c) t[c] = MacCellType(type[c]);
  B.A = kernels::mac::build_poisson_stencil<HostExecSpace, HostMemSpace>(
      HostExecSpace(), g, to_view<HostMemSpace>(t), to_view<HostMemSpace>(phi), faces);
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

std::vector<double> solve(MPI_Comm comm, const Block& B, const Index3& lower) {
  solvers::StructPfmgCG pfmg(comm, B.grid, {lower[0], lower[1], lower[2]}, B.A.diag.data(), B.A.cx.data(),
                             B.A.cy.data(), B.A.cz.data());
  std::vector<double> x(B.grid.padded_size(), 0.0);
  const auto r = pfmg.solve(B.b.data(), x.data(), 1e-11, 200);
  EXPECT_LE(r.final_relative_residual, 1e-11);
  return x;
}

TEST(MacDecomposition, BlockMatricesAndDistributedPressureMatchTheSingleBlock) {
  Communicator comm;
  const Index3 global{N, N, N};
  // horizontal only: the vertical (y) is never split
  const BoxDecomposition dec(global, {false, false, false}, comm.size(), 4, {true, false, true});
  ASSERT_EQ(dec.blocks()[1], 1);
  const Box box = dec.box(comm.rank());
  mesh::MacBoxBoundaries faces;
  for (int d = 0; d < 3; ++d)
    for (int side = 0; side < 2; ++side)
      faces[2 * d + side] = dec.neighbor(comm.rank(), d, side) >= 0 ? mesh::MacBoundary::neighbour
                                                                     : mesh::MacBoundary::wall;
  const mesh::MacBlock block = mesh::MacBlock::of(dec, comm.get(), comm.rank());
  const mesh::LatticeGhostExchange halo(block);
  const Block local = make_block(box, faces, &halo);

  mesh::MacBoxBoundaries walls;
  walls.fill(mesh::MacBoundary::wall);
  const Block whole = make_block(Box{{0, 0, 0}, global}, walls, nullptr);

  // every coefficient of this block's cells equals the single block's
  long compared = 0, differ = 0;
  const int sy = local.grid.stride_y(), sz = local.grid.stride_z();
  const int wy = whole.grid.stride_y(), wz = whole.grid.stride_z();
  for (int k = 0; k < local.grid.nz; ++k)
    for (int j = 0; j < local.grid.ny; ++j)
      for (int i = 0; i < local.grid.nx; ++i) {
        const int c = local.grid.index(i, j, k);
        const int w = whole.grid.index(box.lo[0] + i, box.lo[1] + j, box.lo[2] + k);
        const double a[7] = {local.A.diag(c), local.A.cx(c - 1), local.A.cx(c), local.A.cy(c - sy), local.A.cy(c),
                             local.A.cz(c - sz), local.A.cz(c)};
        const double e[7] = {whole.A.diag(w), whole.A.cx(w - 1), whole.A.cx(w), whole.A.cy(w - wy), whole.A.cy(w),
                             whole.A.cz(w - wz), whole.A.cz(w)};
        for (int m = 0; m < 7; ++m, ++compared) differ += a[m] != e[m];
      }
  EXPECT_EQ(differ, 0) << "of " << compared << " coefficients on rank " << comm.rank();

  // the distributed pressure equals the single-block one (solved on this rank alone)
  const std::vector<double> p = solve(comm.get(), local, box.lo);
  const std::vector<double> q = solve(MPI_COMM_SELF, whole, {0, 0, 0});
  double diff = 0, scale = 0;
  for (int k = 0; k < local.grid.nz; ++k)
    for (int j = 0; j < local.grid.ny; ++j)
      for (int i = 0; i < local.grid.nx; ++i) {
        const double pv = p[local.grid.index(i, j, k)];
        const double qv = q[whole.grid.index(box.lo[0] + i, box.lo[1] + j, box.lo[2] + k)];
        diff = std::max(diff, std::abs(pv - qv));
        scale = std::max(scale, std::abs(qv));
      }
  MPI_Allreduce(MPI_IN_PLACE, &diff, 1, MPI_DOUBLE, MPI_MAX, comm.get());
  MPI_Allreduce(MPI_IN_PLACE, &scale, 1, MPI_DOUBLE, MPI_MAX, comm.get());
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(diff, 1e-8 * scale) << "ranks " << comm.size();

  // the same through the pressure-solver interface; MIC(0) refuses a block
  const auto A = kernels::mac::copy_stencil<Mem>(local.A);
  auto hypre = solvers::mac::make_pressure_solver(solvers::mac::PressureBackend::hypre, Exec(), A, block);
  Kokkos::View<double*, Mem> x("x", local.grid.padded_size());
  solvers::SolverControl control;
  control.relative_tolerance = 1e-11;
  EXPECT_TRUE(hypre->solve(Exec(), to_view<Mem>(local.b), x, control).converged);
  const auto xh = to_std_vector(x);
  double d2 = 0;
  for (std::size_t c = 0; c < xh.size(); ++c) d2 = std::max(d2, std::abs(xh[c] - p[c]));
  EXPECT_LT(d2, 1e-12 * scale);
  if (comm.size() > 1) {
    EXPECT_THROW(solvers::mac::make_pressure_solver(solvers::mac::PressureBackend::mic0, Exec(), A, block),
                 std::invalid_argument);
  }

  // multigrid-CG on the blocks takes the single block's V-cycle: the same iterations and pressure
  const auto solve_mg = [&](const Block& B, const mesh::MacBlock& where, std::vector<double>& out) {
    auto mg = solvers::mac::make_pressure_solver(solvers::mac::PressureBackend::multigrid, Exec(),
                                                 kernels::mac::copy_stencil<Mem>(B.A), where);
    Kokkos::View<double*, Mem> xm("x", B.grid.padded_size());
    const auto r = mg->solve(Exec(), to_view<Mem>(B.b), xm, control);
    EXPECT_TRUE(r.converged);
    out = to_std_vector(xm);
    return r.iterations;
  };
  std::vector<double> pm, qm;
  const int split_iterations = solve_mg(local, block, pm);
  const int whole_iterations = solve_mg(whole, mesh::MacBlock{}, qm);
  EXPECT_EQ(split_iterations, whole_iterations) << "ranks " << comm.size();
  double d3 = 0;
  for (int k = 0; k < local.grid.nz; ++k)
    for (int j = 0; j < local.grid.ny; ++j)
      for (int i = 0; i < local.grid.nx; ++i)
        d3 = std::max(d3, std::abs(pm[local.grid.index(i, j, k)] -
                                   qm[whole.grid.index(box.lo[0] + i, box.lo[1] + j, box.lo[2] + k)]));
  MPI_Allreduce(MPI_IN_PLACE, &d3, 1, MPI_DOUBLE, MPI_MAX, comm.get());
  EXPECT_LT(d3, 1e-9 * scale) << "multigrid on " << comm.size() << " ranks, " << split_iterations << " iterations";
  // and one V-cycle on the blocks is the single block's V-cycle, to single-precision round-off
  using MG = solvers::mac::MacMultigrid<Exec>;
  const MG split_mg(Exec(), kernels::mac::copy_stencil<Mem>(local.A), {}, block);
  const MG whole_mg(Exec(), kernels::mac::copy_stencil<Mem>(whole.A));
  EXPECT_EQ(split_mg.levels(), whole_mg.levels());
  Kokkos::View<double*, Mem> zs("zs", local.grid.padded_size()), zw("zw", whole.grid.padded_size());
  split_mg.apply(Exec(), to_view<Mem>(local.b), zs);
  whole_mg.apply(Exec(), to_view<Mem>(whole.b), zw);
  const auto zsh = to_std_vector(zs), zwh = to_std_vector(zw);
  double d4 = 0, zmax = 0;
  for (int k = 0; k < local.grid.nz; ++k)
    for (int j = 0; j < local.grid.ny; ++j)
      for (int i = 0; i < local.grid.nx; ++i) {
        const double w = zwh[whole.grid.index(box.lo[0] + i, box.lo[1] + j, box.lo[2] + k)];
        d4 = std::max(d4, std::abs(zsh[local.grid.index(i, j, k)] - w));
        zmax = std::max(zmax, std::abs(w));
      }
  MPI_Allreduce(MPI_IN_PLACE, &d4, 1, MPI_DOUBLE, MPI_MAX, comm.get());
  EXPECT_LT(d4, 1e-6 * zmax) << "V-cycle on " << comm.size() << " ranks";
  if (comm.rank() == 0)
    std::printf("V-cycle: max difference %.3g of %.3g\n", d4, zmax);
  if (comm.rank() == 0)
    std::printf("multigrid-CG: %d iterations on %d rank(s), %d on one block; max difference %.3g of %.3g\n",
                split_iterations, comm.size(), whole_iterations, d3, scale);
}

}  // namespace
}  // namespace amphora
