#pragma once
// Errors against the exact 2D flows of flow_solutions.hpp, compiled once for every enabled
// execution space (flow_error_norms.cpp) instead of in every file that measures them: each is a
// sum-factorised quadrature kernel per degree 1-8.
#include "kernels/spaces.hpp"
#include "physics/ins_fem/flow_solutions.hpp"
#include "solvers/matrix_free/error_norms.hpp"

#define AMPHORA_FLOW_ERROR_NORMS(PREFIX, E)                                            \
  AMPHORA_ERROR_NORMS_INSTANCE(PREFIX, 2, E, amphora::physics::ins_fem::TaylorGreen2D) \
  AMPHORA_ERROR_NORMS_INSTANCE(PREFIX, 2, E, amphora::physics::ins_fem::Kovasznay)     \
  AMPHORA_ERROR_NORMS_INSTANCE(PREFIX, 2, E, amphora::physics::ins_fem::Poiseuille)
#define AMPHORA_FLOW_ERROR_NORMS_EXTERN(E) AMPHORA_FLOW_ERROR_NORMS(extern, E)
AMPHORA_FOR_EACH_EXEC_SPACE(AMPHORA_FLOW_ERROR_NORMS_EXTERN)
#undef AMPHORA_FLOW_ERROR_NORMS_EXTERN
