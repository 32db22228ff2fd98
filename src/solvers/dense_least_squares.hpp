#pragma once
// The minimum-norm least-squares solve of a small assembled matrix, dense (Eigen's complete
// orthogonal decomposition): the coarsest-level solve of a multigrid whose operator is
// non-symmetric and may be singular (the Oseen pressure, fixed up to a constant on periodic or
// closed boxes). Host only; O(n^3) to factor, so for a few thousand unknowns at most.
#include <memory>

#include "solvers/csr_matrix.hpp"

namespace amphora::solvers {

class DenseLeastSquares {
 public:
  explicit DenseLeastSquares(const CsrMatrix& A);
  ~DenseLeastSquares();
  DenseLeastSquares(const DenseLeastSquares&) = delete;
  DenseLeastSquares& operator=(const DenseLeastSquares&) = delete;
  /// x = A^+ b (host arrays of A.n entries; x may alias b).
  void solve(const double* b, double* x) const;
  long size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amphora::solvers
