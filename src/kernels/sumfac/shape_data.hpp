#pragma once
// The 1D matrices of a Q_k element (nodes: the k+1 Gauss–Lobatto points) with n_q quadrature
// points per direction, in even–odd form, plus the collocation derivative on the quadrature
// points: gradients are taken on the quadrature-point interpolant, exact for polynomials of
// degree n_q - 1 >= k (Kronbichler & Kormann 2019, sec. 3.3), which cuts the work of a
// gradient from dim (dim) to dim sweeps.
#include <vector>

#include "kernels/sumfac/even_odd_matrix.hpp"
#include "kernels/sumfac/quadrature_1d.hpp"

namespace amphora::kernels::sumfac {

enum class QuadratureKind { gauss, gauss_lobatto };

template <int n_p, int n_q>
struct ShapeData {
  EvenOddMatrix<n_q, n_p> values;      ///< l_j(x_q)
  EvenOddMatrix<n_p, n_q> values_t;    ///< its transpose (integration)
  EvenOddMatrix<n_q, n_q> derivative;  ///< d/dx of the Lagrange basis on the points, at the points
  EvenOddMatrix<n_q, n_q> derivative_t;
  /// Transposed products of basis values s and derivatives d at the points, entry-wise:
  /// s*s, s*d, d*d, and with second derivatives h: s*h, d*h. They integrate a point field
  /// against phi_i^2 and its derivative products, which gives an operator's diagonal in dim
  /// sweeps per term.
  EvenOddMatrix<n_p, n_q> ss_t, sd_t, dd_t, sh_t, dh_t;
  /// The quadrature's 1D mass and stiffness matrices, n_p x n_p: M_ij = sum_q w_q l_i l_j and
  /// K_ij = sum_q w_q l_i' l_j' at the points. A Cartesian cell's Laplacian is their Kronecker
  /// sum (TensorProductEvaluator::cartesian_laplace).
  EvenOddMatrix<n_p, n_p> mass, stiffness;
  double weights[n_q];
  double points[n_q];
  /// Quadrature points coincide with the nodes (n_q = n_p, Gauss–Lobatto): values are identity.
  bool collocated = false;

  static ShapeData create(QuadratureKind kind) {
    const std::vector<double> nodes = gauss_lobatto(n_p).points;
    const Quadrature1D q = kind == QuadratureKind::gauss ? gauss(n_q) : gauss_lobatto(n_q);
    ShapeData s{};
    s.values = EvenOddMatrix<n_q, n_p>::from_dense(lagrange_values(nodes, q.points), 1);
    s.values_t = EvenOddMatrix<n_p, n_q>::from_dense(
        transpose(lagrange_values(nodes, q.points), n_q, n_p), 1);
    {
      const std::vector<double> v = lagrange_values(nodes, q.points),
                                g = lagrange_derivatives(nodes, q.points),
                                dq = lagrange_derivatives(q.points, q.points);
      // second derivatives: the derivative on the points of the first (degree k - 1 < n_q: exact)
      std::vector<double> h(v.size(), 0.0);
      for (int p = 0; p < n_q; ++p)
        for (int r = 0; r < n_q; ++r)
          for (int i = 0; i < n_p; ++i) h[p * n_p + i] += dq[p * n_q + r] * g[r * n_p + i];
      std::vector<double> ss(v.size()), sd(v.size()), dd(v.size()), sh(v.size()), dh(v.size());
      for (std::size_t i = 0; i < v.size(); ++i) {
        ss[i] = v[i] * v[i], sd[i] = v[i] * g[i], dd[i] = g[i] * g[i];
        sh[i] = v[i] * h[i], dh[i] = g[i] * h[i];
      }
      s.ss_t = EvenOddMatrix<n_p, n_q>::from_dense(transpose(ss, n_q, n_p), 1);
      s.sd_t = EvenOddMatrix<n_p, n_q>::from_dense(transpose(sd, n_q, n_p), -1);
      s.dd_t = EvenOddMatrix<n_p, n_q>::from_dense(transpose(dd, n_q, n_p), 1);
      s.sh_t = EvenOddMatrix<n_p, n_q>::from_dense(transpose(sh, n_q, n_p), 1);
      s.dh_t = EvenOddMatrix<n_p, n_q>::from_dense(transpose(dh, n_q, n_p), -1);
      std::vector<double> m(n_p * n_p, 0.0), k(n_p * n_p, 0.0);
      for (int i = 0; i < n_p; ++i)
        for (int j = 0; j < n_p; ++j)
          for (int p = 0; p < n_q; ++p) {
            m[i * n_p + j] += q.weights[p] * v[p * n_p + i] * v[p * n_p + j];
            k[i * n_p + j] += q.weights[p] * g[p * n_p + i] * g[p * n_p + j];
          }
      s.mass = EvenOddMatrix<n_p, n_p>::from_dense(m, 1);
      s.stiffness = EvenOddMatrix<n_p, n_p>::from_dense(k, 1);
    }
    const std::vector<double> d = lagrange_derivatives(q.points, q.points);
    s.derivative = EvenOddMatrix<n_q, n_q>::from_dense(d, -1);
    s.derivative_t = EvenOddMatrix<n_q, n_q>::from_dense(transpose(d, n_q, n_q), -1);
    for (int i = 0; i < n_q; ++i) {
      s.weights[i] = q.weights[i];
      s.points[i] = q.points[i];
    }
    s.collocated = kind == QuadratureKind::gauss_lobatto && n_q == n_p;
    return s;
  }

  /// Interpolation from the Q_k nodes (k = n_p - 1) to the Gauss–Lobatto nodes of Q_{n_q - 1}
  /// in `values` (and its transpose): the 1D factor of p- and h-transfers. No derivatives.
  static ShapeData interpolation() {
    const std::vector<double> from = gauss_lobatto(n_p).points, to = gauss_lobatto(n_q).points;
    ShapeData s{};
    s.values = EvenOddMatrix<n_q, n_p>::from_dense(lagrange_values(from, to), 1);
    s.values_t =
        EvenOddMatrix<n_p, n_q>::from_dense(transpose(lagrange_values(from, to), n_q, n_p), 1);
    s.collocated = false;
    return s;
  }

 private:
  static std::vector<double> transpose(const std::vector<double>& m, int rows, int cols) {
    std::vector<double> t(m.size());
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) t[c * rows + r] = m[r * cols + c];
    return t;
  }
};

}  // namespace amphora::kernels::sumfac
