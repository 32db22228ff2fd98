#pragma once
// A sparse Cholesky (LDL^T, Eigen's SimplicialLDLT with AMD ordering) of a small assembled SPD
// matrix: the exact coarsest-level solve of the MAC multigrid. Host only.
#include <memory>

#include "solvers/csr_matrix.hpp"

namespace amphora::solvers::mac {

class CoarseCholesky {
 public:
  /// Throws std::runtime_error if A is not positive definite (a fluid region that touches no
  /// free surface and no open boundary makes the pressure singular).
  explicit CoarseCholesky(const CsrMatrix& A);
  ~CoarseCholesky();
  CoarseCholesky(const CoarseCholesky&) = delete;
  CoarseCholesky& operator=(const CoarseCholesky&) = delete;
  /// x = A^-1 b (host arrays of A.n entries; x may alias b).
  void solve(const double* b, double* x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amphora::solvers::mac
