#pragma once
// A host CSR matrix: the assembled form handed to hypre (coarse grids, comparisons).
#include <vector>

namespace amphora::solvers {

struct CsrMatrix {
  long n = 0;
  std::vector<long> row_ptr;  ///< n + 1
  std::vector<int> cols;
  std::vector<double> values;
  long nnz() const { return static_cast<long>(values.size()); }
};

}  // namespace amphora::solvers
