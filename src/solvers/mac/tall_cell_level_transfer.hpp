#pragma once
// The transfers between two levels of the tall-cell multigrid as assembled matrices, so a
// V-cycle moves between levels in work proportional to the unknowns, not to the lattices under
// them. The prolongation Q evaluates the coarse tall-cell pressure (linear in height inside a
// tall cell, one value per uniform cell) by cell-centred trilinear interpolation at each fine
// unknown's carrier cell (a uniform cell itself, a tall cell its bottom and top rows): the
// prolongation of McAdams, Sifakis & Teran (2010, sec. 4) at the box faces (even reflection at
// a wall, odd at an open face), with the weights of solid coarse cells (terrain) spread over
// the others in proportion (a zero normal derivative, as the uniform multigrid's extension into
// solids gives), air cells holding zero. A tall cell's two rows are the least-squares fit of
// the interpolated pressure over its rows. The restriction is Q^T exactly, so the V-cycle
// stays symmetric for CG.
//
// Built by kernels in the stencil's memory space, with local columns: Q holds this block's
// fine rows over the coarse grid's local columns (its unknowns, then its ring's slots), Q^T
// this block's coarse rows over the fine grid's, gathered from the rows of the fine ghost ring
// too (a ring of one cell reaches every coarse cell of the block). Each row sums its terms in
// the order the interpolation meets them and lists them by column (a plain trilinear row in the
// order of its eight cells), so the matrices are the same for any number of threads.
#include "mesh/mac/tall_cell_grid.hpp"
#include "solvers/device_csr.hpp"

namespace amphora::solvers::mac {

template <class MemSpace>
struct TallCellLevelTransfer {
  DeviceCsrMatrix<MemSpace> prolongation;  ///< this block's fine unknowns x coarse columns
  DeviceCsrMatrix<MemSpace> restriction;   ///< this block's coarse unknowns x fine columns
};

/// The transfers between `fine` and `coarse` (on the lattice with cells twice as wide), both
/// built in coarse_A's memory space; coarse_A is the coarse lattice matrix (its solid and fluid
/// cells, its box faces; on a split grid with its ghost ring exchanged). fine_carriers: the
/// lattice cell of each of fine's unknowns (tall_cell_carriers). device_schedule: Q's rows
/// counted, then written, and Q^T by atomics, as on a device, on host threads too (tests).
template <class ExecSpace>
TallCellLevelTransfer<typename ExecSpace::memory_space> tall_cell_level_transfer(
    const ExecSpace& exec, const mesh::mac::TallCellGrid& fine,
    const mesh::mac::TallCellGrid& coarse,
    const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& coarse_A,
    const Kokkos::View<int*, typename ExecSpace::memory_space>& fine_carriers,
    bool device_schedule = !kernels::runs_on_host_v<ExecSpace>);

}  // namespace amphora::solvers::mac
