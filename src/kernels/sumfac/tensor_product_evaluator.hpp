#pragma once
// Evaluation at quadrature points and integration back, for one cell batch of a Q_k element
// in dim = 2 or 3, as sequences of 1D sweeps (sum factorisation; Orszag 1980). Evaluation and
// integration are separate steps, as in deal.II's FEEvaluation, so an operator is
// "evaluate, apply the point-wise physics, integrate". Arrays are lexicographic with x fastest.
#include "kernels/sumfac/shape_data.hpp"

namespace amphora::kernels::sumfac {

KOKKOS_INLINE_FUNCTION constexpr int ipow(int b, int e) { return e == 0 ? 1 : b * ipow(b, e - 1); }

template <int dim, int n_p, int n_q>
struct TensorProductEvaluator {
  static_assert(dim == 2 || dim == 3, "dim must be 2 or 3");
  static constexpr int n_dofs = ipow(n_p, dim);
  static constexpr int n_points = ipow(n_q, dim);
  /// Whether values() and integrate_values() run their square 3D sweeps in place (a line is
  /// read whole before it is written; the same numbers): from n_q = 6 on, where three point
  /// arrays of a W = 8 batch outgrow a 48 KB L1 (at n_q = 3 in place measured no faster,
  /// possibly slower: LaplaceDealii/2, 2 threads, 3 noisy rounds).
  static constexpr bool in_place = dim == 3 && n_p == n_q && n_q >= 6;
  /// Scratch needed by values() and integrate_values().
  static constexpr int n_scratch = ipow(n_q, dim - 1) * (n_p > n_q ? n_p : n_q);

  /// v = values of u at the points; v needs n_points, tmp n_scratch. u and v distinct, or the
  /// same array when in_place (then tmp is not used).
  template <class T>
  KOKKOS_FORCEINLINE_FUNCTION static void values(const ShapeData<n_p, n_q>& s, const T* u, T* v,
                                                 T* tmp) {
    if constexpr (n_p == n_q) {
      if (s.collocated) {
        if (v != u)
          for (int i = 0; i < n_points; ++i) v[i] = u[i];
        return;
      }
    }
    if constexpr (dim == 2) {
      apply_even_odd<n_q, n_p, 1, n_p, false, 1>(s.values, u, tmp);
      apply_even_odd<n_q, n_p, n_q, 1, false, 1>(s.values, tmp, v);
    } else if constexpr (in_place) {
      apply_even_odd<n_q, n_p, 1, n_p * n_p, false, 1>(s.values, u, v);
      apply_even_odd<n_q, n_p, n_q, n_p, false, 1>(s.values, v, v);
      apply_even_odd<n_q, n_p, n_q * n_q, 1, false, 1>(s.values, v, v);
    } else {
      apply_even_odd<n_q, n_p, 1, n_p * n_p, false, 1>(s.values, u, v);
      apply_even_odd<n_q, n_p, n_q, n_p, false, 1>(s.values, v, tmp);
      apply_even_odd<n_q, n_p, n_q * n_q, 1, false, 1>(s.values, tmp, v);
    }
  }

  /// u = integral of v against the basis (transpose of values()); v is overwritten.
  template <class T>
  KOKKOS_FORCEINLINE_FUNCTION static void integrate_values(const ShapeData<n_p, n_q>& s, T* v, T* u,
                                                           T* tmp) {
    if constexpr (n_p == n_q) {
      if (s.collocated) {
        for (int i = 0; i < n_dofs; ++i) u[i] = v[i];
        return;
      }
    }
    if constexpr (dim == 2) {
      apply_even_odd<n_p, n_q, n_q, 1, false, 1>(s.values_t, v, tmp);
      apply_even_odd<n_p, n_q, 1, n_p, false, 1>(s.values_t, tmp, u);
    } else if constexpr (in_place) {
      apply_even_odd<n_p, n_q, n_q * n_q, 1, false, 1>(s.values_t, v, v);
      apply_even_odd<n_p, n_q, n_q, n_p, false, 1>(s.values_t, v, v);
      apply_even_odd<n_p, n_q, 1, n_p * n_p, false, 1>(s.values_t, v, u);
    } else {
      apply_even_odd<n_p, n_q, n_q * n_q, 1, false, 1>(s.values_t, v, tmp);
      apply_even_odd<n_p, n_q, n_q, n_p, false, 1>(s.values_t, tmp, v);
      apply_even_odd<n_p, n_q, 1, n_p * n_p, false, 1>(s.values_t, v, u);
    }
  }

  /// u (+)= integral of v with a different 1D matrix per direction (m[d], each n_p x n_q);
  /// v is overwritten.
  template <bool add, class T>
  KOKKOS_FORCEINLINE_FUNCTION static void integrate_tensor(const EvenOddMatrix<n_p, n_q>* const* m,
                                                           T* v, T* u, T* tmp) {
    if constexpr (dim == 2) {
      apply_even_odd<n_p, n_q, n_q, 1, false>(*m[1], v, tmp);
      apply_even_odd<n_p, n_q, 1, n_p, add>(*m[0], tmp, u);
    } else {
      apply_even_odd<n_p, n_q, n_q * n_q, 1, false>(*m[2], v, tmp);
      apply_even_odd<n_p, n_q, n_q, n_p, false>(*m[1], tmp, v);
      apply_even_odd<n_p, n_q, 1, n_p * n_p, add>(*m[0], v, u);
    }
  }

