#pragma once
// BLAS-1 kernels on rank-local 1D Views, templated on the execution space (passed first).
// Reductions use Kokkos' built-in reducers: their order depends on the thread count, so
// results agree across thread counts to round-off, and are bitwise repeatable for a fixed one.
#include "kernels/spaces.hpp"

namespace amphora::kernels::blas1 {

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
  Kokkos::parallel_for(
      "amphora::blas1::fill", detail::range(exec, x), KOKKOS_LAMBDA(int i) { x(i) = value; });
}

/// y(i) = x(i)
template <class ExecSpace, class X, class Y>
void copy(const ExecSpace& exec, const X& x, const Y& y) {
  Kokkos::parallel_for(
      "amphora::blas1::copy", detail::range(exec, y), KOKKOS_LAMBDA(int i) { y(i) = x(i); });
}

/// x(i) *= a
template <class ExecSpace, class X>
void scale(const ExecSpace& exec, typename X::non_const_value_type a, const X& x) {
  Kokkos::parallel_for(
      "amphora::blas1::scale", detail::range(exec, x), KOKKOS_LAMBDA(int i) { x(i) *= a; });
}

/// y(i) += a x(i)
template <class ExecSpace, class X, class Y>
void axpy(const ExecSpace& exec, typename Y::non_const_value_type a, const X& x, const Y& y) {
  Kokkos::parallel_for(
      "amphora::blas1::axpy", detail::range(exec, y), KOKKOS_LAMBDA(int i) { y(i) += a * x(i); });
}

/// x(i) = 1 / x(i) (a diagonal into its inverse, for Jacobi).
template <class ExecSpace, class X>
void reciprocal(const ExecSpace& exec, const X& x) {
  Kokkos::parallel_for(
      "amphora::blas1::reciprocal", detail::range(exec, x),
      KOKKOS_LAMBDA(int i) { x(i) = 1.0 / x(i); });
}

/// y(i) = a x(i) + b y(i)
template <class ExecSpace, class X, class Y>
void axpby(const ExecSpace& exec, typename Y::non_const_value_type a, const X& x,
           typename Y::non_const_value_type b, const Y& y) {
  Kokkos::parallel_for(
      "amphora::blas1::axpby", detail::range(exec, y),
      KOKKOS_LAMBDA(int i) { y(i) = a * x(i) + b * y(i); });
}

/// y(i) = x(i) + b y(i), and y = x where b is 0 (y is not read: it may be uninitialised). CG's
/// new direction p = z + beta p.
template <class ExecSpace, class X, class Y>
void xpby(const ExecSpace& exec, const X& x, typename Y::non_const_value_type b, const Y& y) {
  if (b == 0)
    copy(exec, x, y);
  else
    Kokkos::parallel_for(
        "amphora::blas1::xpby", detail::range(exec, y),
        KOKKOS_LAMBDA(int i) { y(i) = x(i) + b * y(i); });
}

/// sum_i x(i) y(i). Each work item sums a block of 8 entries as a tree: without reassociation a
/// compiler adds one entry after the other, and the latency of that chain, not memory, bounds a
/// plain loop (3x slower on 2M entries here).
template <class ExecSpace, class X, class Y>
typename X::non_const_value_type dot(const ExecSpace& exec, const X& x, const Y& y) {
  using T = typename X::non_const_value_type;
  const int n = static_cast<int>(x.extent(0)), blocks = n / 8;
  T result{};
  Kokkos::parallel_reduce(
      "amphora::blas1::dot", RangePolicy<ExecSpace>(exec, 0, blocks + (n % 8 != 0)),
      KOKKOS_LAMBDA(int blk, T& acc) {
        const int i = 8 * blk;
        if (blk < blocks) {
          acc +=
              ((x(i) * y(i) + x(i + 1) * y(i + 1)) + (x(i + 2) * y(i + 2) + x(i + 3) * y(i + 3))) +
              ((x(i + 4) * y(i + 4) + x(i + 5) * y(i + 5)) +
               (x(i + 6) * y(i + 6) + x(i + 7) * y(i + 7)));
        } else {
          for (int m = i; m < n; ++m) acc += x(m) * y(m);
        }
      },
      result);
  return result;
}

/// The update of a CG iteration in one pass: x += a p, r -= a q; returns r.r (blocks of 8 as in
/// dot).
template <class ExecSpace, class P, class Q, class X, class R>
typename X::non_const_value_type cg_update(const ExecSpace& exec,
                                           typename X::non_const_value_type a, const P& p,
                                           const Q& q, const X& x, const R& r) {
  using T = typename X::non_const_value_type;
  const int n = static_cast<int>(x.extent(0)), blocks = (n + 7) / 8;
  T result{};
  Kokkos::parallel_reduce(
      "amphora::blas1::cg_update", RangePolicy<ExecSpace>(exec, 0, blocks),
      KOKKOS_LAMBDA(int blk, T& acc) {
        const int i0 = 8 * blk, len = n - i0 < 8 ? n - i0 : 8;
        T rr[8] = {};
        for (int m = 0; m < len; ++m) {
          x(i0 + m) += a * p(i0 + m);
          const T ri = r(i0 + m) - a * q(i0 + m);
          r(i0 + m) = ri;
          rr[m] = ri * ri;
        }
        acc += ((rr[0] + rr[1]) + (rr[2] + rr[3])) + ((rr[4] + rr[5]) + (rr[6] + rr[7]));
      },
      result);
  return result;
}

/// sum_i x(i)
template <class ExecSpace, class X>
typename X::non_const_value_type sum(const ExecSpace& exec, const X& x) {
  using T = typename X::non_const_value_type;
  T result{};
  Kokkos::parallel_reduce(
      "amphora::blas1::sum", detail::range(exec, x), KOKKOS_LAMBDA(int i, T& acc) { acc += x(i); },
      result);
  return result;
}

/// sum_i |x(i)|
template <class ExecSpace, class X>
typename X::non_const_value_type norm1(const ExecSpace& exec, const X& x) {
  using T = typename X::non_const_value_type;
  T result{};
  Kokkos::parallel_reduce(
      "amphora::blas1::norm1", detail::range(exec, x),
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

}  // namespace amphora::kernels::blas1
