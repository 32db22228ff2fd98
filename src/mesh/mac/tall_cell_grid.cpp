#include "mesh/mac/tall_cell_grid.hpp"

#include <mpi.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace amphora::mesh::mac {

template <class ExecSpace>
TallCellGrid::TallCellGrid(const ExecSpace& exec,
                           const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A,
                           int optical_depth, const MacBlock& block)
    : grid_(A.grid), block_(block), optical_depth_(optical_depth) {
  if (optical_depth < 1)
    throw std::invalid_argument("tall cells: the optical depth must be at least one cell");
  // the rule of the water module's columns (TallCellColumns: tall_cell_rows)
  build(exec, A, kernels::mac::OpticalDepthBand{optical_depth});
}

template <class ExecSpace>
TallCellGrid::TallCellGrid(const ExecSpace& exec,
                           const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A,
                           const TallCellGrid& finer, const MacBlock& block)
    : grid_(A.grid), block_(block), optical_depth_((finer.optical_depth() + 1) / 2) {
  const kernels::mac::MacGrid& f = finer.grid();
  if (f.nx != 2 * grid_.nx || f.ny != 2 * grid_.ny || f.nz != 2 * grid_.nz)
    throw std::invalid_argument(
        "tall cells: a coarser level's lattice must have half the finer one's cells");
  using Mem = typename ExecSpace::memory_space;
  const auto F = finer.layout<Mem>();
  build(exec, A, kernels::mac::FollowFinerBand<Mem>{F.terrain, F.band, f.nx, f.ny});
}

template <class ExecSpace, class Stencil, class Band>
void TallCellGrid::build(const ExecSpace& exec, const Stencil& A, const Band& band_of) {
  using Mem = typename ExecSpace::memory_space;
  kernels::mac::TallCellMap<Mem> M;
  M.own.grid = grid_;
  unknowns_ = kernels::mac::number_tall_cells(
      exec, M.own, kernels::mac::NonzeroDiagonal<decltype(A.diag)>{A.diag}, band_of);
  global_unknowns_ = unknowns_;
  if (block_.split()) {
    MPI_Exscan(&unknowns_, &first_unknown_, 1, MPI_LONG, MPI_SUM, block_.comm);
    int rank = 0;
    MPI_Comm_rank(block_.comm, &rank);
    if (rank == 0) first_unknown_ = 0;  // MPI_Exscan leaves rank 0's result undefined
    MPI_Allreduce(&unknowns_, &global_unknowns_, 1, MPI_LONG, MPI_SUM, block_.comm);
    // the ring: each block's codes per cell, exchanged, read back
    Kokkos::View<long*, Mem> code(
        Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall::ring_code")),
        grid_.padded_size());
    kernels::mac::tall_cell_ring_codes(exec, M.own, first_unknown_, code);
    LatticeGhostExchange(block_).exchange(exec, grid_, code);
    M.ring = kernels::mac::read_tall_cell_ring<ExecSpace, Mem>(exec, grid_, code);
    M.split = true;
  }
  M.first = first_unknown_;
  if constexpr (std::is_same_v<Mem, kernels::DefaultMemSpace>) built_ = M;
  if constexpr (std::is_same_v<Mem, kernels::HostMemSpace>) host_ = M;
  tall_cells_ = kernels::mac::count_tall_cells(exec, M.own);
}

#define AMPHORA_TALL_CELL_GRID(E)                                                            \
  template TallCellGrid::TallCellGrid(                                                       \
      const E&, const kernels::mac::PoissonStencil<E::memory_space>&, int, const MacBlock&); \
  template TallCellGrid::TallCellGrid(const E&,                                              \
                                      const kernels::mac::PoissonStencil<E::memory_space>&,  \
                                      const TallCellGrid&, const MacBlock&);
AMPHORA_FOR_EACH_EXEC_SPACE(AMPHORA_TALL_CELL_GRID)
#undef AMPHORA_TALL_CELL_GRID

void TallCellGrid::prolongate(const double* y, double* lattice) const {
  const kernels::mac::MacGrid& g = grid_;
  const auto& M = host();
  for (long c = 0; c < g.padded_size(); ++c) lattice[c] = 0.0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        int u[2];
        double w[2];
        const int n = M.weights(i, j, k, u, w);
        double v = 0.0;
        for (int m = 0; m < n; ++m) v += w[m] * y[u[m] - first_unknown_];
        lattice[g.index(i, j, k)] = v;
      }
}

void TallCellGrid::restrict_to_unknowns(const double* lattice, double* y) const {
  const kernels::mac::MacGrid& g = grid_;
  const auto& M = host();
  for (long u = 0; u < unknowns_; ++u) y[u] = 0.0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        int u[2];
        double w[2];
        const int n = M.weights(i, j, k, u, w);
        for (int m = 0; m < n; ++m) y[u[m] - first_unknown_] += w[m] * lattice[g.index(i, j, k)];
      }
}

}  // namespace amphora::mesh::mac
