// The matrix-free operators' kernels of the elasticity point functor, 2D and 3D.
#include "solvers/matrix_free/matrix_free_operator_install.hpp"

using amphora::kernels::sumfac::ElasticityPoint;
AMPHORA_MF_FUNCTOR(ElasticityPoint)
