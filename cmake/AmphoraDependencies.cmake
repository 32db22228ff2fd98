# Every dependency is found here, once. Required backends and features are checked
# explicitly so a wrong installation fails at configure time with a message saying what to do.

find_package(Kokkos REQUIRED)
set(AMPHORA_REQUIRED_KOKKOS_BACKENDS SERIAL OPENMP CACHE STRING
    "Kokkos backends amphora requires (checked with kokkos_check)")
foreach(backend IN LISTS AMPHORA_REQUIRED_KOKKOS_BACKENDS)
  if(COMMAND kokkos_check)
    kokkos_check(DEVICES ${backend} RETURN_VALUE _has_backend)
  else()
    list(FIND Kokkos_DEVICES ${backend} _idx)
    if(_idx GREATER -1)
      set(_has_backend TRUE)
    else()
      set(_has_backend FALSE)
    endif()
  endif()
  if(NOT _has_backend)
    message(FATAL_ERROR
      "The Kokkos found in ${Kokkos_DIR} lacks the ${backend} backend (it has: ${Kokkos_DEVICES}). "
      "Run scripts/setup.sh (builds Kokkos with Serial+OpenMP under the build tree) or pass "
      "-DKokkos_ROOT=<prefix of a Kokkos with ${AMPHORA_REQUIRED_KOKKOS_BACKENDS}>.")
  endif()
endforeach()
message(STATUS "Kokkos ${Kokkos_VERSION} from ${Kokkos_DIR}, devices: ${Kokkos_DEVICES}")

# CUDA: nvcc must compile every kernel. A device function that calls a host function is an
# error, not the warning nvcc gives by default (#20011-#20015: host function, constexpr host
# function, or a defaulted function's ignored annotation, called from device code), so such a
# kernel fails the build rather than a later GPU run.
set(AMPHORA_CUDA OFF)
if(Kokkos_DEVICES MATCHES "CUDA")
  set(AMPHORA_CUDA ON)
  # Eigen serves host code only: without this its defaulted members carry __host__ __device__.
  add_compile_definitions(EIGEN_NO_CUDA)
  foreach(diag 20011 20012 20013 20014 20015)
    add_compile_options("SHELL:-Xcudafe --diag_error=${diag}")
  endforeach()
  # Each object keeps its own KOKKOS_LAMBDA wrappers (nvcc's per-file function pointers behind
  # weak, merged members make the host jump to address 0): see cmake/nvcc_lambda_wrappers.sh.
  find_program(AMPHORA_OBJCOPY objcopy REQUIRED)
  # A compile check (the cuda-check preset, CI's): nvcc's fastest device mode (-Ofc max) runs
  # every kernel through cudafe++, cicc and ptxas with few optimisations (times: docs/gpu.md);
  # the define keeps its objects apart from optimised ones in ccache.
  option(AMPHORA_CUDA_FAST_COMPILE "CUDA: device code at nvcc -Ofc max (a compile check)" OFF)
  set(_amphora_fast "")
  if(AMPHORA_CUDA_FAST_COMPILE)
    set(_amphora_fast --fast-compile)
    add_compile_definitions(AMPHORA_CUDA_FAST_COMPILE)
  endif()
  set(CMAKE_CXX_COMPILER_LAUNCHER
      ${CMAKE_CURRENT_LIST_DIR}/nvcc_lambda_wrappers.sh ${_amphora_fast} ${CCACHE_PROGRAM})
endif()

find_package(MPI REQUIRED COMPONENTS C CXX)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(HYPRE 2.20 REQUIRED)

set(HDF5_PREFER_PARALLEL ON)
find_package(HDF5 REQUIRED COMPONENTS C)
if(NOT HDF5_IS_PARALLEL)
  message(FATAL_ERROR "HDF5 at ${HDF5_INCLUDE_DIRS} is not built with MPI (H5_HAVE_PARALLEL); "
                      "install libhdf5-openmpi-dev (scripts/setup.sh does).")
endif()
add_library(amphora_hdf5 INTERFACE)
target_include_directories(amphora_hdf5 SYSTEM INTERFACE ${HDF5_INCLUDE_DIRS})
target_link_libraries(amphora_hdf5 INTERFACE ${HDF5_LIBRARIES})
target_compile_definitions(amphora_hdf5 INTERFACE ${HDF5_DEFINITIONS})

find_package(tomlplusplus REQUIRED)
find_package(CLI11 REQUIRED)

if(AMPHORA_ENABLE_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
if(AMPHORA_ENABLE_TESTS)
  find_package(GTest REQUIRED)
endif()

find_program(AMPHORA_PYTHON NAMES python3 HINTS /usr/bin NO_DEFAULT_PATH)
if(NOT AMPHORA_PYTHON)
  find_program(AMPHORA_PYTHON NAMES python3)
endif()
