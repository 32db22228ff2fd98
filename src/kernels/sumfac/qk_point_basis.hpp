#pragma once
// The continuous Q_k basis at arbitrary points of a Cartesian box (the particles of CFD-DEM):
// the cell that holds a point, its reference coordinates, the k + 1 Lagrange values per
// direction and the DoFs they belong to (QkLattice's numbering, periodic wraps applied).
// Scattering a particle's share to the nodes and gathering a field at a particle both go
// through it. Plain data, copied into kernels by value.
#include "kernels/kokkos_compat.hpp"
#include "kernels/sumfac/qk_lattice.hpp"

namespace amphora::kernels::sumfac {

inline constexpr int max_point_basis_degree = 8;

template <int dim>
struct QkPointBasis {
  QkLattice<dim> lattice;
  double lower[3] = {0, 0, 0};
  double h[3] = {1, 1, 1};                        ///< cell size per direction
  double nodes[max_point_basis_degree + 1] = {};  ///< the 1D nodes on [0, 1]

  /// The cell of point x and its reference coordinates in [0, 1]: periodic directions wrap,
  /// others clamp to the box (a point on the upper face lies in the last cell).
  KOKKOS_INLINE_FUNCTION void locate(const double* x, int* cell, double* xi) const {
    for (int d = 0; d < dim; ++d) {
      const int n = lattice.cells[d];
      double s = (x[d] - lower[d]) / h[d];
      if (lattice.periodic[d]) s -= n * math::floor(s / n);
      int c = static_cast<int>(math::floor(s));
      c = c < 0 ? 0 : (c >= n ? n - 1 : c);
      const double r = s - c;
      cell[d] = c;
      xi[d] = r < 0 ? 0.0 : (r > 1 ? 1.0 : r);
    }
  }

  /// The k + 1 Lagrange polynomials of the nodes at xi.
  KOKKOS_INLINE_FUNCTION void values_1d(double xi, double* v) const {
    const int k = lattice.degree;
    for (int a = 0; a <= k; ++a) {
      double p = 1.0;
      for (int b = 0; b <= k; ++b) {
        if (b != a) p *= (xi - nodes[b]) / (nodes[a] - nodes[b]);
      }
      v[a] = p;
    }
  }

  /// The k + 1 Lagrange polynomials' derivatives d/dxi at xi.
  KOKKOS_INLINE_FUNCTION void derivatives_1d(double xi, double* v) const {
    const int k = lattice.degree;
    for (int a = 0; a <= k; ++a) {
      double s = 0.0;
      for (int m = 0; m <= k; ++m) {
        if (m == a) continue;
        double p = 1.0 / (nodes[a] - nodes[m]);
        for (int b = 0; b <= k; ++b) {
          if (b != a && b != m) p *= (xi - nodes[b]) / (nodes[a] - nodes[b]);
        }
        s += p;
      }
      v[a] = s;
    }
  }

  /// The k + 1 Lagrange polynomials' second derivatives d^2/dxi^2 at xi (each ordered pair of
  /// distinct factors differentiated once).
  KOKKOS_INLINE_FUNCTION void second_derivatives_1d(double xi, double* v) const {
    const int k = lattice.degree;
    for (int a = 0; a <= k; ++a) {
      double s = 0.0;
      for (int m = 0; m <= k; ++m) {
        if (m == a) continue;
        for (int n = 0; n <= k; ++n) {
          if (n == a || n == m) continue;
          double p = 1.0 / ((nodes[a] - nodes[m]) * (nodes[a] - nodes[n]));
          for (int b = 0; b <= k; ++b) {
            if (b != a && b != m && b != n) p *= (xi - nodes[b]) / (nodes[a] - nodes[b]);
          }
          s += p;
        }
      }
      v[a] = s;
    }
  }

