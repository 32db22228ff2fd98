#pragma once
// Software prefetch: asks for the 64-byte line holding an address to be brought into L2 (or L1)
// ahead of use, where the hardware prefetcher cannot guess the address (indirect accesses). A hint:
// it does nothing on devices or with compilers that lack the builtin.
#include "kernels/kokkos_compat.hpp"

namespace amphora::kernels {

/// Where a prefetched line goes (__builtin_prefetch's locality).
enum PrefetchTarget : int { into_l2 = 2, into_l1 = 3 };

/// The line at p, to be read (write = false) or written (write = true).
template <int target = into_l2>
KOKKOS_FORCEINLINE_FUNCTION void prefetch_line(const void* p, bool write) {
#if defined(__GNUC__) && !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)
  if (write)
    __builtin_prefetch(p, 1, target);
  else
    __builtin_prefetch(p, 0, target);
#else
  (void)p, (void)write;
#endif
}

}  // namespace amphora::kernels
