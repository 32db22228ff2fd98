#pragma once
// Errors against SineSolution, compiled once for every enabled execution space
// (sine_error_norms.cpp) instead of in every file that measures them: each is a sum-factorised
// quadrature kernel per degree 1-8.
#include "kernels/spaces.hpp"
#include "physics/poisson_fem/sine_solution.hpp"
#include "solvers/matrix_free/error_norms.hpp"

#define AMPHORA_SINE_ERROR_NORMS(PREFIX, E)                                                  \
  AMPHORA_ERROR_NORMS_INSTANCE(PREFIX, 2, E, amphora::physics::poisson_fem::SineSolution<2>) \
  AMPHORA_ERROR_NORMS_INSTANCE(PREFIX, 3, E, amphora::physics::poisson_fem::SineSolution<3>)
#define AMPHORA_SINE_ERROR_NORMS_EXTERN(E) AMPHORA_SINE_ERROR_NORMS(extern, E)
AMPHORA_FOR_EACH_EXEC_SPACE(AMPHORA_SINE_ERROR_NORMS_EXTERN)
#undef AMPHORA_SINE_ERROR_NORMS_EXTERN
