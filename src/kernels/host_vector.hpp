#pragma once
// Copies between host std::vector and 1D Views in any memory space (setup, output, tests).
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

namespace amphora::kernels {

template <class MemSpace, class T, class Allocator>
Kokkos::View<T*, MemSpace> to_view(const std::vector<T, Allocator>& v,
                                   const char* label = "amphora::vector") {
  Kokkos::View<T*, MemSpace> d(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(label)),
                               v.size());
  auto h = Kokkos::create_mirror_view(d);
  for (std::size_t i = 0; i < v.size(); ++i) h(i) = v[i];
  Kokkos::deep_copy(d, h);
  return d;
}

template <class View>
std::vector<double> to_std_vector(const View& d) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), d);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

}  // namespace amphora::kernels
