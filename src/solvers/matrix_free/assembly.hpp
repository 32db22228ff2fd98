#pragma once
// The assembled matrix of a matrix-free operator (any number of blocked components), from its
// element matrices, with the Dirichlet rows and columns of its constrained components replaced
// by identity: the same constrained system the operator applies. For coarse-grid AMG and for
// comparisons against sparse-matrix solvers.
#include "solvers/csr_matrix.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"

namespace amphora::solvers::matrix_free {

template <int dim, class ExecSpace>
CsrMatrix assemble(const ExecSpace& exec, const MatrixFreeOperator<dim, ExecSpace>& op);

}  // namespace amphora::solvers::matrix_free
