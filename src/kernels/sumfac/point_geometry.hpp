#pragma once
// Point-wise geometry of the map x(xi) at one quadrature point, from its Jacobian
// J_ab = d x_a / d xi_b: the factors the operators need, all including det(J) and the
// quadrature weight w (so an operator is a weighted contraction with them):
//   mass:        w det J
//   Laplace:     G = w det J J^-1 J^-T           (symmetric; packed 00 01 11 | 00 01 02 11 12 22)
//   convection:  c = w det J J^-1 b
// A coefficient a(x) of a variable-coefficient Laplace multiplies G.
#include <Kokkos_Core.hpp>

namespace amphora::kernels::sumfac {

template <int dim>
inline constexpr int n_symmetric = dim*(dim + 1) / 2;

/// Index of (a, b), a <= b, in the packed symmetric storage.
template <int dim>
KOKKOS_INLINE_FUNCTION constexpr int sym_index(int a, int b) {
  if (a > b) {
    const int t = a;
    a = b;
    b = t;
  }
  return dim == 2 ? a + b : (a == 0 ? b : a + b + 1);
}

/// det J and J^-1 (row-major) of a dim x dim matrix.
template <int dim, class T>
KOKKOS_INLINE_FUNCTION T inverse(const T* J, T* inv) {
  if constexpr (dim == 2) {
    const T det = J[0] * J[3] - J[1] * J[2];
    const T r = T(1.0) / det;
    inv[0] = J[3] * r;
    inv[1] = -J[1] * r;
    inv[2] = -J[2] * r;
    inv[3] = J[0] * r;
    return det;
  } else {
    const T c00 = J[4] * J[8] - J[5] * J[7], c01 = J[5] * J[6] - J[3] * J[8],
            c02 = J[3] * J[7] - J[4] * J[6];
    const T det = J[0] * c00 + J[1] * c01 + J[2] * c02;
    const T r = T(1.0) / det;
    inv[0] = c00 * r;
    inv[1] = (J[2] * J[7] - J[1] * J[8]) * r;
    inv[2] = (J[1] * J[5] - J[2] * J[4]) * r;
    inv[3] = c01 * r;
    inv[4] = (J[0] * J[8] - J[2] * J[6]) * r;
    inv[5] = (J[2] * J[3] - J[0] * J[5]) * r;
    inv[6] = c02 * r;
    inv[7] = (J[1] * J[6] - J[0] * J[7]) * r;
    inv[8] = (J[0] * J[4] - J[1] * J[3]) * r;
    return det;
  }
}

/// G (packed) = scale det J J^-1 J^-T.
template <int dim, class T>
KOKKOS_INLINE_FUNCTION void laplace_metric(const T* J, const T& scale, T* G) {
  T inv[dim * dim];
  const T f = scale * inverse<dim>(J, inv);
  for (int a = 0; a < dim; ++a)
    for (int b = a; b < dim; ++b) {
      T s = T(0.0);
      for (int k = 0; k < dim; ++k) s += inv[a * dim + k] * inv[b * dim + k];
      G[sym_index<dim>(a, b)] = f * s;
    }
}

/// c = scale det J J^-1 b.
template <int dim, class T>
KOKKOS_INLINE_FUNCTION void convection_metric(const T* J, const T& scale, const T* b, T* c) {
  T inv[dim * dim];
  const T f = scale * inverse<dim>(J, inv);
  for (int a = 0; a < dim; ++a) {
    T s = T(0.0);
    for (int k = 0; k < dim; ++k) s += inv[a * dim + k] * b[k];
    c[a] = f * s;
  }
}

template <int dim, class T>
KOKKOS_INLINE_FUNCTION T determinant(const T* J) {
  if constexpr (dim == 2) {
    return J[0] * J[3] - J[1] * J[2];
  } else {
    return J[0] * (J[4] * J[8] - J[5] * J[7]) + J[1] * (J[5] * J[6] - J[3] * J[8]) +
           J[2] * (J[3] * J[7] - J[4] * J[6]);
  }
}

}  // namespace amphora::kernels::sumfac
