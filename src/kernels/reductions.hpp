#pragma once
// Reductions beyond BLAS-1: extrema, and the search for the first non-finite entry that a run
// uses to stop cleanly and say where it diverged.
#include <Kokkos_Core.hpp>

#include "kernels/blas1.hpp"

namespace amphora::kernels::reduce {

template <class T>
struct MinMax {
  T min;
  T max;
};

/// Smallest and largest entry (undefined for an empty View).
template <class ExecSpace, class X>
MinMax<typename X::non_const_value_type> min_max(const ExecSpace& exec, const X& x) {
  using T = typename X::non_const_value_type;
  typename Kokkos::MinMax<T>::value_type r;
  Kokkos::parallel_reduce(
      "amphora::reduce::min_max", blas1::detail::range(exec, x),
      KOKKOS_LAMBDA(int i, typename Kokkos::MinMax<T>::value_type& acc) {
        if (x(i) < acc.min_val) acc.min_val = x(i);
        if (x(i) > acc.max_val) acc.max_val = x(i);
      },
      Kokkos::MinMax<T>(r));
  return {r.min_val, r.max_val};
}

/// Index of the first entry that is NaN or infinite, or -1 if all are finite. The smallest
/// such index is found whatever the thread count, so the message it feeds is reproducible.
template <class ExecSpace, class X>
int first_nonfinite(const ExecSpace& exec, const X& x) {
  const int none = static_cast<int>(x.extent(0));
  int first = none;
  Kokkos::parallel_reduce(
      "amphora::reduce::first_nonfinite", blas1::detail::range(exec, x),
      KOKKOS_LAMBDA(int i, int& acc) {
        if (!math::isfinite(x(i)) && i < acc) acc = i;
      },
      Kokkos::Min<int>(first));
  return first >= none ? -1 : first;
}

}  // namespace amphora::kernels::reduce
