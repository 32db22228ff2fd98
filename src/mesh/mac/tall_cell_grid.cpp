#include "mesh/mac/tall_cell_grid.hpp"

#include <stdexcept>

namespace amphora::mesh {

TallCellGrid::TallCellGrid(const kernels::mac::PoissonStencil<HostMemSpace>& A, int optical_depth)
    : grid_(A.grid), optical_depth_(optical_depth) {
  if (optical_depth < 1) throw std::invalid_argument("tall cells: the optical depth must be at least one cell");
  const MacGrid& g = grid_;
  const auto& d = A.diag;
  columns_.resize(static_cast<std::size_t>(g.nx) * g.nz);
  cell_unknown_.assign(static_cast<std::size_t>(g.padded_size()), -1);
  long next = 0;
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) {
      TallCellColumn& col = columns_[i + g.nx * k];
      // a fluid cell is one with a diagonal
      tall_cell_rows(g.ny, optical_depth, [&](int j) { return d(g.index(i, j, k)) != 0.0; }, col.terrain, col.band);
      col.first_unknown = static_cast<int>(next);
      if (col.has_tall_cell()) {
        next += 2;
        ++tall_cells_;
      }
      for (int j = col.band; j < g.ny; ++j)
        if (d(g.index(i, j, k)) != 0.0) cell_unknown_[g.index(i, j, k)] = static_cast<int>(next++);
    }
  unknowns_ = next;
}

int TallCellGrid::weights(int i, int j, int k, int u[2], double w[2]) const {
  const TallCellColumn& col = columns_[i + grid_.nx * k];
  if (j >= col.terrain && j < col.band) {
    const double t = double(j - col.terrain) / double(col.band - 1 - col.terrain);
    u[0] = col.first_unknown, w[0] = 1.0 - t;
    u[1] = col.first_unknown + 1, w[1] = t;
    return 2;
  }
  const int unknown = cell_unknown_[grid_.index(i, j, k)];
  if (unknown < 0) return 0;
  u[0] = unknown, w[0] = 1.0;
  return 1;
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
        for (int m = 0; m < n; ++m) v += w[m] * y[u[m]];
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
        for (int m = 0; m < n; ++m) y[u[m]] += w[m] * lattice[g.index(i, j, k)];
      }
}

}  // namespace amphora::mesh
