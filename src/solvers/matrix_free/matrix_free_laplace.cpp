// The matrix-free operators' kernels of the laplace point functor, 2D and 3D.
#include "solvers/matrix_free/matrix_free_operator_install.hpp"

using amphora::kernels::sumfac::LaplacePoint;
AMPHORA_MF_FUNCTOR(LaplacePoint)
