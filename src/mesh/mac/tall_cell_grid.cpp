#include "mesh/mac/tall_cell_grid.hpp"

#include <mpi.h>

#include <algorithm>
#include <stdexcept>

namespace amphora::mesh::mac {

using kernels::mac::fluid_run;
using kernels::mac::MacGrid;
using kernels::mac::tall_cell_band;

TallCellGrid::TallCellGrid(const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A,
                           int optical_depth, const MacBlock& block)
    : grid_(A.grid), block_(block), optical_depth_(optical_depth) {
  if (optical_depth < 1)
    throw std::invalid_argument("tall cells: the optical depth must be at least one cell");
  // the rule of the water module's columns (TallCellColumns: tall_cell_rows)
  build(A, [&](int, int, int terrain, int fluid_top) {
    return tall_cell_band(terrain, fluid_top - optical_depth);
  });
}

TallCellGrid::TallCellGrid(const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A,
                           const TallCellGrid& finer, const MacBlock& block)
    : grid_(A.grid), block_(block), optical_depth_((finer.optical_depth() + 1) / 2) {
  const MacGrid& f = finer.grid();
  if (f.nx != 2 * grid_.nx || f.ny != 2 * grid_.ny || f.nz != 2 * grid_.nz)
    throw std::invalid_argument(
        "tall cells: a coarser level's lattice must have half the finer one's cells");
  build(A, [&](int i, int k, int terrain, int fluid_top) {
    // the lowest band of the four finer columns, all with a tall cell (else none here)
    int lowest = f.ny;
    for (int c = 0; c < 2; ++c)
      for (int a = 0; a < 2; ++a) {
        const TallCellColumn& child = finer.column(2 * i + a, 2 * k + c);
        if (!child.has_tall_cell()) return terrain;
        lowest = std::min(lowest, child.band);
      }
    return tall_cell_band(terrain, std::min((lowest + 1) / 2, fluid_top));
  });
}

template <class Band>
void TallCellGrid::build(const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A,
                         const Band& band_of) {
  const MacGrid& g = grid_;
  const auto& d = A.diag;
  columns_.resize(static_cast<std::size_t>(g.nx) * g.nz);
  cell_unknown_.assign(static_cast<std::size_t>(g.padded_size()), -1);
  // Lines of columns in parallel: each column's rows and its number of unknowns, then (after the
  // running sum, in column order) its unknowns' numbers, so the numbering is the serial one.
  std::vector<int> count(columns_.size());
  Kokkos::parallel_for("amphora::tall::grid_columns",
                       Kokkos::RangePolicy<kernels::HostExecSpace>(0, g.nz), [&](int k) {
                         for (int i = 0; i < g.nx; ++i) {
                           TallCellColumn& col = columns_[i + g.nx * k];
                           // a fluid cell is one with a diagonal: the column's lowest run of them
                           int terrain, top;
                           fluid_run(
                               g.ny, [&](int j) { return d(g.index(i, j, k)) != 0.0; }, terrain,
                               top);
                           col.terrain = terrain;
                           col.band = band_of(i, k, terrain, top);
                           int n = col.has_tall_cell() ? 2 : 0;
                           for (int j = col.band; j < g.ny; ++j) n += d(g.index(i, j, k)) != 0.0;
                           count[i + g.nx * k] = n;
                         }
                       });
  long next = 0;
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    columns_[c].first_unknown = static_cast<int>(next);
    next += count[c];
    tall_cells_ += columns_[c].has_tall_cell();
  }
  Kokkos::parallel_for("amphora::tall::grid_numbering",
                       Kokkos::RangePolicy<kernels::HostExecSpace>(0, g.nz), [&](int k) {
                         for (int i = 0; i < g.nx; ++i) {
                           const TallCellColumn& col = columns_[i + g.nx * k];
                           int u = col.first_unknown + (col.has_tall_cell() ? 2 : 0);
                           for (int j = col.band; j < g.ny; ++j)
                             if (d(g.index(i, j, k)) != 0.0) cell_unknown_[g.index(i, j, k)] = u++;
                         }
                       });
  unknowns_ = next;
  global_unknowns_ = unknowns_;
  if (block_.split()) {
    MPI_Exscan(&unknowns_, &first_unknown_, 1, MPI_LONG, MPI_SUM, block_.comm);
    int rank = 0;
    MPI_Comm_rank(block_.comm, &rank);
    if (rank == 0) first_unknown_ = 0;  // MPI_Exscan leaves rank 0's result undefined
    MPI_Allreduce(&unknowns_, &global_unknowns_, 1, MPI_LONG, MPI_SUM, block_.comm);
    learn_ghost_ring();
  }
}