  /// grad[d * n_points + q] = d v / d xi_d at the points (reference coordinates).
  template <class T>
  KOKKOS_FORCEINLINE_FUNCTION static void gradients(const ShapeData<n_p, n_q>& s, const T* v,
                                                    T* grad) {
    apply_even_odd<n_q, n_q, 1, ipow(n_q, dim - 1), false, -1>(s.derivative, v, grad);
    apply_even_odd<n_q, n_q, n_q, ipow(n_q, dim - 2), false, -1>(s.derivative, v, grad + n_points);
    if constexpr (dim == 3)
      apply_even_odd<n_q, n_q, n_q * n_q, 1, false, -1>(s.derivative, v, grad + 2 * n_points);
  }

  /// v = sum_d D_d^T flux_d (transpose of gradients()); with `add`, v += ... .
  template <bool add, class T>
  KOKKOS_FORCEINLINE_FUNCTION static void integrate_gradients(const ShapeData<n_p, n_q>& s,
                                                              const T* flux, T* v) {
    apply_even_odd<n_q, n_q, 1, ipow(n_q, dim - 1), add, -1>(s.derivative_t, flux, v);
    apply_even_odd<n_q, n_q, n_q, ipow(n_q, dim - 2), true, -1>(s.derivative_t, flux + n_points, v);
    if constexpr (dim == 3)
      apply_even_odd<n_q, n_q, n_q * n_q, 1, true, -1>(s.derivative_t, flux + 2 * n_points, v);
  }

  /// u <- A u for the Laplacian of a Cartesian cell with metric diag(c):
  ///   A = c_0 M (x) M (x) K + c_1 M (x) K (x) M + c_2 K (x) M (x) M   (z (x) y (x) x)
  /// with the quadrature's 1D mass and stiffness matrices (ShapeData::mass, stiffness). The
  /// tensor quadrature factors into 1D sums, so A is the operator of values(), the point-wise
  /// metric and their transposes (up to round-off), applied in 2 + 3 + 2 sweeps of n_p x n_p
  /// instead of 12 through the points (4 instead of 8 in 2D). Planes of u along z are consumed
  /// one at a time into two arrays, which the z sweeps combine into u. tmp: n_dofs.
  template <class T>
  KOKKOS_FORCEINLINE_FUNCTION static void cartesian_laplace(const ShapeData<n_p, n_q>& s,
                                                            const T* c, T* u, T* tmp) {
    constexpr int nn = n_p * n_p;
    if constexpr (dim == 2) {
      T a[nn], b[nn];
      apply_even_odd<n_p, n_p, 1, n_p, false, 1>(s.mass, u, a);  // along x
      apply_even_odd<n_p, n_p, 1, n_p, false, 1>(s.stiffness, u, b);
      for (int i = 0; i < nn; ++i) {
        b[i] *= c[0];
        a[i] *= c[1];
      }
      apply_even_odd<n_p, n_p, n_p, 1, false, 1>(s.mass, b, u);  // along y
      apply_even_odd<n_p, n_p, n_p, 1, true, 1>(s.stiffness, a, u);
    } else {
      // Plane k of u is read whole before plane k of mm is written: mm takes u's place, so
      // the working set is 2 n_dofs (2 x 22 KB at n_p = 7, W = 8) and two planes. Sweeps of
      // M and K over the same lines share the lines' even and odd parts.
      T* const mm = u;    // c_2 M_y M_x u
      T* const mk = tmp;  // c_0 M_y K_x u + c_1 K_y M_x u
      const T one(1.0);
      for (int k = 0; k < n_p; ++k) {
        T a[nn], b[nn];
        for (int j = 0; j < n_p; ++j)  // along x: a = M_x u, b = c_0 K_x u
          apply_even_odd_pair_line<n_p, 1, 1, false>(s.mass, s.stiffness, u + k * nn + j * n_p,
                                                     a + j * n_p, b + j * n_p, one, c[0]);
        apply_even_odd<n_p, n_p, n_p, 1, false, 1>(s.mass, b, mk + k * nn);  // along y
        for (int i = 0; i < n_p; ++i)
          apply_even_odd_pair_line<n_p, n_p, n_p, true>(s.mass, s.stiffness, a + i, mm + k * nn + i,
                                                        mk + k * nn + i, c[2], c[1]);
      }
      for (int i = 0; i < nn; ++i)  // along z, in place
        apply_even_odd_sum_line<n_p, nn>(s.stiffness, mm + i, s.mass, mk + i, u + i);
    }
  }

