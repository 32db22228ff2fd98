#include "solvers/mac/coarse_cholesky.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <stdexcept>
#include <vector>

namespace amphora::solvers::mac {

struct CoarseCholesky::Impl {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  long n = 0;
};

CoarseCholesky::CoarseCholesky(const CsrMatrix& A) : impl_(std::make_unique<Impl>()) {
  impl_->n = A.n;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(A.values.size());
  for (long i = 0; i < A.n; ++i)
    for (long e = A.row_ptr[i]; e < A.row_ptr[i + 1]; ++e)
      entries.emplace_back(i, A.cols[e], A.values[e]);
  Eigen::SparseMatrix<double> M(A.n, A.n);
  M.setFromTriplets(entries.begin(), entries.end());
  impl_->ldlt.compute(M);
  bool positive = impl_->ldlt.info() == Eigen::Success;
  if (positive) positive = (impl_->ldlt.vectorD().array() > 0.0).all();
  if (!positive)
    throw std::runtime_error(
        "pressure matrix is singular on the coarsest multigrid level: some fluid region touches "
        "neither a free surface nor an open boundary, so its pressure is defined only up to a "
        "constant");
}

CoarseCholesky::~CoarseCholesky() = default;

void CoarseCholesky::solve(const double* b, double* x) const {
  Eigen::Map<const Eigen::VectorXd> bv(b, impl_->n);
  Eigen::VectorXd xv = impl_->ldlt.solve(bv);
  Eigen::Map<Eigen::VectorXd>(x, impl_->n) = xv;
}

}  // namespace amphora::solvers::mac