  /// The DoF of local node (local[0], ..., local[dim - 1]) of cell `cell`.
  KOKKOS_INLINE_FUNCTION long dof(const int* cell, const int* local) const {
    long index = 0, stride = 1;
    for (int d = 0; d < dim; ++d) {
      int n = cell[d] * lattice.degree + local[d];
      if (n >= lattice.dofs[d]) n -= lattice.dofs[d];  // periodic: the last layer is the first
      index += n * stride;
      stride *= lattice.dofs[d];
    }
    return index;
  }

  /// Calls f(dof, value) for each of the (k + 1)^dim basis functions of x's cell at x.
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each(const double* x, const F& f) const {
    int cell[3] = {0, 0, 0};
    double xi[3] = {0, 0, 0};
    locate(x, cell, xi);
    double v[3][max_point_basis_degree + 1];
    for (int d = 0; d < dim; ++d) values_1d(xi[d], v[d]);
    const int k1 = lattice.degree + 1;
    int n_local = 1;
    for (int d = 0; d < dim; ++d) n_local *= k1;
    for (int l = 0; l < n_local; ++l) {
      int local[3] = {0, 0, 0}, rest = l;
      double value = 1.0;
      for (int d = 0; d < dim; ++d) {
        local[d] = rest % k1;
        rest /= k1;
        value *= v[d][local[d]];
      }
      f(dof(cell, local), value);
    }
  }

  /// Calls f(dof, grad) for each basis function of x's cell, grad its physical gradient at x.
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_gradient(const double* x, const F& f) const {
    for_each_with_derivatives<1>(x, [&](long j, const int* local, const Table& v, const Table& dv) {
      double grad[3] = {0, 0, 0};
      for (int a = 0; a < dim; ++a) grad[a] = along(a, local, v, dv, h[a]);
      f(j, grad);
    });
  }

  /// Calls f(dof, laplacian) for each basis function of x's cell, its physical Laplacian at x
  /// (zero for Q1: each cell's functions are linear in every direction).
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_laplacian(const double* x, const F& f) const {
    for_each_with_derivatives<2>(x,
                                 [&](long j, const int* local, const Table& v, const Table& d2v) {
                                   double lap = 0.0;
                                   for (int a = 0; a < dim; ++a)
                                     lap += along(a, local, v, d2v, h[a] * h[a]);
                                   f(j, lap);
                                 });
  }

 private:
  using Table = double[3][max_point_basis_degree + 1];  ///< 1D tables per direction

  /// The tensor-product function `local` differentiated along a only, over `scale` (the
  /// cell's size to the derivative's order): d[a] / scale times the others' values.
  KOKKOS_INLINE_FUNCTION double along(int a, const int* local, const Table& v, const Table& d,
                                      double scale) const {
    double g = d[a][local[a]] / scale;
    for (int e = 0; e < dim; ++e) {
      if (e != a) g *= v[e][local[e]];
    }
    return g;
  }

  /// Calls f(dof, local, values, derivatives) for each basis function of x's cell, with the
  /// 1D values and the 1D derivatives of the given order (1 or 2) at x.
  template <int order, class F>
  KOKKOS_INLINE_FUNCTION void for_each_with_derivatives(const double* x, const F& f) const {
    int cell[3] = {0, 0, 0};
    double xi[3] = {0, 0, 0};
    locate(x, cell, xi);
    Table v, d;
    for (int e = 0; e < dim; ++e) {
      values_1d(xi[e], v[e]);
      if constexpr (order == 1) {
        derivatives_1d(xi[e], d[e]);
      } else {
        second_derivatives_1d(xi[e], d[e]);
      }
    }
    const int k1 = lattice.degree + 1;
    int n_local = 1;
    for (int e = 0; e < dim; ++e) n_local *= k1;
    for (int l = 0; l < n_local; ++l) {
      int local[3] = {0, 0, 0}, rest = l;
      for (int e = 0; e < dim; ++e) {
        local[e] = rest % k1;
        rest /= k1;
      }
      f(dof(cell, local), local, v, d);
    }
  }
};

}  // namespace amphora::kernels::sumfac
