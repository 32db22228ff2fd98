#pragma once
// An assembled CSR matrix in a memory space, with y = A x as a kernel (one row per work item)
// and 1/diag(A) for Jacobi-type smoothers.
#include <memory>
#include <type_traits>
#include <vector>

#include "kernels/host_vector.hpp"
#include "kernels/spaces.hpp"
#include "solvers/csr_matrix.hpp"

namespace amphora::solvers {

// Values stay double: float values (the tall-cell multigrid's matrices, tried three times) made
// the products no faster on the host (README, "Tried and not kept"): their bytes are not what
// limits them there.
template <class MemSpace>
struct DeviceCsrMatrix {
  using Vector = Kokkos::View<double*, MemSpace>;
  int n = 0;
  Kokkos::View<int*, MemSpace> row_ptr, cols;
  Vector values, inverse_diagonal;

  DeviceCsrMatrix() = default;
  /// A copy of A; with_inverse_diagonal: also 1 / a_ii (zero where a_ii is; a square matrix).
  explicit DeviceCsrMatrix(const CsrMatrix& A, bool with_inverse_diagonal = true)
      : n(static_cast<int>(A.n)) {
    copy(A, with_inverse_diagonal);
  }
  /// A itself, where MemSpace is the host's: its columns and values are kept and viewed,
  /// not copied (the multigrid's transfers are assembled every sub-step); elsewhere a copy.
  DeviceCsrMatrix(CsrMatrix&& A, bool with_inverse_diagonal) : n(static_cast<int>(A.n)) {
    // HostSpace itself, not any space the host can read: a managed (UVM) space would let GPU
    // kernels read the vector's pageable memory
    if constexpr (std::is_same_v<MemSpace, Kokkos::HostSpace>) {
      auto kept = std::make_shared<CsrMatrix>(std::move(A));
      cols = Kokkos::View<int*, MemSpace>(kept->cols.data(), kept->cols.size());
      values = Vector(kept->values.data(), kept->values.size());
      finish(*kept, with_inverse_diagonal);
      kept_ = std::move(kept);
    } else {
      copy(A, with_inverse_diagonal);
    }
  }

  template <class ExecSpace, class X, class Y>
  void apply(const ExecSpace& exec, const X& x, const Y& y) const {
    const auto rp = row_ptr;
    const auto c = cols;
    const auto v = values;
    Kokkos::parallel_for(
        "amphora::DeviceCsrMatrix::apply", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i) {
          double s = 0.0;
          for (int e = rp(i); e < rp(i + 1); ++e) s += v(e) * x(c(e));
          y(i) = s;
        });
  }

 private:
  void copy(const CsrMatrix& A, bool with_inverse_diagonal) {
    cols = kernels::to_view<MemSpace>(A.cols, "amphora::csr::cols");
    values = kernels::to_view<MemSpace>(A.values, "amphora::csr::values");
    finish(A, with_inverse_diagonal);
  }
  /// The row pointers (as int) and the inverse diagonal.
  /// Both filled on the host threads, a row each (set up every sub-step by the tall-cell
  /// multigrid, whose finest matrix has about 650k entries in the deep splash).
  void finish(const CsrMatrix& A, bool with_inverse_diagonal) {
    using HostPolicy = Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>;
    Kokkos::View<int*, Kokkos::HostSpace> rp(
        Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::csr::row_ptr"), A.row_ptr.size());
    Kokkos::parallel_for("amphora::csr::row_ptr", HostPolicy(0, rp.extent(0)),
                         [&](std::size_t i) { rp(i) = static_cast<int>(A.row_ptr[i]); });
    row_ptr = Kokkos::create_mirror_view_and_copy(MemSpace(), rp);
    if (!with_inverse_diagonal) return;
    Kokkos::View<double*, Kokkos::HostSpace> inv(
        Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::csr::inverse_diagonal"), A.n);
    Kokkos::parallel_for("amphora::csr::inverse_diagonal", HostPolicy(0, A.n), [&](long i) {
      double v = 0.0;
      for (long e = A.row_ptr[i]; e < A.row_ptr[i + 1]; ++e)
        if (A.cols[e] == i && A.values[e] != 0.0) v = 1.0 / A.values[e];
      inv(i) = v;
    });
    inverse_diagonal = Kokkos::create_mirror_view_and_copy(MemSpace(), inv);
  }
  std::shared_ptr<const CsrMatrix> kept_;  ///< the arrays cols and values view, if kept
};

/// r = b - A x for an assembled matrix.
template <class ExecSpace, class MemSpace, class B, class X, class R>
void residual_csr(const ExecSpace& exec, const DeviceCsrMatrix<MemSpace>& A, const B& b, const X& x,
                  const R& r) {
  const auto rp = A.row_ptr;
  const auto c = A.cols;
  const auto v = A.values;
  Kokkos::parallel_for(
      "amphora::residual_csr", kernels::RangePolicy<ExecSpace>(exec, 0, A.n), KOKKOS_LAMBDA(int i) {
        double s = b(i);
        for (int e = rp(i); e < rp(i + 1); ++e) s -= v(e) * x(c(e));
        r(i) = s;
      });
}

/// Gershgorin's bound of the eigenvalues of D^-1 A (as jacobi_gershgorin_bound) over the rows
/// of A, whose row i has its diagonal in column i, reduced on exec.
template <class ExecSpace, class MemSpace>
double jacobi_gershgorin_bound(const ExecSpace& exec, const DeviceCsrMatrix<MemSpace>& A) {
  const auto rp = A.row_ptr;
  const auto c = A.cols;
  const auto v = A.values;
  double bound = 0.0;
  Kokkos::parallel_reduce(
      "amphora::csr::gershgorin_bound_device", kernels::RangePolicy<ExecSpace>(exec, 0, A.n),
      KOKKOS_LAMBDA(int i, double& acc) {
        double diag = 0.0, off = 0.0;
        for (int e = rp(i); e < rp(i + 1); ++e)
          if (c(e) == i)
            diag = v(e);
          else
            off += v(e) < 0.0 ? -v(e) : v(e);
        if (diag > 0.0 && 1.0 + off / diag > acc) acc = 1.0 + off / diag;
      },
      Kokkos::Max<double>(bound));
  return bound > 0.0 ? bound : 0.0;  // no row with a positive diagonal: 0
}

/// A host copy of A (for the host's direct and hypre solvers).
template <class MemSpace>
CsrMatrix to_csr_matrix(const DeviceCsrMatrix<MemSpace>& A) {
  const auto rp = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), A.row_ptr);
  const auto c = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), A.cols);
  const auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), A.values);
  CsrMatrix M;
  M.n = A.n;
  M.row_ptr.resize(A.n + 1);
  for (long i = 0; i <= M.n; ++i) M.row_ptr[i] = rp(i);
  M.cols.assign(c.data(), c.data() + c.extent(0));
  M.values.assign(v.data(), v.data() + v.extent(0));
  return M;
}

}  // namespace amphora::solvers
