#pragma once
// One-dimensional quadrature rules and Lagrange bases on [0, 1], the building blocks of the
// tensor-product (sum-factorised) operators. Host code: computed once at setup.
#include <vector>

namespace amphora::kernels::sumfac {

struct Quadrature1D {
  std::vector<double> points;   ///< ascending, in [0, 1], symmetric about 1/2
  std::vector<double> weights;  ///< sum to 1
};

/// n-point Gauss–Legendre rule, exact for degree 2n - 1 (Newton on P_n from Chebyshev guesses).
Quadrature1D gauss(int n);

/// n-point Gauss–Lobatto rule (n >= 2), end points included, exact for degree 2n - 3:
/// interior points are the roots of P'_{n-1}.
Quadrature1D gauss_lobatto(int n);

/// Values l_j(x_q) (row q, column j: matrix[q * nodes.size() + j]) of the Lagrange polynomials
/// on `nodes` at the points `x`.
std::vector<double> lagrange_values(const std::vector<double>& nodes, const std::vector<double>& x);

/// Derivatives l_j'(x_q), same layout.
std::vector<double> lagrange_derivatives(const std::vector<double>& nodes,
                                         const std::vector<double>& x);

}  // namespace amphora::kernels::sumfac
