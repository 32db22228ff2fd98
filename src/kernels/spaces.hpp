#pragma once
// Execution- and memory-space vocabulary. Kernels and data structures are templated on these;
// nothing below the apps layer names a concrete backend except through this header.
#include <string>
#include <type_traits>

#include "kernels/kokkos_compat.hpp"

namespace amphora {

using DefaultExecSpace = Kokkos::DefaultExecutionSpace;
using DefaultMemSpace = DefaultExecSpace::memory_space;
using HostExecSpace = Kokkos::DefaultHostExecutionSpace;
using HostMemSpace = Kokkos::HostSpace;

template <class T>
inline constexpr bool is_execution_space_v = Kokkos::is_execution_space<T>::value;
template <class T>
inline constexpr bool is_memory_space_v = Kokkos::is_memory_space<T>::value;

/// Contiguous 1D array of T in memory space MemSpace (the SoA building block).
template <class T, class MemSpace = DefaultMemSpace>
using Array1D = Kokkos::View<T*, Kokkos::LayoutRight, MemSpace>;

/// Index range over [begin, end) on ExecSpace, with the index type spelled once.
template <class ExecSpace>
using RangePolicy = Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<int>>;

/// Names of the execution spaces this Kokkos was built with, e.g. "Serial OpenMP".
std::string enabled_backends();

}  // namespace amphora
