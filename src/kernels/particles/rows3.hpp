#pragma once
// A LayoutRight [n][3] View seen as a restrict pointer whose row stride, 3, is known at compile
// time. Kokkos keeps a LayoutRight stride at run time (rows may be padded), which in a contact
// loop costs a register (spilled) and a multiply per access.
#include <cstddef>
#include <stdexcept>
#include <type_traits>

#include "kernels/spaces.hpp"

namespace amphora::kernels::particles {

template <class T>
struct Rows3 {
  T* KOKKOS_RESTRICT p;
  template <class View>
  explicit Rows3(const View& v) : p(v.data()) {
    static_assert(std::is_same_v<typename View::array_layout, Kokkos::LayoutRight> &&
                      View::rank == 2 && View::static_extent(1) == 3,
                  "Rows3 views a LayoutRight [n][3] View");
    if (v.extent(0) > 1 && v.stride(0) != 3) throw std::logic_error("Rows3: padded rows");
  }
  KOKKOS_FORCEINLINE_FUNCTION T& operator()(int i, int d) const { return p[3 * size_t(i) + d]; }
};

}  // namespace amphora::kernels::particles
