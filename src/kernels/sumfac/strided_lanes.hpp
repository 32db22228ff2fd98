#pragma once
// One row of nodes of a cell batch, between the DoF vector and the batch's lanes: the W cells
// of a batch are consecutive along x, so lane l's node i of a row sits at p[l k + i]
// (k = the degree; node k of lane l is node 0 of lane l + 1). With k known at compile time
// the compiler turns the strided reads into whole-vector loads and permutes; the adds go
// through a contiguous buffer, so they are whole vectors too instead of a chain of scalar
// read-modify-writes that may alias one another.
#include <cstddef>
#include <utility>

#include "kernels/sumfac/simd.hpp"

namespace amphora::kernels::sumfac {

// (not under nvcc, whose host pass hands GCC a pack expansion inside the builtin it rejects)
#if defined(__has_builtin) && !defined(__CUDACC__)
#if __has_builtin(__builtin_shufflevector)
#define AMPHORA_HAS_SHUFFLEVECTOR 1
#endif
#endif

#ifdef AMPHORA_SIMD_VECTOR_EXTENSIONS
namespace detail {
/// (0, a_0, ..., a_{W-2}): a's lanes moved up by one, in one permute where the compiler has
/// __builtin_shufflevector (clang, GCC 12+; lane l of the result is lane W + l - 1 of the pair
/// (zero, a)), else lane by lane.
template <int W, std::size_t... l>
KOKKOS_FORCEINLINE_FUNCTION typename Simd<W>::native up_one_lane(const typename Simd<W>::native& a,
                                                                 std::index_sequence<l...>) {
  const typename Simd<W>::native zero = {};
#ifdef AMPHORA_HAS_SHUFFLEVECTOR
  return __builtin_shufflevector(zero, a, (l == 0 ? 0 : int(W + l - 1))...);
#else
  typename Simd<W>::native r = zero;
  for (int m = 1; m < W; ++m) r[m] = a[m - 1];
  return r;
#endif
}
}  // namespace detail
#endif

/// u[i][l] = p[l k + i] for i <= k and every lane l.
template <int k, int W>
KOKKOS_FORCEINLINE_FUNCTION void read_strided_row(const double* p, Simd<W>* u) {
#ifdef AMPHORA_SIMD_VECTOR_EXTENSIONS
  if constexpr (k == 1) {
    // degree 1: node i of the lanes is p[i .. i + W), two unaligned whole-vector loads (GCC
    // otherwise assembles them from scalar loads and inserts)
    __builtin_memcpy(&u[0].v, p, sizeof(u[0].v));
    __builtin_memcpy(&u[1].v, p + 1, sizeof(u[1].v));
    return;
  }
#endif
  for (int l = 0; l < W; ++l)
    for (int i = 0; i <= k; ++i) u[i][l] = p[l * k + i];
}

/// p[l k + i] += u[i][l] for i <= k and every lane l. Lane l's node k is lane l+1's node 0:
/// folding it in first leaves W k disjoint, contiguous entries and the row's last node.
template <int k, int W>
KOKKOS_FORCEINLINE_FUNCTION void add_strided_row(double* p, const Simd<W>* u) {
#ifdef AMPHORA_SIMD_VECTOR_EXTENSIONS
  if constexpr (k == 1) {
    // degree 1: p[0 .. W) += u[0] + u[1] shifted up one lane, then the last node; one
    // read-modify-write of a whole vector (two overlapping ones would stall on store
    // forwarding)
    const typename Simd<W>::native row =
        u[0].v + detail::up_one_lane<W>(u[1].v, std::make_index_sequence<W>());
    typename Simd<W>::native dst;
    __builtin_memcpy(&dst, p, sizeof(dst));
    dst += row;
    __builtin_memcpy(p, &dst, sizeof(dst));
    p[W] += u[1][W - 1];
    return;
  }
#endif
  alignas(64) double row[W * k];
  for (int l = 0; l < W; ++l) {
    row[l * k] = u[0][l] + (l > 0 ? u[k][l - 1] : 0.0);
    for (int i = 1; i < k; ++i) row[l * k + i] = u[i][l];
  }
  for (int m = 0; m < W * k; ++m) p[m] += row[m];
  p[W * k] += u[k][W - 1];
}

}  // namespace amphora::kernels::sumfac
