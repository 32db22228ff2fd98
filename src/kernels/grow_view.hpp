#pragma once
// Kept work arrays: a View reallocated only when it is too small, so that a time step that
// reuses it allocates nothing on the device.
#include <cstddef>
#include <string>

#include <Kokkos_Core.hpp>

namespace amphora::kernels {

/// Reallocates v (uninitialised, under `label`) unless it holds n entries already.
template <class View>
void grow_uninitialized(View& v, std::size_t n, const char* label) {
  if (v.extent(0) < n)
    v = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(label)), n);
}

}  // namespace amphora::kernels
