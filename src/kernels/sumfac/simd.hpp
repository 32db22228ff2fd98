#pragma once
// A batch of W numbers processed in lock step: the cell-batch type of the matrix-free kernels.
// On CPUs one batch holds W cells and every arithmetic operation is one SIMD instruction
// (GNU vector extensions, so AVX-512 registers are used even where the compiler prefers
// 256-bit auto-vectorisation); on GPUs W = 1 and the lanes are threads. Data at quadrature
// points are stored lane-fastest, so a batch is one aligned load on CPUs and consecutive
// threads read consecutive addresses on GPUs (DESIGN.md; KOKKOS.md, "lessons from others").
#include <Kokkos_Core.hpp>

#include "kernels/spaces.hpp"

namespace amphora::kernels::sumfac {

#if defined(__AVX512F__)
inline constexpr int host_simd_width = 8;
#elif defined(__AVX__)
inline constexpr int host_simd_width = 4;
#else
inline constexpr int host_simd_width = 2;
#endif

/// Lanes per batch on execution space E: the SIMD width on host spaces, 1 on devices.
template <class ExecSpace>
inline constexpr int simd_width_v = runs_on_host_v<ExecSpace> ? host_simd_width : 1;

#if (defined(__GNUC__) || defined(__clang__)) && !defined(__CUDA_ARCH__) && \
    !defined(__HIP_DEVICE_COMPILE__)
#define AMPHORA_SIMD_VECTOR_EXTENSIONS 1
#endif

template <int W>
struct alignas(W * sizeof(double)) Simd {
#ifdef AMPHORA_SIMD_VECTOR_EXTENSIONS
  typedef double native __attribute__((vector_size(W * sizeof(double))));
  native v;
  KOKKOS_INLINE_FUNCTION double& operator[](int l) { return reinterpret_cast<double*>(&v)[l]; }
  KOKKOS_INLINE_FUNCTION double operator[](int l) const {
    return reinterpret_cast<const double*>(&v)[l];
  }
  Simd() = default;
  KOKKOS_INLINE_FUNCTION Simd(double s) : v(s - native{}) {}
  KOKKOS_INLINE_FUNCTION Simd& operator+=(const Simd& o) {
    v += o.v;
    return *this;
  }
  KOKKOS_INLINE_FUNCTION Simd& operator-=(const Simd& o) {
    v -= o.v;
    return *this;
  }
  KOKKOS_INLINE_FUNCTION Simd& operator*=(const Simd& o) {
    v *= o.v;
    return *this;
  }
  KOKKOS_INLINE_FUNCTION friend Simd operator+(Simd a, const Simd& b) {
    a.v += b.v;
    return a;
  }
  KOKKOS_INLINE_FUNCTION friend Simd operator-(Simd a, const Simd& b) {
    a.v -= b.v;
    return a;
  }
  KOKKOS_INLINE_FUNCTION friend Simd operator*(Simd a, const Simd& b) {
    a.v *= b.v;
    return a;
  }
  KOKKOS_INLINE_FUNCTION friend Simd operator/(Simd a, const Simd& b) {
    a.v /= b.v;
    return a;
  }
  KOKKOS_INLINE_FUNCTION friend Simd operator-(Simd a) {
    a.v = -a.v;
    return a;
  }
#else
  double v[W];
  KOKKOS_INLINE_FUNCTION double& operator[](int l) { return v[l]; }
  KOKKOS_INLINE_FUNCTION double operator[](int l) const { return v[l]; }
  Simd() = default;
  KOKKOS_INLINE_FUNCTION Simd(double s) {
    for (int l = 0; l < W; ++l) v[l] = s;
  }
#define AMPHORA_SIMD_OP(op)                                               \
  KOKKOS_INLINE_FUNCTION Simd& operator op##=(const Simd& o) {            \
    for (int l = 0; l < W; ++l) v[l] op## = o.v[l];                       \
    return *this;                                                         \
  }                                                                       \
  KOKKOS_INLINE_FUNCTION friend Simd operator op(Simd a, const Simd& b) { \
    a op## = b;                                                           \
    return a;                                                             \
  }
  AMPHORA_SIMD_OP(+)
  AMPHORA_SIMD_OP(-)
  AMPHORA_SIMD_OP(*)
  AMPHORA_SIMD_OP(/)
#undef AMPHORA_SIMD_OP
  KOKKOS_INLINE_FUNCTION friend Simd operator-(Simd a) {
    for (int l = 0; l < W; ++l) a.v[l] = -a.v[l];
    return a;
  }
#endif
};

}  // namespace amphora::kernels::sumfac
