#pragma once
// The pressure matrix of a tall-cell grid, P^T A P (Irving et al. 2006, sec. 4: the tall-cell
// Laplacian from the linear-in-height pressure). A uniform cell's row is gathered: A's row times
// P (its neighbours' unknowns, two for a neighbour in a tall cell). A tall cell's two rows come
// from the quadratic form
//   p^T A p = sum_faces c_f (p_i - p_j)^2 + sum_cells D_i p_i^2,  p = P y,
// over the faces and cells that touch it, with the faces inside a tall cell and between two tall
// cells summed in closed blocks. Host. On a split grid: the rows of this block's unknowns
// (global column numbers), its ghost ring supplying the neighbours across the block faces.
#include "mesh/mac/tall_cell_grid.hpp"
#include "solvers/csr_matrix.hpp"

namespace amphora::solvers::mac {

CsrMatrix assemble_tall_cell_matrix(const mesh::mac::TallCellGrid& T,
                                    const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A);

}  // namespace amphora::solvers::mac
