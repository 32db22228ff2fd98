#include "solvers/dense_least_squares.hpp"

#include <Eigen/Dense>

namespace amphora::solvers {

struct DenseLeastSquares::Impl {
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  long n = 0;
};

DenseLeastSquares::DenseLeastSquares(const CsrMatrix& A) : impl_(std::make_unique<Impl>()) {
  impl_->n = A.n;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(A.n, A.n);
  for (long i = 0; i < A.n; ++i)
    for (long e = A.row_ptr[i]; e < A.row_ptr[i + 1]; ++e) dense(i, A.cols[e]) += A.values[e];
  // Entries below 1e-12 of the largest pivot count as zero: the rank of a singular operator.
  impl_->cod.setThreshold(1e-12);
  impl_->cod.compute(dense);
}

DenseLeastSquares::~DenseLeastSquares() = default;

void DenseLeastSquares::solve(const double* b, double* x) const {
  const Eigen::Map<const Eigen::VectorXd> rhs(b, impl_->n);
  const Eigen::VectorXd sol = impl_->cod.solve(rhs);
  Eigen::Map<Eigen::VectorXd>(x, impl_->n) = sol;
}

long DenseLeastSquares::size() const { return impl_->n; }

}  // namespace amphora::solvers
