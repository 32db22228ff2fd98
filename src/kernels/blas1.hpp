#pragma once
// BLAS-1 kernels on rank-local 1D Views, templated on the execution space (passed first).
// Reductions use Kokkos' built-in reducers: their order depends on the thread count, so
// results agree across thread counts to round-off, and are bitwise repeatable for a fixed one.
#include "kernels/spaces.hpp"

namespace amphora::blas1 {

namespace detail {
template <class ExecSpace, class View>
RangePolicy<ExecSpace> range(const ExecSpace& exec, const View& x) {
  static_assert(is_execution_space_v<ExecSpace>, "first argument must be an execution space");
  static_assert(Kokkos::SpaceAccessibility<ExecSpace, typename View::memory_space>::accessible,
                "View is not accessible from this execution space");
  return RangePolicy<ExecSpace>(exec, 0, static_cast<int>(x.extent(0)));
}
}  // namespace detail

/// x(i) = value
template <class ExecSpace, class X>
void fill(const ExecSpace& exec, const X& x, typename X::non_const_value_type value) {
  Kokkos::parallel_for("amphora::blas1::fill", detail::range(exec, x),
                       KOKKOS_LAMBDA(int i) { x(i) = value; });
}

/// y(i) = x(i)
template <class ExecSpace, class X, class Y>
void copy(const ExecSpace& exec, const X& x, const Y& y) {
  Kokkos::parallel_for("amphora::blas1::copy", detail::range(exec, y),
                       KOKKOS_LAMBDA(int i) { y(i) = x(i); });
}

/// x(i) *= a
template <class ExecSpace, class X>
void scale(const ExecSpace& exec, typename X::non_const_value_type a, const X& x) {
  Kokkos::parallel_for("amphora::blas1::scale", detail::range(exec, x),
                       KOKKOS_LAMBDA(int i) { x(i) *= a; });
}

/// y(i) += a x(i)
template <class ExecSpace, class X, class Y>
void axpy(const ExecSpace& exec, typename Y::non_const_value_type a, const X& x, const Y& y) {
  Kokkos::parallel_for("amphora::blas1::axpy", detail::range(exec, y),
                       KOKKOS_LAMBDA(int i) { y(i) += a * x(i); });
}

/// y(i) = a x(i) + b y(i)
template <class ExecSpace, class X, class Y>
void axpby(const ExecSpace& exec, typename Y::non_const_value_type a, const X& x,
           typename Y::non_const_value_type b, const Y& y) {
  Kokkos::parallel_for("amphora::blas1::axpby", detail::range(exec, y),
                       KOKKOS_LAMBDA(int i) { y(i) = a * x(i) + b * y(i); });
}

/// sum_i x(i) y(i)
template <class ExecSpace, class X, class Y>
typename X::non_const_value_type dot(const ExecSpace& exec, const X& x, const Y& y) {
  using T = typename X::non_const_value_type;
  T result{};
  Kokkos::parallel_reduce("amphora::blas1::dot", detail::range(exec, x),
                          KOKKOS_LAMBDA(int i, T& acc) { acc += x(i) * y(i); }, result);
  return result;
}

/// sum_i x(i)
template <class ExecSpace, class X>
typename X::non_const_value_type sum(const ExecSpace& exec, const X& x) {
  using T = typename X::non_const_value_type;
  T result{};
  Kokkos::parallel_reduce("amphora::blas1::sum", detail::range(exec, x),
                          KOKKOS_LAMBDA(int i, T& acc) { acc += x(i); }, result);
  return result;
}

/// sum_i |x(i)|
template <class ExecSpace, class X>
typename X::non_const_value_type norm1(const ExecSpace& exec, const X& x) {
  using T = typename X::non_const_value_type;
  T result{};
  Kokkos::parallel_reduce("amphora::blas1::norm1", detail::range(exec, x),
                          KOKKOS_LAMBDA(int i, T& acc) { acc += math::abs(x(i)); }, result);
  return result;
}

/// sqrt(sum_i x(i)^2)
template <class ExecSpace, class X>
typename X::non_const_value_type norm2(const ExecSpace& exec, const X& x) {
  return math::sqrt(dot(exec, x, x));
}

/// max_i |x(i)| (0 for an empty View)
template <class ExecSpace, class X>
typename X::non_const_value_type norm_inf(const ExecSpace& exec, const X& x) {
  using T = typename X::non_const_value_type;
  T result{};
  Kokkos::parallel_reduce(
      "amphora::blas1::norm_inf", detail::range(exec, x),
      KOKKOS_LAMBDA(int i, T& acc) { acc = math::max(acc, math::abs(x(i))); },
      Kokkos::Max<T>(result));
  return x.extent(0) == 0 ? T{} : result;
}

}  // namespace amphora::blas1
