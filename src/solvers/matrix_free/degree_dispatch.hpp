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

namespace amphora::solvers {

inline constexpr int max_compiled_degree = AMPHORA_SUMFAC_MAX_DEGREE;

/// True if the table holds a kernel for (degree, n_q).
inline bool compiled_kernel(int degree, int n_q) {
  return degree >= 1 && degree <= max_compiled_degree && (n_q == degree + 1 || n_q == degree + 2);
}

template <int k = 1, class F>
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
  if constexpr (k < max_compiled_degree) {
    dispatch_degree<k + 1>(degree, n_q, f);
  } else {
    throw std::invalid_argument("matrix-free: degree " + std::to_string(degree) +
                                " outside the compiled range 1.." +
                                std::to_string(max_compiled_degree));
  }
}

}  // namespace amphora::solvers
