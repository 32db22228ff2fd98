#pragma once
// A tall-cell grid (Irving, Guendelman, Losasso & Fedkiw 2006, sec. 3) over a uniform MAC
// lattice: in each (x, z) column the cells within an optical depth of the free surface stay
// uniform; the fluid below them, down to the terrain, is one tall cell carrying two pressure
// samples (at the centres of its bottom and top lattice cells), linear in between.
//
// The pressure of the lattice is P y for the tall-cell unknowns y (P: the linear-in-height
// prolongation); the tall-cell matrix P^T A P is assembled in solvers/mac/tall_cell_matrix.
// Unknowns are numbered column by column (x fastest over columns): the tall
// cell's bottom and top samples, then the column's fluid cells upwards.
#include <vector>

#include "kernels/mac/poisson_stencil.hpp"

namespace amphora::mesh {

/// One (x, z) column: lattice rows [terrain, band) form the tall cell (empty if band == terrain),
/// rows band.. are uniform.
struct TallCellColumn {
  int terrain = 0;        ///< lowest fluid row (cells below are solid)
  int band = 0;           ///< lowest uniform row
  int first_unknown = 0;  ///< the column's first unknown
  KOKKOS_INLINE_FUNCTION bool has_tall_cell() const { return band > terrain; }
};

class TallCellGrid {
 public:
  /// The columns of A's fluid cells with uniform rows within optical_depth cells of the lowest
  /// non-fluid row above the terrain; a tall cell needs at least two rows (else the column stays
  /// uniform). A is on the host.
  TallCellGrid(const kernels::mac::PoissonStencil<HostMemSpace>& A, int optical_depth);

  const MacGrid& grid() const { return grid_; }
  long unknowns() const { return unknowns_; }
  int optical_depth() const { return optical_depth_; }
  long tall_cells() const { return tall_cells_; }
  const std::vector<TallCellColumn>& columns() const { return columns_; }
  /// Unknown of a uniform fluid cell (padded index), -1 elsewhere.
  const std::vector<int>& cell_unknown() const { return cell_unknown_; }

  /// The (at most two) unknowns and weights of lattice cell (i, j, k): p = sum w u.
  int weights(int i, int j, int k, int u[2], double w[2]) const;
  /// Lattice values P y (host, padded lattice; zero off the fluid).
  void prolongate(const double* y, double* lattice) const;
  /// y = P^T lattice.
  void restrict_to_unknowns(const double* lattice, double* y) const;

 private:
  MacGrid grid_;
  int optical_depth_ = 0;
  long unknowns_ = 0, tall_cells_ = 0;
  std::vector<TallCellColumn> columns_;
  std::vector<int> cell_unknown_;
};

}  // namespace amphora::mesh
