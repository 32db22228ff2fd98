#pragma once
// The pressure matrix of a tall-cell grid, P^T A P (Irving et al. 2006, sec. 4: the tall-cell
// Laplacian from the linear-in-height pressure), assembled by kernels in the stencil's memory
// space, one work item per row. A uniform cell's row is gathered: A's row times P (its
// neighbours' unknowns, two for a neighbour in a tall cell). A tall cell's two rows come from
// the quadratic form
//   p^T A p = sum_faces c_f (p_i - p_j)^2 + sum_cells D_i p_i^2,  p = P y,
// over the faces and cells that touch it, with the faces inside a tall cell and between two tall
// cells summed in closed blocks. Each row is written sorted by column (solvers/csr_rows.hpp:
// counted first on a device), so the matrix is the same on every backend and for any number of
// threads. On a split grid: the rows of this block's unknowns, its
// ghost ring supplying the neighbours across the block faces, with global columns or local ones
// (this block's unknowns, then the ring's slots: kernels::mac::TallCellRing).
#include "mesh/mac/tall_cell_grid.hpp"
#include "solvers/csr_matrix.hpp"
#include "solvers/device_csr.hpp"

namespace amphora::solvers::mac {

/// This block's rows of P^T A P in A's memory space, with the inverse diagonal; columns global,
/// or local (local_columns). Not collective: T's ring is known already. `carriers`:
/// tall_cell_carriers(exec, T) if the caller has them. device_schedule: the rows counted, then
/// written, as on a device, on host threads too (solvers/csr_rows.hpp; tests).
template <class ExecSpace>
DeviceCsrMatrix<typename ExecSpace::memory_space> assemble_tall_cell_matrix(
    const ExecSpace& exec, const mesh::mac::TallCellGrid& T,
    const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A, bool local_columns,
    Kokkos::View<int*, typename ExecSpace::memory_space> carriers = {},
    bool device_schedule = !kernels::runs_on_host_v<ExecSpace>);

/// The same on the host with global columns (the host back ends, hypre's and IC(0)'s).
CsrMatrix assemble_tall_cell_matrix(const mesh::mac::TallCellGrid& T,
                                    const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A);

/// The lattice cell carrying each of T's unknowns (as T.unknown_cells()), in MemSpace.
template <class ExecSpace>
Kokkos::View<int*, typename ExecSpace::memory_space> tall_cell_carriers(
    const ExecSpace& exec, const mesh::mac::TallCellGrid& T);

}  // namespace amphora::solvers::mac
