#pragma once
// The generic fallback of the matrix-free operators: mass and Laplace (scalar or blocked
// components) for any degree and number of quadrature points the compiled table lacks, by the
// same sum factorisation with run-time sizes, one cell at a time, geometry from the node
// coordinates (isoparametric, as GeometryMode::on_the_fly). Slower than the compiled kernels
// (no unrolling, no SIMD across cells) and meant for what they do not cover, e.g. a rule with
// degree + 3 points. Sizes up to n_p <= max_nodes_1d, n_q <= max_points_1d.
#include <Kokkos_Core.hpp>

#include "kernels/sumfac/point_geometry.hpp"
#include "kernels/sumfac/qk_lattice.hpp"
#include "solvers/matrix_free/cell_operator_kernel.hpp"

namespace amphora::solvers {

template <int dim, class ExecSpace>
struct GenericCellKernel {
  static constexpr int max_nodes_1d = 9, max_points_1d = 12;
  static constexpr int max_points = dim == 3 ? max_points_1d * max_points_1d * max_points_1d
                                             : max_points_1d * max_points_1d;
  using Mem = typename ExecSpace::memory_space;

  sumfac::QkLattice<dim> lattice;
  OperatorKind kind = OperatorKind::laplace;
  int n_p = 2, n_q = 2;
  Kokkos::View<const double*, Mem> values, derivatives;  // [q * n_p + i] at the points
  Kokkos::View<const double*, Mem> weights;              // n_q, sum 1 on [0, 1]
  Kokkos::View<const double*, Mem> coordinates;          // QkSpace::coordinates()

  /// out = M (or M^T) applied along direction d of the tensor `in` with extents ext (x
  /// fastest); M is n_q x n_p (row q); ext[d] goes from n_p to n_q (or back with transpose).
  KOKKOS_INLINE_FUNCTION void sweep(const double* M, bool transpose, int d, int* ext, const double* in,
                                    double* out) const {
    const int from = ext[d], to = transpose ? n_p : n_q;
    int before = 1, after = 1;
    for (int e = 0; e < d; ++e) before *= ext[e];
    for (int e = d + 1; e < dim; ++e) after *= ext[e];
    for (int a = 0; a < after; ++a)
      for (int r = 0; r < to; ++r)
        for (int b = 0; b < before; ++b) {
          double s = 0.0;
          for (int c = 0; c < from; ++c)
            s += (transpose ? M[c * n_p + r] : M[r * n_p + c]) * in[(a * from + c) * before + b];
          out[(a * to + r) * before + b] = s;
        }
    ext[d] = to;
  }

  /// The tensor of nodal values u mapped to the points, with the derivative matrix in
  /// direction `deriv` (-1: none), into out; tmp is scratch of max_points.
  KOKKOS_INLINE_FUNCTION void evaluate(const double* u, int deriv, double* out, double* tmp) const {
    int ext[3] = {n_p, n_p, n_p};
    const double* in = u;
    double* bufs[2] = {dim % 2 == 1 ? out : tmp, dim % 2 == 1 ? tmp : out};
    for (int d = 0; d < dim; ++d) {
      sweep(d == deriv ? derivatives.data() : values.data(), false, d, ext, in, bufs[d % 2]);
      in = bufs[d % 2];
    }
  }
  /// u += the transpose of evaluate() applied to v (v and tmp are overwritten).
  KOKKOS_INLINE_FUNCTION void integrate_add(double* v, int deriv, double* u, double* tmp) const {
    int ext[3] = {n_q, n_q, n_q};
    double* in = v;
    double* out = tmp;
    for (int d = 0; d < dim; ++d) {
      sweep(d == deriv ? derivatives.data() : values.data(), true, d, ext, in, out);
      double* t = in;
      in = out;
      out = t;
    }
    int nd = 1;
    for (int d = 0; d < dim; ++d) nd *= n_p;
    for (int i = 0; i < nd; ++i) u[i] += in[i];
  }

