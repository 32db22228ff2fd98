#pragma once
// The transfers between two levels of the tall-cell multigrid as assembled matrices, so a
// V-cycle moves between levels in work proportional to the unknowns, not to the lattices under
// them. The prolongation Q evaluates the coarse tall-cell pressure (linear in height inside a
// tall cell, one value per uniform cell) by cell-centred trilinear interpolation at each fine
// unknown's carrier cell (a uniform cell itself, a tall cell its bottom and top rows): the
// prolongation of McAdams, Sifakis & Teran (2010, sec. 4) at the box faces (even reflection at
// a wall, odd at an open face), with the weights of solid coarse cells (terrain) spread over
// the others in proportion (a zero normal derivative, as the uniform multigrid's extension into
// solids gives), air cells holding zero. The restriction is Q^T exactly, so the V-cycle stays
// symmetric for CG.
//
// On a split grid Q holds this block's fine rows with global coarse columns (its ghost ring's
// among them) and Q^T this block's coarse rows with global fine columns, gathered from the rows
// of the fine ghost ring too (a ring of one cell reaches every coarse cell of the block).
#include "mesh/mac/tall_cell_grid.hpp"
#include "solvers/csr_matrix.hpp"

namespace amphora::solvers::mac {

struct TallCellLevelTransfer {
  CsrMatrix prolongation;  ///< this block's fine unknowns x global coarse unknowns
  CsrMatrix restriction;   ///< this block's coarse unknowns x global fine unknowns (the transpose)
};

/// The transfers between `fine` and `coarse` (on the lattice with cells twice as wide); coarse_A
/// is the coarse lattice matrix on the host (its solid and fluid cells, its box faces; on a split
/// grid with its ghost ring exchanged).
TallCellLevelTransfer tall_cell_level_transfer(
    const mesh::mac::TallCellGrid& fine, const mesh::mac::TallCellGrid& coarse,
    const kernels::mac::PoissonStencil<kernels::HostMemSpace>& coarse_A);

}  // namespace amphora::solvers::mac
