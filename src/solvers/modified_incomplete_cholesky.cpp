#include "solvers/modified_incomplete_cholesky.hpp"

namespace amphora::solvers {

ModifiedIncompleteCholesky::ModifiedIncompleteCholesky(const CsrMatrix& A, double tau, double sigma)
    : inverse_e_(A.n) {
  lower_.row_ptr.assign(1, 0);
  upper_.row_ptr.assign(1, 0);
  for (long i = 0; i < A.n; ++i) {
    for (long k = A.row_ptr[i]; k < A.row_ptr[i + 1]; ++k) {
      Triangle& t = A.cols[k] < i ? lower_ : upper_;
      if (A.cols[k] == i) continue;
      t.cols.push_back(A.cols[k]);
      t.values.push_back(A.values[k]);
    }
    lower_.row_ptr.push_back(static_cast<int>(lower_.cols.size()));
    upper_.row_ptr.push_back(static_cast<int>(upper_.cols.size()));
  }
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
  const long n = static_cast<long>(inverse_e_.size());
  // (E + L) y = r, y in z
  for (long i = 0; i < n; ++i) {
    double s = r[i];
    for (int k = lower_.row_ptr[i]; k < lower_.row_ptr[i + 1]; ++k)
      s -= lower_.values[k] * z[lower_.cols[k]];
    z[i] = s * inverse_e_[i];
  }
  // (E + L^T) z = E y
  for (long i = n - 1; i >= 0; --i) {
    double s = 0.0;
    for (int k = upper_.row_ptr[i]; k < upper_.row_ptr[i + 1]; ++k)
      s += upper_.values[k] * z[upper_.cols[k]];
    z[i] -= s * inverse_e_[i];
  }
}

}  // namespace amphora::solvers