  /// y_cell = A_cell u_cell for cell c (lattice cell coordinates); X: the cell's node
  /// coordinates [d * n_dofs_cell + i]. Scratch s: scratch_size() doubles.
  KOKKOS_INLINE_FUNCTION void apply_cell(const double* X, const double* u, double* y, double* s) const {
    double* tmp = s;
    double* grad = s + max_points;             // dim blocks
    double* geo = grad + dim * max_points;     // dim * dim blocks: J[a][b] = d x_a / d xi_b
    int nq = 1, nd = 1;
    for (int d = 0; d < dim; ++d) nq *= n_q, nd *= n_p;
    for (int i = 0; i < nd; ++i) y[i] = 0.0;
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b) evaluate(X + a * nd, b, geo + (a * dim + b) * max_points, tmp);
    auto jacobian = [&](int q, double* J) {
      for (int e = 0; e < dim * dim; ++e) J[e] = geo[e * max_points + q];
    };
    if (kind == OperatorKind::mass) {
      evaluate(u, -1, grad, tmp);
      for (int q = 0; q < nq; ++q) {
        double J[dim * dim];
        jacobian(q, J);
        grad[q] *= point_weight(q) * sumfac::determinant<dim>(J);
      }
      integrate_add(grad, -1, y, tmp);
      return;
    }
    for (int b = 0; b < dim; ++b) evaluate(u, b, grad + b * max_points, tmp);
    for (int q = 0; q < nq; ++q) {
      // reference flux G grad_xi u, G = w det J J^-1 J^-T (point_geometry.hpp)
      double J[dim * dim], G[dim * (dim + 1) / 2], g[dim];
      jacobian(q, J);
      sumfac::laplace_metric<dim>(J, point_weight(q), G);
      for (int b = 0; b < dim; ++b) g[b] = grad[b * max_points + q];
      for (int a2 = 0; a2 < dim; ++a2) {
        double f = 0.0;
        for (int b = 0; b < dim; ++b) f += G[sumfac::sym_index<dim>(a2, b)] * g[b];
        grad[a2 * max_points + q] = f;
      }
    }
    for (int b = 0; b < dim; ++b) integrate_add(grad + b * max_points, b, y, tmp);
  }

  static constexpr int scratch_size() { return (1 + dim + dim * dim) * max_points; }

  KOKKOS_INLINE_FUNCTION double point_weight(int q) const {
    double w = 1.0;
    for (int d = 0; d < dim; ++d, q /= n_q) w *= weights(q % n_q);
    return w;
  }

  static constexpr int max_cell_dofs = dim == 3 ? max_nodes_1d * max_nodes_1d * max_nodes_1d
                                                : max_nodes_1d * max_nodes_1d;

  /// The cell's node coordinates into X [d * n_dofs_cell + i], its DoF numbers into dof (-1 where
  /// constrained); returns the number of nodes.
  KOKKOS_INLINE_FUNCTION int cell_setup(const int* c, double* X, long* dof) const {
    int nd = 1;
    for (int d = 0; d < dim; ++d) nd *= n_p;
    const long n_nodes = lattice.n_nodes();
    for (int i = 0; i < nd; ++i) {
      int node[3] = {0, 0, 0};
      cell_node(c, i, node);
      const long idx = lattice.node_index(node);
      for (int d = 0; d < dim; ++d) X[d * nd + i] = coordinates(d * n_nodes + idx);
      dof[i] = lattice.constrained(node) ? -1 : lattice.dof_index(node);
    }
    return nd;
  }

  /// Lattice node of local node i of the cell at cell coordinates c.
  KOKKOS_INLINE_FUNCTION void cell_node(const int* c, int i, int* node) const {
    for (int d = 0; d < dim; ++d, i /= n_p) node[d] = c[d] * lattice.degree + i % n_p;
  }
};

}  // namespace amphora::solvers
