#pragma once
// Execution- and memory-space vocabulary. Kernels and data structures are templated on these;
// nothing below the apps layer names a concrete backend except through this header.
#include <string>
#include <type_traits>

#include "kernels/kokkos_compat.hpp"

namespace amphora::kernels {

using DefaultExecSpace = Kokkos::DefaultExecutionSpace;
using DefaultMemSpace = DefaultExecSpace::memory_space;
using HostExecSpace = Kokkos::DefaultHostExecutionSpace;
using HostMemSpace = Kokkos::HostSpace;

template <class T>
inline constexpr bool is_execution_space_v = Kokkos::is_execution_space<T>::value;
template <class T>
inline constexpr bool is_memory_space_v = Kokkos::is_memory_space<T>::value;

/// Whether ExecSpace's threads run on the host: the schedules meant for CPUs (coloured cell
/// loops instead of atomics, SIMD lanes) go by this. It asks about the execution space, not its
/// memory space: CUDA's UVM memory is host-accessible, yet its kernels run on the device.
template <class ExecSpace>
inline constexpr bool runs_on_host_v =
    Kokkos::SpaceAccessibility<ExecSpace, Kokkos::HostSpace>::accessible;

/// Contiguous 1D array of T in memory space MemSpace (the SoA building block).
template <class T, class MemSpace = DefaultMemSpace>
using Array1D = Kokkos::View<T*, Kokkos::LayoutRight, MemSpace>;

/// Index range over [begin, end) on ExecSpace, with the index type spelled once.
template <class ExecSpace>
using RangePolicy = Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<int>>;

/// Names of the execution spaces this Kokkos was built with, e.g. "Serial OpenMP".
std::string enabled_backends();

}  // namespace amphora::kernels

// Explicit instantiation of a class template on every enabled execution space, for classes
// whose members live in a .cpp: AMPHORA_INSTANTIATE_ON_EXEC_SPACES(MyClass) inside its namespace.
#ifdef KOKKOS_ENABLE_SERIAL
#define AMPHORA_IF_SERIAL(x) x
#else
#define AMPHORA_IF_SERIAL(x)
#endif
#ifdef KOKKOS_ENABLE_OPENMP
#define AMPHORA_IF_OPENMP(x) x
#else
#define AMPHORA_IF_OPENMP(x)
#endif
#ifdef KOKKOS_ENABLE_CUDA
#define AMPHORA_IF_CUDA(x) x
#else
#define AMPHORA_IF_CUDA(x)
#endif
#ifdef KOKKOS_ENABLE_HIP
#define AMPHORA_IF_HIP(x) x
#else
#define AMPHORA_IF_HIP(x)
#endif
// MACRO(space) for every enabled execution space: explicit instantiations of members defined
// in another .cpp than their class's AMPHORA_INSTANTIATE_ON_EXEC_SPACES.
#define AMPHORA_FOR_EACH_EXEC_SPACE(MACRO) \
  AMPHORA_IF_SERIAL(MACRO(Kokkos::Serial)) \
  AMPHORA_IF_OPENMP(MACRO(Kokkos::OpenMP)) \
  AMPHORA_IF_CUDA(MACRO(Kokkos::Cuda))     \
  AMPHORA_IF_HIP(MACRO(Kokkos::Experimental::HIP))
#define AMPHORA_INSTANTIATE_ON_EXEC_SPACES(CLASS)          \
  AMPHORA_IF_SERIAL(template class CLASS<Kokkos::Serial>;) \
  AMPHORA_IF_OPENMP(template class CLASS<Kokkos::OpenMP>;) \
  AMPHORA_IF_CUDA(template class CLASS<Kokkos::Cuda>;)     \
  AMPHORA_IF_HIP(template class CLASS<Kokkos::Experimental::HIP>;)
