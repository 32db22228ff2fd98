#pragma once
// Software prefetch: asks for the 64-byte line holding an address to be brought into L2 ahead
// of use, where the hardware prefetcher cannot guess the address (indirect accesses). A hint:
// it does nothing on devices or with compilers that lack the builtin.
#include "kernels/kokkos_compat.hpp"

namespace amphora {

/// The line at p, to be read (write = false) or written (write = true).
KOKKOS_FORCEINLINE_FUNCTION void prefetch_line(const void* p, bool write) {
#if defined(__GNUC__) && !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)
  if (write) __builtin_prefetch(p, 1, 2);
  else __builtin_prefetch(p, 0, 2);
#else
  (void)p, (void)write;
#endif
}

/// The line at p, to be read soon: into L1.
KOKKOS_FORCEINLINE_FUNCTION void prefetch_line_l1(const void* p) {
#if defined(__GNUC__) && !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)
  __builtin_prefetch(p, 0, 3);
#else
  (void)p;
#endif
}

}  // namespace amphora
