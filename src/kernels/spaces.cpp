#include "kernels/spaces.hpp"

namespace amphora::kernels {

std::string enabled_backends() {
  std::string names;
  auto add = [&](const char* n) { names += names.empty() ? n : std::string(" ") + n; };
#ifdef KOKKOS_ENABLE_SERIAL
  add("Serial");
#endif
#ifdef KOKKOS_ENABLE_OPENMP
  add("OpenMP");
#endif
#ifdef KOKKOS_ENABLE_THREADS
  add("Threads");
#endif
#ifdef KOKKOS_ENABLE_CUDA
  add("Cuda");
#endif
#ifdef KOKKOS_ENABLE_HIP
  add("HIP");
#endif
#ifdef KOKKOS_ENABLE_SYCL
  add("SYCL");
#endif
  return names;
}

}  // namespace amphora::kernels
