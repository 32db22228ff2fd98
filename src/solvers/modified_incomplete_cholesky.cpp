#include "solvers/modified_incomplete_cholesky.hpp"

namespace amphora::solvers {

ModifiedIncompleteCholesky::ModifiedIncompleteCholesky(const CsrMatrix& A, double tau, double sigma)
    : A_(&A), inverse_e_(A.n) {
  // Sum of each row's strictly upper entries: then sum_{m>j, m!=i} a_jm = upper[j] - a_ji.
  std::vector<double> upper(A.n, 0.0), e(A.n);
  for (long j = 0; j < A.n; ++j)
    for (long k = A.row_ptr[j]; k < A.row_ptr[j + 1]; ++k)
      if (A.cols[k] > j) upper[j] += A.values[k];
  for (long i = 0; i < A.n; ++i) {
    double a_ii = 0.0, ei = 0.0;
    for (long k = A.row_ptr[i]; k < A.row_ptr[i + 1]; ++k) {
      const long j = A.cols[k];
      const double a = A.values[k];
      if (j == i) a_ii = a;
      if (j < i) ei -= a / e[j] * (a + tau * (upper[j] - a));
    }
    ei += a_ii;
    if (ei < sigma * a_ii) ei = a_ii;
    e[i] = ei;
    inverse_e_[i] = 1.0 / ei;
  }
}

void ModifiedIncompleteCholesky::apply(const double* r, double* z) const {
  const CsrMatrix& A = *A_;
  // (E + L) y = r, y in z
  for (long i = 0; i < A.n; ++i) {
    double s = r[i];
    for (long k = A.row_ptr[i]; k < A.row_ptr[i + 1]; ++k)
      if (A.cols[k] < i) s -= A.values[k] * z[A.cols[k]];
    z[i] = s * inverse_e_[i];
  }
  // (E + L^T) z = E y
  for (long i = A.n - 1; i >= 0; --i) {
    double s = 0.0;
    for (long k = A.row_ptr[i]; k < A.row_ptr[i + 1]; ++k)
      if (A.cols[k] > i) s += A.values[k] * z[A.cols[k]];
    z[i] -= s * inverse_e_[i];
  }
}

}  // namespace amphora::solvers
