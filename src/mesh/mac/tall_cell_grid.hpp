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
#include <type_traits>

#include "kernels/mac/poisson_stencil.hpp"
#include "mesh/mac/lattice_halo.hpp"
#include "kernels/mac/tall_cell_columns.hpp"
#include "kernels/mac/tall_cell_layout.hpp"
#include "kernels/mac/tall_cell_numbering.hpp"

namespace amphora::mesh::mac {

/// One (x, z) column: lattice rows [terrain, band) form the tall cell (empty if band == terrain),
/// rows band.. are uniform.
struct TallCellColumn {
  int terrain = 0;        ///< lowest fluid row (cells below are solid)
  int band = 0;           ///< lowest uniform row
  int first_unknown = 0;  ///< the column's first unknown
  KOKKOS_INLINE_FUNCTION bool has_tall_cell() const { return band > terrain; }
};

namespace detail {
template <class MemSpace, class View>
auto copy_to(const View& v) {
  return Kokkos::create_mirror_view_and_copy(MemSpace(), v);
}
/// M's arrays in MemSpace (the same Views where they are there already).
template <class MemSpace, class From>
kernels::mac::TallCellMap<MemSpace> copy_map(const kernels::mac::TallCellMap<From>& M) {
  kernels::mac::TallCellMap<MemSpace> C;
  C.first = M.first, C.split = M.split;
  C.own.grid = M.own.grid;
  C.own.terrain = copy_to<MemSpace>(M.own.terrain);
  C.own.band = copy_to<MemSpace>(M.own.band);
  C.own.first_unknown = copy_to<MemSpace>(M.own.first_unknown);
  C.own.cell_unknown = copy_to<MemSpace>(M.own.cell_unknown);
  if (!M.split) return C;
  C.ring.slots = M.ring.slots;
  C.ring.terrain = copy_to<MemSpace>(M.ring.terrain);
  C.ring.band = copy_to<MemSpace>(M.ring.band);
  C.ring.first_unknown = copy_to<MemSpace>(M.ring.first_unknown);
  C.ring.unknown = copy_to<MemSpace>(M.ring.unknown);
  C.ring.first_slot = copy_to<MemSpace>(M.ring.first_slot);
  C.ring.slot = copy_to<MemSpace>(M.ring.slot);
  C.ring.slot_cell = copy_to<MemSpace>(M.ring.slot_cell);
  return C;
}
}  // namespace detail

class TallCellGrid {
 public:
  /// The columns of A's fluid cells with uniform rows within optical_depth cells of the lowest
  /// non-fluid row above the terrain; a tall cell needs at least two rows (else the column stays
  /// uniform). Built by kernels on exec in A's memory space (kernels/mac/tall_cell_numbering);
  /// the host's accessors below read a host copy made at their first call. On a split grid
  /// (block.split()) every rank of block.comm constructs its block's grid together
  /// (collective).
  template <class ExecSpace>
  TallCellGrid(const ExecSpace& exec,
               const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A,
               int optical_depth, const MacBlock& block = {});
  /// The next coarser multigrid level's grid over A, whose lattice has cells twice as wide as
  /// finer's: a column has a tall cell where the four finer columns under it all have one, and
  /// its band is the coarse row holding the lowest of their bands (rounded up), so the coarse
  /// tall cells follow the finer ones (0.5 coarse rows at most apart) rather than A's surface
  /// (fewer CG iterations than bands from A's surface: docs/water.md). Collective on a split
  /// grid.
  template <class ExecSpace>
  TallCellGrid(const ExecSpace& exec,
               const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A,
               const TallCellGrid& finer, const MacBlock& block = {});
  /// The same from a host stencil, built by the host's threads.
  TallCellGrid(const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A, int optical_depth,
               const MacBlock& block = {})
      : TallCellGrid(kernels::HostExecSpace(), A, optical_depth, block) {}
  TallCellGrid(const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A,
               const TallCellGrid& finer, const MacBlock& block = {})
      : TallCellGrid(kernels::HostExecSpace(), A, finer, block) {}

  const kernels::mac::MacGrid& grid() const { return grid_; }
  const MacBlock& block() const { return block_; }
  /// This block's unknowns (all of them on one block).
  long unknowns() const { return unknowns_; }
  /// Global number of this block's first unknown (0 on one block), and of all blocks together.
  long first_unknown() const { return first_unknown_; }
  long global_unknowns() const { return global_unknowns_; }
  int optical_depth() const { return optical_depth_; }
  long tall_cells() const { return tall_cells_; }
  /// The grid in MemSpace, for kernels: the arrays it was built in (no copy), or the host's.
  template <class MemSpace>
  kernels::mac::TallCellMap<MemSpace> map() const;
  template <class MemSpace>
  kernels::mac::TallCellLayout<MemSpace> layout() const {
    return map<MemSpace>().own;
  }
  /// Unknown of a uniform fluid cell (padded index), -1 elsewhere (this block's numbering; host).
  const Kokkos::View<int*, kernels::HostMemSpace>& cell_unknown() const {
    return host().own.cell_unknown;
  }
  /// Column (i, k) of the block or of its ghost ring (i = -1..nx, k = -1..nz; the ring's
  /// first_unknown in the global numbering; outside the global box: no fluid).
  TallCellColumn column(int i, int k) const {
    TallCellColumn c;
    host().column(i, k, c.terrain, c.band, c.first_unknown);
    return c;
  }
  /// The (at most two) global unknowns and weights of lattice cell (i, j, k) of the block or of
  /// its ghost ring: p = sum w u.
  /// (Inline: the assemblies and level transfers call it a few times per unknown.)
  int weights(int i, int j, int k, int u[2], double w[2]) const {
    return host().weights(i, j, k, u, w);
  }
  /// Lattice values P y (host, padded lattice; zero off the fluid).
  void prolongate(const double* y, double* lattice) const;
  /// y = P^T lattice.
  void restrict_to_unknowns(const double* lattice, double* y) const;

 private:
  /// Columns and numbering by the kernels (band_of: the band rule), the ghost ring on a split
  /// grid, and the host copies.
  template <class ExecSpace, class Stencil, class Band>
  void build(const ExecSpace& exec, const Stencil& A, const Band& band_of);
  kernels::mac::MacGrid grid_;
  MacBlock block_;
  int optical_depth_ = 0;
  long unknowns_ = 0, tall_cells_ = 0, first_unknown_ = 0, global_unknowns_ = 0;
  /// The arrays on the host: the built ones where the host can read them, else a copy made at
  /// the first call (from one thread), so a step that never asks copies nothing.
  const kernels::mac::TallCellMap<kernels::HostMemSpace>& host() const {
    if (host_.own.cell_unknown.data() == nullptr)
      host_ = detail::copy_map<kernels::HostMemSpace>(built_);
    return host_;
  }

  /// the arrays where they were built (the default memory space's, if they were built there)
  /// and on the host (host())
  kernels::mac::TallCellMap<kernels::DefaultMemSpace> built_;
  mutable kernels::mac::TallCellMap<kernels::HostMemSpace> host_;
};

template <class MemSpace>
kernels::mac::TallCellMap<MemSpace> TallCellGrid::map() const {
  if constexpr (std::is_same_v<MemSpace, kernels::DefaultMemSpace>) {
    if (built_.own.cell_unknown.data() != nullptr) return built_;
  }
  if constexpr (std::is_same_v<MemSpace, kernels::HostMemSpace>)
    return host();
  else
    return detail::copy_map<MemSpace>(host());
}

}  // namespace amphora::mesh::mac
