// The matrix-free operators' kernels of the VANS point functor (velocity, pressure, with a void
// fraction), 2D and 3D.
#include "solvers/matrix_free/matrix_free_operator_install.hpp"

using amphora::kernels::sumfac::VansPoint;
AMPHORA_MF_FUNCTOR(VansPoint)
