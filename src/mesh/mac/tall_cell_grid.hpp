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
//
// On a grid split over ranks (mesh::mac::MacBlock) each block numbers its own columns, after the
// blocks of lower ranks (global number = local + first_unknown()), and learns the columns of
// its ghost ring (their rows and global unknowns) from the neighbouring blocks, so the matrix
// rows of its unknowns can be assembled with their couplings across the block faces.
#include <utility>
#include <vector>

#include "kernels/host_vector.hpp"
#include "kernels/mac/poisson_stencil.hpp"
#include "mesh/mac/lattice_halo.hpp"
#include "kernels/mac/tall_cell_columns.hpp"
#include "kernels/mac/tall_cell_layout.hpp"

namespace amphora::mesh::mac {

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
  /// uniform). A is on the host. On a split grid (block.split()) every rank of block.comm
  /// constructs its block's grid together (collective).
  TallCellGrid(const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A, int optical_depth,
               const MacBlock& block = {});
  /// The next coarser multigrid level's grid over A, whose lattice has cells twice as wide as
  /// finer's: a column has a tall cell where the four finer columns under it all have one, and
  /// its band is the coarse row holding the lowest of their bands (rounded up), so the coarse
  /// tall cells follow the finer ones (0.5 coarse rows at most apart) rather than A's surface
  /// (fewer CG iterations than bands from A's surface: docs/water.md). Collective on a split
  /// grid.
  TallCellGrid(const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A,
               const TallCellGrid& finer, const MacBlock& block = {});

  const kernels::mac::MacGrid& grid() const { return grid_; }
  const MacBlock& block() const { return block_; }
  /// This block's unknowns (all of them on one block).
  long unknowns() const { return unknowns_; }
  /// Global number of this block's first unknown (0 on one block), and of all blocks together.
  long first_unknown() const { return first_unknown_; }
  long global_unknowns() const { return global_unknowns_; }
  int optical_depth() const { return optical_depth_; }
  long tall_cells() const { return tall_cells_; }
  const std::vector<TallCellColumn>& columns() const { return columns_; }
  /// Unknown of a uniform fluid cell (padded index), -1 elsewhere (this block's numbering).
  const std::vector<int>& cell_unknown() const { return cell_unknown_; }
  /// Column (i, k) of the block or of its ghost ring (i = -1..nx, k = -1..nz; the ring's
  /// first_unknown in the global numbering; outside the global box: no fluid).
  const TallCellColumn& column(int i, int k) const {
    if (i >= 0 && i < grid_.nx && k >= 0 && k < grid_.nz) return columns_[i + grid_.nx * k];
    return ring_columns_.at((i + 1) + (grid_.nx + 2) * (k + 1));
  }
  /// Global number of the first unknown of column (i, k) (block or ghost ring).
  long global_first_unknown(int i, int k) const {
    const bool own = i >= 0 && i < grid_.nx && k >= 0 && k < grid_.nz;
    return (own ? first_unknown_ : 0) + column(i, k).first_unknown;
  }

  /// f(u, i, j, k) for the unknowns u of this block's column (i, k) in their order (this block's
  /// numbering) and the lattice cell (i, j, k) that carries each: a tall cell's bottom and top
  /// samples its lowest two cells, then the uniform fluid cells upwards.
  template <class F>
  void for_each_unknown_in_column(int i, int k, const F& f) const {
    for_each_carrier(columns_[i + grid_.nx * k], cell_unknown_, i, k, f);
  }
  /// The lattice cell (padded index) that carries each of this block's unknowns in a ghost
  /// exchange (as for_each_unknown_in_column).
  std::vector<int> unknown_cells() const;
  /// The same for the ghost ring's unknowns: (global unknown, padded index) pairs.
  std::vector<std::pair<long, int>> ring_unknown_cells() const;

  /// The (at most two) global unknowns and weights of lattice cell (i, j, k) of the block or of
  /// its ghost ring: p = sum w u.
  /// (Inline: the assemblies and level transfers call it a few times per unknown.)
  int weights(int i, int j, int k, int u[2], double w[2]) const {
    const bool own = i >= 0 && i < grid_.nx && k >= 0 && k < grid_.nz;
    const TallCellColumn& col = column(i, k);
    const long base = own ? first_unknown_ : 0;  // the ring's numbers are global already
    if (j >= col.terrain && j < col.band) {
      const double t = double(j - col.terrain) / double(col.band - 1 - col.terrain);
      u[0] = static_cast<int>(base + col.first_unknown), w[0] = 1.0 - t;
      u[1] = static_cast<int>(base + col.first_unknown + 1), w[1] = t;
      return 2;
    }
    const int unknown =
        own ? cell_unknown_[grid_.index(i, j, k)] : ring_unknown_.at(grid_.index(i, j, k));
    if (unknown < 0) return 0;
    u[0] = static_cast<int>(base + unknown), w[0] = 1.0;
    return 1;
  }
  /// Lattice values P y (host, padded lattice; zero off the fluid).
  void prolongate(const double* y, double* lattice) const;
  /// y = P^T lattice.
  void restrict_to_unknowns(const double* lattice, double* y) const;

 private:
  /// Columns (terrain: the lowest fluid row; band = band_of(i, k, terrain, top of the fluid run
  /// above it)), numbering and ghost ring.
  template <class Band>
  void build(const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A, const Band& band_of);
  void learn_ghost_ring();
  /// f(u, i, j, k) for the unknowns of column (i, k) as `uniform` (per padded cell) and the
  /// column number them.
  template <class F>
  void for_each_carrier(const TallCellColumn& col, const std::vector<int>& uniform, int i, int k,
                        const F& f) const {
    if (col.has_tall_cell()) {
      f(col.first_unknown, i, col.terrain, k);
      f(col.first_unknown + 1, i, col.terrain + 1, k);
    }
    for (int j = col.band; j < grid_.ny; ++j) {
      const int u = uniform[grid_.index(i, j, k)];
      if (u >= 0) f(u, i, j, k);
    }
  }

  kernels::mac::MacGrid grid_;
  MacBlock block_;
  int optical_depth_ = 0;
  long unknowns_ = 0, tall_cells_ = 0, first_unknown_ = 0, global_unknowns_ = 0;
  std::vector<TallCellColumn> columns_;
  std::vector<int> cell_unknown_;
  // the ghost ring: columns (nx + 2) x (nz + 2) padded (own ones unused), global unknowns of
  // its uniform cells per padded lattice index (-1: none)
  std::vector<TallCellColumn> ring_columns_;
  std::vector<int> ring_unknown_;
};

}  // namespace amphora::mesh::mac

namespace amphora::mesh::mac {

/// The grid's arrays in a memory space, for kernels.
template <class MemSpace>
kernels::mac::TallCellLayout<MemSpace> make_layout(const TallCellGrid& T) {
  std::vector<int> t, b, f;
  for (const TallCellColumn& c : T.columns())
    t.push_back(c.terrain), b.push_back(c.band), f.push_back(c.first_unknown);
  kernels::mac::TallCellLayout<MemSpace> L;
  L.grid = T.grid();
  L.terrain = kernels::to_view<MemSpace>(t, "amphora::tall::terrain");
  L.band = kernels::to_view<MemSpace>(b, "amphora::tall::band");
  L.first_unknown = kernels::to_view<MemSpace>(f, "amphora::tall::first_unknown");
  L.cell_unknown = kernels::to_view<MemSpace>(T.cell_unknown(), "amphora::tall::cell_unknown");
  return L;
}

}  // namespace amphora::mesh::mac
