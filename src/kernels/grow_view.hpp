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

/// Grows v (contents kept) to at least n rows, by half its size at a time or more, unless it
/// holds n rows already; inner extents are kept.
template <class View>
void grow_preserving(View& v, int n) {
  if (int(v.extent(0)) >= n) return;
  const int cap = n > int(v.extent(0)) * 3 / 2 ? n : int(v.extent(0)) * 3 / 2;
  if constexpr (View::rank_dynamic == 1) {
    Kokkos::resize(v, cap);
  } else {
    Kokkos::resize(v, cap, v.extent(1));
  }
}

}  // namespace amphora::kernels