  /// u <- A u for the Laplacian of a Cartesian cell whose quadrature points are its nodes
  /// (Gauss–Lobatto, n_q = n_p): the 1D mass is then diagonal, M = diag(w), and
  ///   A = c_0 W (x) W (x) K + c_1 W (x) K (x) W + c_2 K (x) W (x) W
  /// is one sweep of K per direction, each line scaled by the other directions' weights:
  /// 3 sweeps where the path through the points takes 6 (2 and 4 in 2D). The x and y sweeps
  /// of a plane go into tmp (n_dofs); the z sweep adds them into u in place.
  template <class T>
  KOKKOS_FORCEINLINE_FUNCTION static void collocated_cartesian_laplace(const ShapeData<n_p, n_q>& s,
                                                                       const T* c, T* u, T* tmp) {
    static_assert(n_p == n_q, "collocation needs the points to be the nodes");
    const double* w = s.weights;
    if constexpr (dim == 2) {
      for (int j = 0; j < n_p; ++j)  // along x
        scaled_stiffness_line<1, 1, false>(s, u + j * n_p, c[0] * T(w[j]), tmp + j * n_p);
      for (int i = 0; i < n_p; ++i)  // along y, in place
        scaled_stiffness_line<n_p, n_p, true>(s, u + i, c[1] * T(w[i]), u + i, tmp + i);
    } else {
      constexpr int nn = n_p * n_p;
      for (int k = 0; k < n_p; ++k) {
        T* const t = tmp + k * nn;
        for (int j = 0; j < n_p; ++j)  // along x
          scaled_stiffness_line<1, 1, false>(s, u + k * nn + j * n_p, c[0] * T(w[j] * w[k]),
                                             t + j * n_p);
        for (int i = 0; i < n_p; ++i)  // along y
          scaled_stiffness_line<n_p, n_p, true>(s, u + k * nn + i, c[1] * T(w[i] * w[k]), t + i,
                                                t + i);
      }
      for (int j = 0; j < n_p; ++j)  // along z, in place
        for (int i = 0; i < n_p; ++i)
          scaled_stiffness_line<nn, nn, true>(s, u + j * n_p + i, c[2] * T(w[i] * w[j]),
                                              u + j * n_p + i, tmp + j * n_p + i);
    }
  }
  /// One line: y = scale (K x), with `add` y = base + scale (K x). x is read whole before y
  /// is written, so y may be x or base.
  template <int xs, int ys, bool add, class T>
  KOKKOS_FORCEINLINE_FUNCTION static void scaled_stiffness_line(const ShapeData<n_p, n_q>& s,
                                                                const T* x, const T& scale, T* y,
                                                                const T* base = nullptr) {
    T g[n_p];
    apply_even_odd_line<n_p, n_p, xs, 1, false, 1>(s.stiffness, x, g);
    for (int o = 0; o < n_p; ++o) y[o * ys] = add ? base[o * ys] + scale * g[o] : scale * g[o];
  }

  /// u <- c M (x) M (x) M u: the mass matrix of a cell with a constant Jacobian determinant c
  /// (Cartesian and affine cells) from the quadrature's 1D mass (ShapeData::mass; the tensor
  /// quadrature factors), in dim in-place sweeps of n_p x n_p where the path through the
  /// points takes 2 dim of n_p x n_q.
  template <class T>
  KOKKOS_FORCEINLINE_FUNCTION static void per_cell_mass(const ShapeData<n_p, n_q>& s, const T& c,
                                                        T* u) {
    if constexpr (dim == 2) {
      apply_even_odd<n_p, n_p, 1, n_p, false, 1>(s.mass, u, u);
      apply_even_odd<n_p, n_p, n_p, 1, false, 1>(s.mass, u, u);
    } else {
      apply_even_odd<n_p, n_p, 1, n_p * n_p, false, 1>(s.mass, u, u);
      apply_even_odd<n_p, n_p, n_p, n_p, false, 1>(s.mass, u, u);
      apply_even_odd<n_p, n_p, n_p * n_p, 1, false, 1>(s.mass, u, u);
    }
    for (int i = 0; i < n_dofs; ++i) u[i] *= c;
  }

  /// f(q, weight(q)) for every point q in order, without weight()'s divisions (the same
  /// products in the same order, so the same numbers).
  template <class F>
  KOKKOS_FORCEINLINE_FUNCTION static void for_each_weighted_point(const ShapeData<n_p, n_q>& s,
                                                                  const F& f) {
    constexpr int n_outer = dim == 3 ? n_q : 1;
    for (int k = 0; k < n_outer; ++k)
      for (int j = 0; j < n_q; ++j)
        for (int i = 0; i < n_q; ++i) f((k * n_q + j) * n_q + i, weight(s, i, j, k));
  }

  /// Tensor weight w_i w_j (w_k) of point (i, j, k) (k ignored in 2D).
  KOKKOS_FORCEINLINE_FUNCTION static double weight(const ShapeData<n_p, n_q>& s, int i, int j,
                                                   int k) {
    double w = s.weights[i] * s.weights[j];
    if constexpr (dim == 3) w *= s.weights[k];
    return w;
  }
  /// Tensor weight of point q.
  KOKKOS_FORCEINLINE_FUNCTION static double weight(const ShapeData<n_p, n_q>& s, int q) {
    return weight(s, q % n_q, (q / n_q) % n_q, dim == 3 ? q / (n_q * n_q) : 0);
  }
};

}  // namespace amphora::kernels::sumfac
