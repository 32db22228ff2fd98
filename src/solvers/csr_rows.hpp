#pragma once
// A CSR matrix assembled row by row from a row functor, in ExecSpace's memory: on a device each
// row is counted, then written (the functor runs twice per row); on host threads groups of
// consecutive rows are written once into buffers of their own and then placed, which saves the
// second run where a row costs more than its copy.
#include <algorithm>
#include <string>
#include <vector>

#include "kernels/kokkos_compat.hpp"
#include "kernels/spaces.hpp"
#include "solvers/device_csr.hpp"

namespace amphora::solvers {

namespace detail {
/// Sorts entries [from, to) of a CSR row by column (insertion sort: rows are short).
template <class Cols, class Values>
KOKKOS_INLINE_FUNCTION void sort_csr_row(const Cols& cols, const Values& values, int from, int to) {
  for (int e = from + 1; e < to; ++e)
    for (int s = e; s > from && cols(s - 1) > cols(s); --s) {
      const int c = cols(s);
      const double v = values(s);
      cols(s) = cols(s - 1), values(s) = values(s - 1);
      cols(s - 1) = c, values(s - 1) = v;
    }
}
/// row_ptr(r) = the entries of the rows before r, from row_ptr(r + 1) = row r's and row_ptr(0)
/// = 0; returns the entries of all.
template <class ExecSpace, class Mem>
int scan_row_lengths(const ExecSpace& exec, const Kokkos::View<int*, Mem>& row_ptr,
                     const std::string& label) {
  int entries = 0;
  Kokkos::parallel_scan(
      label + "::scan",
      kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(row_ptr.extent(0))),
      KOKKOS_LAMBDA(int r, int& partial, bool final) {
        partial += row_ptr(r);
        if (final) row_ptr(r) = partial;
      },
      entries);
  return entries;
}

/// Columns and values for `entries` entries, uninitialised.
template <class Mem>
void allocate_entries(Kokkos::View<int*, Mem>& cols, Kokkos::View<double*, Mem>& values,
                      int entries, const std::string& label) {
  cols = Kokkos::View<int*, Mem>(Kokkos::view_alloc(Kokkos::WithoutInitializing, label + "::cols"),
                                 entries);
  values = Kokkos::View<double*, Mem>(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, label + "::values"), entries);
}

template <class ExecSpace>
DeviceCsrMatrix<typename ExecSpace::memory_space> csr_rows_start(int rows,
                                                                 const std::string& label) {
  DeviceCsrMatrix<typename ExecSpace::memory_space> M;
  M.n = rows;
  M.row_ptr = Kokkos::View<int*, typename ExecSpace::memory_space>(label + "::row_ptr", rows + 1);
  return M;
}

/// The device's schedule: each row counted, then written.
template <class ExecSpace, class Row>
DeviceCsrMatrix<typename ExecSpace::memory_space> csr_rows_counted(const ExecSpace& exec, int rows,
                                                                   const Row& row,
                                                                   const std::string& label) {
  using Mem = typename ExecSpace::memory_space;
  using Policy = kernels::RangePolicy<ExecSpace>;
  DeviceCsrMatrix<Mem> M = csr_rows_start<ExecSpace>(rows, label);
  const auto row_ptr = M.row_ptr;
  Kokkos::parallel_for(
      label + "::lengths", Policy(exec, 0, rows), KOKKOS_LAMBDA(int r) {
        int n = 0;
        row(r, [&](int, double) { ++n; });
        row_ptr(r + 1) = n;
      });
  allocate_entries(M.cols, M.values, scan_row_lengths(exec, row_ptr, label), label);
  const auto cols = M.cols;
  const auto values = M.values;
  Kokkos::parallel_for(
      label + "::rows", Policy(exec, 0, rows), KOKKOS_LAMBDA(int r) {
        int at = row_ptr(r);
        const bool sort = row(r, [&](int c, double v) { cols(at) = c, values(at++) = v; });
        if (sort) detail::sort_csr_row(cols, values, row_ptr(r), at);
      });
  return M;
}

/// The host threads' schedule: groups of consecutive rows written once into their own buffers.
template <class ExecSpace, class Row>
DeviceCsrMatrix<typename ExecSpace::memory_space> csr_rows_grouped(const ExecSpace& exec, int rows,
                                                                   const Row& row,
                                                                   const std::string& label) {
  using Mem = typename ExecSpace::memory_space;
  DeviceCsrMatrix<Mem> M = csr_rows_start<ExecSpace>(rows, label);
  const auto row_ptr = M.row_ptr;
  // groups of consecutive rows, several per thread for balance, each into its own buffers
  const int groups = std::max(1, std::min(rows, 8 * exec.concurrency()));
  const auto first_row = [=](int q) { return int(long(q) * rows / groups); };
  std::vector<std::vector<int>> group_cols(groups);
  std::vector<std::vector<double>> group_values(groups);
  Kokkos::parallel_for(
      label + "::rows", Kokkos::RangePolicy<ExecSpace>(exec, 0, groups), [&](int q) {
        std::vector<int>& c = group_cols[q];
        std::vector<double>& v = group_values[q];
        c.reserve(8 * std::size_t(first_row(q + 1) - first_row(q)));
        v.reserve(c.capacity());
        const auto push = [&](int column, double value) {
          c.push_back(column), v.push_back(value);
        };
        const kernels::AnySpaceCall<decltype(push)> emit{push};
        for (int r = first_row(q); r < first_row(q + 1); ++r) {
          const std::size_t from = c.size();
          const bool sort = row(r, emit);
          row_ptr(r + 1) = static_cast<int>(c.size() - from);
          if (!sort) continue;
          using Unmanaged = Kokkos::MemoryTraits<Kokkos::Unmanaged>;
          sort_csr_row(Kokkos::View<int*, Kokkos::HostSpace, Unmanaged>(c.data(), c.size()),
                       Kokkos::View<double*, Kokkos::HostSpace, Unmanaged>(v.data(), v.size()),
                       int(from), int(c.size()));
        }
      });
  allocate_entries(M.cols, M.values, scan_row_lengths(exec, row_ptr, label), label);
  const auto cols = M.cols;
  const auto values = M.values;
  Kokkos::parallel_for(
      label + "::place", Kokkos::RangePolicy<ExecSpace>(exec, 0, groups), [&](int q) {
        const int at = row_ptr(first_row(q));
        std::copy(group_cols[q].begin(), group_cols[q].end(), cols.data() + at);
        std::copy(group_values[q].begin(), group_values[q].end(), values.data() + at);
      });
  return M;
}
}  // namespace detail

/// The matrix of `rows` rows whose row r is row(r, emit): emit(column, value) once per entry, and
/// the return value whether the entries need sorting by column (else their order is kept). The
/// same matrix on every backend and for any number of threads. No inverse diagonal.
/// `counted`: the device's schedule (count, then write) on host threads too (tests).
template <class ExecSpace, class Row>
DeviceCsrMatrix<typename ExecSpace::memory_space> assemble_csr_rows(
    const ExecSpace& exec, int rows, const Row& row, const std::string& label,
    bool counted = !kernels::runs_on_host_v<ExecSpace>) {
  if constexpr (kernels::runs_on_host_v<ExecSpace>) {
    if (!counted) return detail::csr_rows_grouped(exec, rows, row, label);
  }
  return detail::csr_rows_counted(exec, rows, row, label);
}

}  // namespace amphora::solvers
