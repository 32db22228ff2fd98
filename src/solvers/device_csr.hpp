#pragma once
// An assembled CSR matrix in a memory space (solvers/csr_rows.hpp builds one), with y = A x as a
// kernel (one row per work item) and 1/diag(A) for Jacobi-type smoothers.
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
