#pragma once
// A host CSR matrix: the assembled form handed to hypre (coarse grids, comparisons).
#include <algorithm>
#include <cmath>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include <Kokkos_Core.hpp>

namespace amphora::solvers {

/// std::allocator, except that a vector's resize leaves new elements default-initialised (a
/// number: unset) rather than zeroed. The CSR arrays are sized and then written entry by entry,
/// on the host threads; zeroed first, on one thread, they cost the tall-cell multigrid's set-up
/// of a deep pool tens of MB of writes per sub-step for nothing.
template <class T>
struct uninitialised_allocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = uninitialised_allocator<U>;
  };
  uninitialised_allocator() = default;
  template <class U>
  uninitialised_allocator(const uninitialised_allocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using csr_vector = std::vector<T, uninitialised_allocator<T>>;

struct CsrMatrix {
  long n = 0;
  csr_vector<long> row_ptr;  ///< n + 1
  csr_vector<int> cols;
  csr_vector<double> values;
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
      "amphora::csr::gershgorin_bound",
      Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0, A.n),
      [&](long i, double& acc) {
        double diag = 0.0, off = 0.0;
        for (long e = A.row_ptr[i]; e < A.row_ptr[i + 1]; ++e)
          if (A.cols[e] == first_column + i)
            diag = A.values[e];
          else
            off += std::abs(A.values[e]);
        if (diag > 0.0) acc = std::max(acc, 1.0 + off / diag);
      },
      Kokkos::Max<double>(bound));
  return std::max(bound, 0.0);  // no row with a positive diagonal: 0, as before
}

}  // namespace amphora::solvers