// Each block writes, per padded lattice cell of its own, the global unknown of a uniform fluid
// cell (>= 0), -(first unknown + 2) for a cell of a tall cell, -1 elsewhere; after the ghost
// exchange the ring's columns are read back from their cells.
void TallCellGrid::learn_ghost_ring() {
  const MacGrid& g = grid_;
  Kokkos::View<long*, kernels::HostMemSpace> code("amphora::tall::ring_code", g.padded_size());
  Kokkos::deep_copy(code, -1L);
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) {
      const TallCellColumn& col = columns_[i + g.nx * k];
      for (int j = col.terrain; j < g.ny; ++j) {
        const int c = g.index(i, j, k);
        if (j < col.band)
          code(c) = -(first_unknown_ + col.first_unknown + 2);
        else if (cell_unknown_[c] >= 0)
          code(c) = first_unknown_ + cell_unknown_[c];
      }
    }
  LatticeGhostExchange(block_).exchange(kernels::HostExecSpace(), g, code);
  ring_columns_.assign(static_cast<std::size_t>(g.nx + 2) * (g.nz + 2),
                       TallCellColumn{g.ny, g.ny, -1});
  ring_unknown_.assign(static_cast<std::size_t>(g.padded_size()), -1);
  for (int k = -1; k <= g.nz; ++k)
    for (int i = -1; i <= g.nx; ++i) {
      if (i >= 0 && i < g.nx && k >= 0 && k < g.nz) continue;
      TallCellColumn& col = ring_columns_[(i + 1) + (g.nx + 2) * (k + 1)];
      int j = 0;
      while (j < g.ny && code(g.index(i, j, k)) == -1) ++j;
      col.terrain = col.band = j;
      if (j < g.ny && code(g.index(i, j, k)) < -1) {
        col.first_unknown = static_cast<int>(-code(g.index(i, j, k)) - 2);
        while (col.band < g.ny && code(g.index(i, col.band, k)) < -1) ++col.band;
      }
      for (int jj = col.band; jj < g.ny; ++jj)
        ring_unknown_[g.index(i, jj, k)] = static_cast<int>(code(g.index(i, jj, k)));
    }
}

std::vector<int> TallCellGrid::unknown_cells() const {
  std::vector<int> cell(unknowns_, -1);
  for (int k = 0; k < grid_.nz; ++k)
    for (int i = 0; i < grid_.nx; ++i)
      for_each_unknown_in_column(
          i, k, [&](int u, int ci, int cj, int ck) { cell[u] = grid_.index(ci, cj, ck); });
  return cell;
}

std::vector<std::pair<long, int>> TallCellGrid::ring_unknown_cells() const {
  std::vector<std::pair<long, int>> out;
  if (ring_columns_.empty()) return out;
  for (int k = -1; k <= grid_.nz; ++k)
    for (int i = -1; i <= grid_.nx; ++i) {
      if (i >= 0 && i < grid_.nx && k >= 0 && k < grid_.nz) continue;
      for_each_carrier(column(i, k), ring_unknown_, i, k, [&](int u, int ci, int cj, int ck) {
        out.emplace_back(u, grid_.index(ci, cj, ck));
      });
    }
  return out;
}

void TallCellGrid::prolongate(const double* y, double* lattice) const {
  const MacGrid& g = grid_;
  for (long c = 0; c < g.padded_size(); ++c) lattice[c] = 0.0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        int u[2];
        double w[2];
        const int n = weights(i, j, k, u, w);
        double v = 0.0;
        for (int m = 0; m < n; ++m) v += w[m] * y[u[m] - first_unknown_];
        lattice[g.index(i, j, k)] = v;
      }
}

void TallCellGrid::restrict_to_unknowns(const double* lattice, double* y) const {
  const MacGrid& g = grid_;
  for (long u = 0; u < unknowns_; ++u) y[u] = 0.0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        int u[2];
        double w[2];
        const int n = weights(i, j, k, u, w);
        for (int m = 0; m < n; ++m) y[u[m] - first_unknown_] += w[m] * lattice[g.index(i, j, k)];
      }
}

}  // namespace amphora::mesh::mac
