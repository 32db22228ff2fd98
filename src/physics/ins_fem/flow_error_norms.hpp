#pragma once
// Errors against the exact 2D flows of flow_solutions.hpp, compiled once for every enabled
// execution space (flow_error_norms.cpp) instead of in every file that measures them: each is a
// sum-factorised quadrature kernel per degree 1-8.
#include "kernels/spaces.hpp"
#include "physics/ins_fem/flow_solutions.hpp"
#include "solvers/matrix_free/error_norms.hpp"

// PREFIX template error_norms<2, E, EXACT> (PREFIX: extern for the declaration, empty for the
// definition).
#define AMPHORA_FLOW_ERROR_NORM(PREFIX, E, EXACT)                                     \
  PREFIX template amphora::solvers::matrix_free::ErrorNorms                           \
  amphora::solvers::matrix_free::error_norms<2, E, amphora::physics::ins_fem::EXACT>( \
      const E&, const amphora::mesh::hex::QkSpace<2, E>&,                             \
      const Kokkos::View<double*, typename E::memory_space>&,                         \
      const amphora::physics::ins_fem::EXACT&);
#define AMPHORA_FLOW_ERROR_NORMS(PREFIX, E)         \
  AMPHORA_FLOW_ERROR_NORM(PREFIX, E, TaylorGreen2D) \
  AMPHORA_FLOW_ERROR_NORM(PREFIX, E, Kovasznay)     \
  AMPHORA_FLOW_ERROR_NORM(PREFIX, E, Poiseuille)

// At file scope: an explicit instantiation must be in a namespace enclosing the template's.
#define AMPHORA_FLOW_ERROR_NORMS_EXTERN(E) AMPHORA_FLOW_ERROR_NORMS(extern, E)
AMPHORA_FOR_EACH_EXEC_SPACE(AMPHORA_FLOW_ERROR_NORMS_EXTERN)
#undef AMPHORA_FLOW_ERROR_NORMS_EXTERN
