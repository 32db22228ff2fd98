#include "solvers/matrix_free/transfer_impl.hpp"

namespace amphora::solvers::matrix_free {
#define AMPHORA_MF_TRANSFER(E)             \
  template class MatrixFreeTransfer<2, E>; \
  template class MatrixFreeTransfer<3, E>;
AMPHORA_IF_SERIAL(AMPHORA_MF_TRANSFER(Kokkos::Serial))
AMPHORA_IF_OPENMP(AMPHORA_MF_TRANSFER(Kokkos::OpenMP))
AMPHORA_IF_CUDA(AMPHORA_MF_TRANSFER(Kokkos::Cuda))
}  // namespace amphora::solvers::matrix_free
