#pragma once
// A host accumulator for the rows of a sparse matrix (solvers/mac: the tall cells' rows of the
// tall-cell matrix), with global row numbers: a block keeps its own rows.
#include <algorithm>
#include <utility>
#include <vector>

#include "kernels/spaces.hpp"
#include "solvers/csr_matrix.hpp"

namespace amphora::solvers::mac {

/// Rows of a sparse matrix under assembly: up to K entries per row inline in flat arrays, the
/// rest of a longer row in a per-row overflow list; entries found by linear search. No
/// allocation per row (the tall-cell matrices and transfers are assembled every sub-step).
/// Rows come out with their columns sorted.
template <int K>
class RowAccumulator {
 public:
  /// Rows first .. first + n - 1 of the global matrix (the others are dropped).
  RowAccumulator(long n, long first)
      : first_(first), count_(n, 0), cols_(n * K), values_(n * K), overflow_(n) {}
  void add(long global_row, int c, double v) {
    const long r = global_row - first_;
    if (r < 0 || r >= static_cast<long>(count_.size())) return;  // another block's row
    int* cols = cols_.data() + static_cast<long>(r) * K;
    double* values = values_.data() + static_cast<long>(r) * K;
    const int m = count_[r];
    for (int e = 0; e < m; ++e)
      if (cols[e] == c) {
        values[e] += v;
        return;
      }
    if (m < K) {
      cols[m] = c;
      values[m] = v;
      count_[r] = m + 1;
      return;
    }
    for (auto& e : overflow_[r])
      if (e.first == c) {
        e.second += v;
        return;
      }
    overflow_[r].emplace_back(c, v);
  }
  CsrMatrix to_csr() const {
    const long n = static_cast<long>(count_.size());
    CsrMatrix M;
    M.n = n;
    M.row_ptr.resize(n + 1);
    M.row_ptr[0] = 0;
    for (long r = 0; r < n; ++r)
      M.row_ptr[r + 1] = M.row_ptr[r] + count_[r] + static_cast<long>(overflow_[r].size());
    M.cols.resize(M.row_ptr[n]);
    M.values.resize(M.row_ptr[n]);
    // each row alone (sorted in place): in parallel, the same for any number of threads
    Kokkos::parallel_for(
        "amphora::mac::rows_to_csr", Kokkos::RangePolicy<kernels::HostExecSpace>(0, n),
        [&](long r) {
          std::pair<int, double> inline_row[K];
          const int m = count_[r];
          for (int e = 0; e < m; ++e) inline_row[e] = {cols_[r * K + e], values_[r * K + e]};
          std::vector<std::pair<int, double>> long_row;  // only a row with overflow allocates
          std::pair<int, double>* row = inline_row;
          long length = m;
          if (!overflow_[r].empty()) {
            long_row.assign(inline_row, inline_row + m);
            long_row.insert(long_row.end(), overflow_[r].begin(), overflow_[r].end());
            row = long_row.data(), length = static_cast<long>(long_row.size());
          }
          std::sort(row, row + length);
          for (long e = 0; e < length; ++e)
            M.cols[M.row_ptr[r] + e] = row[e].first, M.values[M.row_ptr[r] + e] = row[e].second;
        });
    return M;
  }

 private:
  long first_ = 0;
  std::vector<int> count_;
  std::vector<int> cols_;
  std::vector<double> values_;
  std::vector<std::vector<std::pair<int, double>>> overflow_;
};

}  // namespace amphora::solvers::mac
