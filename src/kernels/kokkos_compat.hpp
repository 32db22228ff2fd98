#pragma once
// The one place where Kokkos 3.4 and 4.x differ for amphora (see ../shared KOKKOS.md):
// math functions moved out of Kokkos::Experimental, abs/min/max/clamp and pi only exist in 4.x,
// and View::HostMirror is deprecated in favour of host_mirror_type.
#include <Kokkos_Core.hpp>

#ifndef KOKKOS_VERSION
#error "Kokkos_Core.hpp did not define KOKKOS_VERSION"
#endif

// Before a KOKKOS_INLINE_FUNCTION template that host code may call with a host-only functor
// (a plain lambda): nvcc then checks the function's execution space per instantiation instead
// of rejecting the host call in the host-device body (its diagnostics 20011-20015).
#if defined(__CUDACC__)
#define AMPHORA_EXEC_CHECK_DISABLE _Pragma("nv_exec_check_disable")
#else
#define AMPHORA_EXEC_CHECK_DISABLE
#endif

namespace amphora::kernels {

/// A functor a kernel calls that may be host-only (a plain struct or lambda) where the kernel
/// runs on a host space: nvcc checks each instantiation instead of rejecting the host call in
/// the kernel's host-device body. On devices F must be device-callable, as ever.
template <class F>
struct AnySpaceCall {
  F f;
  AMPHORA_EXEC_CHECK_DISABLE
  template <class... Args>
  KOKKOS_INLINE_FUNCTION decltype(auto) operator()(Args&&... args) const {
    return f(static_cast<Args&&>(args)...);
  }
};

namespace math {

#if KOKKOS_VERSION >= 30700
using Kokkos::ceil;
using Kokkos::cos;
using Kokkos::exp;
using Kokkos::fabs;
using Kokkos::floor;
using Kokkos::isfinite;
using Kokkos::log;
using Kokkos::pow;
using Kokkos::sin;
using Kokkos::sqrt;
#else
using Kokkos::Experimental::ceil;
using Kokkos::Experimental::cos;
using Kokkos::Experimental::exp;
using Kokkos::Experimental::fabs;
using Kokkos::Experimental::floor;
using Kokkos::Experimental::isfinite;
using Kokkos::Experimental::log;
using Kokkos::Experimental::pow;
using Kokkos::Experimental::sin;
using Kokkos::Experimental::sqrt;
#endif

template <class T>
KOKKOS_INLINE_FUNCTION constexpr T abs(T x) {
  return x < T(0) ? -x : x;
}
template <class T>
KOKKOS_INLINE_FUNCTION constexpr T min(T a, T b) {
  return b < a ? b : a;
}
template <class T>
KOKKOS_INLINE_FUNCTION constexpr T max(T a, T b) {
  return a < b ? b : a;
}
template <class T>
KOKKOS_INLINE_FUNCTION constexpr T clamp(T x, T lo, T hi) {
  return x < lo ? lo : (hi < x ? hi : x);
}

template <class T>
constexpr T pi_v = T(3.141592653589793238462643383279502884L);
constexpr double pi = pi_v<double>;

}  // namespace math

/// Host mirror type of a View, spelled the same way in Kokkos 3.4 and 4.x/5.x.
template <class View>
using host_mirror_t = typename View::host_mirror_type;

}  // namespace amphora::kernels
