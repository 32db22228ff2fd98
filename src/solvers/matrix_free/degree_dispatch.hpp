#pragma once
// The table of compiled kernels: (degree, quadrature points) -> a call of f with both as
// compile-time constants. Degrees 1..AMPHORA_SUMFAC_MAX_DEGREE, n_q = degree + 1 (Gauss,
// or Gauss–Lobatto collocation) and degree + 2 (the CEED BP3/BP4 rule). MatrixFreeOperator
// falls back to a run-time-size kernel (generic_cell_kernel.hpp) for other pairs.
#include <stdexcept>
#include <string>
#include <type_traits>

#ifndef AMPHORA_SUMFAC_MAX_DEGREE
#define AMPHORA_SUMFAC_MAX_DEGREE 8
#endif

namespace amphora::solvers::matrix_free {

inline constexpr int max_compiled_degree = AMPHORA_SUMFAC_MAX_DEGREE;

/// The point functors beyond mass and Laplace (convection, elasticity) are compiled to this
/// degree: each functor's table costs as much compile time as the mass's, most of it in the
/// highest degrees.
inline constexpr int max_compiled_degree_general =
    max_compiled_degree < 4 ? max_compiled_degree : 4;

/// The flow solver's functors (Oseen, and the divergence through elasticity) go to degree 6,
/// the range of the incompressible Navier-Stokes module.
inline constexpr int max_compiled_degree_flow = max_compiled_degree < 6 ? max_compiled_degree : 6;

/// The volume-averaged flow's functor (VANS, CFD-DEM) goes to degree 3.
inline constexpr int max_compiled_degree_vans = max_compiled_degree < 3 ? max_compiled_degree : 3;

/// True if the table up to degree `max` holds a kernel for (degree, n_q).
inline bool compiled_kernel(int degree, int n_q, int max = max_compiled_degree) {
  return degree >= 1 && degree <= max && (n_q == degree + 1 || n_q == degree + 2);
}

template <int k = 1, int max = max_compiled_degree, class F>
void dispatch_degree(int degree, int n_q, F&& f) {
  if (degree == k) {
    if (n_q == k + 1)
      return f(std::integral_constant<int, k + 1>{}, std::integral_constant<int, k + 1>{});
    if (n_q == k + 2)
      return f(std::integral_constant<int, k + 1>{}, std::integral_constant<int, k + 2>{});
    throw std::invalid_argument(
        "matrix-free: no kernel for degree " + std::to_string(degree) + " with " +
        std::to_string(n_q) +
        " quadrature points per direction; compiled: degree + 1 and degree + 2");
  }
  if constexpr (k < max) {
    dispatch_degree<k + 1, max>(degree, n_q, f);
  } else {
    throw std::invalid_argument("matrix-free: degree " + std::to_string(degree) +
                                " outside the compiled range 1.." + std::to_string(max));
  }
}

}  // namespace amphora::solvers::matrix_free
