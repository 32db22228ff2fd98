// The matrix-free operators' kernels of the Oseen point functor (velocity, pressure), 2D and 3D.
#include "solvers/matrix_free/matrix_free_operator_install.hpp"

using amphora::kernels::sumfac::OseenPoint;
AMPHORA_MF_FUNCTOR(OseenPoint)
