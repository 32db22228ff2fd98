// Instances of MatrixFreeOperator for dim = 3 (one file per dimension: parallel compilation).
#include "solvers/matrix_free/matrix_free_operator_impl.hpp"

namespace amphora::solvers::matrix_free {
#define AMPHORA_MF_OPERATOR(E) template class MatrixFreeOperator<3, E>;
AMPHORA_IF_SERIAL(AMPHORA_MF_OPERATOR(Kokkos::Serial))
AMPHORA_IF_OPENMP(AMPHORA_MF_OPERATOR(Kokkos::OpenMP))
AMPHORA_IF_CUDA(AMPHORA_MF_OPERATOR(Kokkos::Cuda))
#undef AMPHORA_MF_OPERATOR  // the unity build puts the 2D and 3D files in one unit
}  // namespace amphora::solvers::matrix_free
