#pragma once
// Modified incomplete Cholesky, MIC(0), of a symmetric CSR matrix: the classical preconditioner
// of fluid pressure solves (Gustafsson 1978; Bridson, Fluid Simulation for Computer Graphics,
// 2nd ed., sec. 5.3). M = (E + L) E^-1 (E + L^T) with L the strict lower triangle of A and
// E diagonal, chosen so that M keeps the row sums of A up to a fraction tau of the dropped fill:
//   e_i = a_ii - sum_{j<i} (a_ij / e_j) (a_ij + tau sum_{m>j, m!=i} a_jm),
// with e_i reset to a_ii where it falls below sigma a_ii. Host only and sequential by nature
// (the triangular solves): the baseline the multigrid is measured against.
#include <vector>

#include "solvers/csr_matrix.hpp"

namespace amphora::solvers {

class ModifiedIncompleteCholesky {
 public:
  explicit ModifiedIncompleteCholesky(const CsrMatrix& A, double tau = 0.97, double sigma = 0.25);
  /// z = M^-1 r (host arrays of n entries).
  void apply(const double* r, double* z) const;
  /// The preconditioner interface of conjugate_gradient (host Views).
  template <class ExecSpace, class R, class Z>
  void apply(const ExecSpace&, const R& r, const Z& z) const {
    apply(r.data(), z.data());
  }

 private:
  /// The strict lower and upper triangles of A, apart, so each triangular solve streams only
  /// its own half.
  struct Triangle {
    std::vector<int> row_ptr, cols;
    std::vector<double> values;
  };
  Triangle lower_, upper_;
  std::vector<double> inverse_e_;
};

/// y = A x, host, sequential: the operator of CG with MIC(0).
struct CsrOperator {
  const CsrMatrix* A;
  void apply(const double* x, double* y) const {
    for (long i = 0; i < A->n; ++i) {
      double s = 0.0;
      for (long e = A->row_ptr[i]; e < A->row_ptr[i + 1]; ++e) s += A->values[e] * x[A->cols[e]];
      y[i] = s;
    }
  }
  template <class ExecSpace, class X, class Y>
  void apply(const ExecSpace&, const X& x, const Y& y) const {
    apply(x.data(), y.data());
  }
};

}  // namespace amphora::solvers
