#pragma once
// A host CSR matrix: the assembled form handed to hypre (coarse grids, comparisons).
#include <algorithm>
#include <cmath>
#include <vector>

#include <Kokkos_Core.hpp>

namespace amphora::solvers {

struct CsrMatrix {
  long n = 0;
  std::vector<long> row_ptr;  ///< n + 1
  std::vector<int> cols;
  std::vector<double> values;
  long nnz() const { return static_cast<long>(values.size()); }
};

/// An upper bound of the eigenvalues of D^-1 A (D = diag A) by Gershgorin's theorem on its
/// rows: max_i (1 + sum_{j != i} |a_ij| / a_ii), over the rows with a positive diagonal. No
/// iterations, and every row alone: the same for any split of the rows (so the rows go to the
/// host threads). Row i's diagonal is in column first_column + i (a block's rows with global
/// columns).
inline double jacobi_gershgorin_bound(const CsrMatrix& A, long first_column = 0) {
  double bound = 0.0;
  Kokkos::parallel_reduce(
      "amphora::csr::gershgorin_bound", Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0, A.n),
      [&](long i, double& acc) {
        double diag = 0.0, off = 0.0;
        for (long e = A.row_ptr[i]; e < A.row_ptr[i + 1]; ++e)
          if (A.cols[e] == first_column + i) diag = A.values[e];
          else off += std::abs(A.values[e]);
        if (diag > 0.0) acc = std::max(acc, 1.0 + off / diag);
      },
      Kokkos::Max<double>(bound));
  return std::max(bound, 0.0);  // no row with a positive diagonal: 0, as before
}

}  // namespace amphora::solvers
