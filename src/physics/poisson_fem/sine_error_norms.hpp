#pragma once
// Errors against SineSolution, compiled once for every enabled execution space
// (sine_error_norms.cpp) instead of in every file that measures them: each is a sum-factorised
// quadrature kernel per degree 1-8.
#include "kernels/spaces.hpp"
#include "physics/poisson_fem/sine_solution.hpp"
#include "solvers/matrix_free/error_norms.hpp"

// PREFIX template error_norms<dim, E, SineSolution<dim>> for dim 2 and 3 (PREFIX: extern for
// the declaration, empty for the definition).
#define AMPHORA_SINE_ERROR_NORM(PREFIX, DIM, E)                                                 \
  PREFIX template amphora::solvers::matrix_free::ErrorNorms                                     \
  amphora::solvers::matrix_free::error_norms<DIM, E,                                            \
                                             amphora::physics::poisson_fem::SineSolution<DIM>>( \
      const E&, const amphora::mesh::hex::QkSpace<DIM, E>&,                                     \
      const Kokkos::View<double*, typename E::memory_space>&,                                   \
      const amphora::physics::poisson_fem::SineSolution<DIM>&);
#define AMPHORA_SINE_ERROR_NORMS(PREFIX, E) \
  AMPHORA_SINE_ERROR_NORM(PREFIX, 2, E)     \
  AMPHORA_SINE_ERROR_NORM(PREFIX, 3, E)

// At file scope: an explicit instantiation must be in a namespace enclosing the template's.
#define AMPHORA_SINE_ERROR_NORMS_EXTERN(E) AMPHORA_SINE_ERROR_NORMS(extern, E)
AMPHORA_FOR_EACH_EXEC_SPACE(AMPHORA_SINE_ERROR_NORMS_EXTERN)
#undef AMPHORA_SINE_ERROR_NORMS_EXTERN
