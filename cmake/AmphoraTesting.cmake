# Test helpers (Kokkos' and Cabana's pattern): a test body is written once against
# `TestExecSpace` and compiled once per enabled backend; OpenMP tests run at 1 and 2 threads,
# MPI tests at 1 and 2 ranks, and the test names say which.

set(AMPHORA_TEST_ENVIRONMENT
  "OMP_PROC_BIND=false"
  "OMPI_ALLOW_RUN_AS_ROOT=1"
  "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"
  "OMPI_MCA_rmaps_base_oversubscribe=1"
  "OMPI_MCA_btl_vader_single_copy_mechanism=none")

# Every enabled backend, unless AMPHORA_TEST_BACKENDS names some (the CUDA preset names only
# Cuda: Serial is the CPU build's, and nvcc compiling each test twice costs CI a quarter hour).
set(AMPHORA_TEST_BACKENDS "" CACHE STRING "Kokkos backends the unit tests are built for (empty: all enabled)")
if(NOT AMPHORA_TEST_BACKENDS)
  set(AMPHORA_TEST_BACKENDS "")
  foreach(backend Serial OpenMP Cuda)
    string(TOUPPER ${backend} upper)
    if(Kokkos_DEVICES MATCHES "${upper}")
      list(APPEND AMPHORA_TEST_BACKENDS ${backend})
    endif()
  endforeach()
endif()
foreach(backend IN LISTS AMPHORA_TEST_BACKENDS)
  string(TOUPPER ${backend} upper)
  if(NOT Kokkos_DEVICES MATCHES "${upper}")
    message(FATAL_ERROR "AMPHORA_TEST_BACKENDS names ${backend}, which this Kokkos lacks (it has: ${Kokkos_DEVICES})")
  endif()
endforeach()

function(_amphora_set_test_env test threads)
  set_tests_properties(${test} PROPERTIES ENVIRONMENT
    "${AMPHORA_TEST_ENVIRONMENT};OMP_NUM_THREADS=${threads};KOKKOS_NUM_THREADS=${threads};AMPHORA_TEST_THREADS=${threads}")
endfunction()

# amphora_backend_test(NAME src... [LABELS l...]): one executable and test set per backend.
function(amphora_backend_test name)
  cmake_parse_arguments(ARG "" "" "LABELS" ${ARGN})
  foreach(backend IN LISTS AMPHORA_TEST_BACKENDS)
    string(TOLOWER ${backend} lower)
    set(exe ${name}_${lower})
    add_executable(${exe} ${ARG_UNPARSED_ARGUMENTS})
    target_compile_definitions(${exe} PRIVATE AMPHORA_TEST_BACKEND=Kokkos::${backend})
    target_link_libraries(${exe} PRIVATE amphora_test_main amphora_warnings)
    if(backend STREQUAL "OpenMP")
      foreach(threads 1 2)
        add_test(NAME ${name}.openmp.${threads}threads COMMAND ${exe})
        _amphora_set_test_env(${name}.openmp.${threads}threads ${threads})
        set_tests_properties(${name}.openmp.${threads}threads PROPERTIES
          PROCESSORS ${threads} LABELS "unit;${ARG_LABELS}")
      endforeach()
    else()
      add_test(NAME ${name}.${lower} COMMAND ${exe})
      _amphora_set_test_env(${name}.${lower} 1)
      set_tests_properties(${name}.${lower} PROPERTIES LABELS "unit;${ARG_LABELS}")
    endif()
  endforeach()
endfunction()

# amphora_host_test(NAME src... [LABELS l...]): host-only code (no kernels), one executable.
function(amphora_host_test name)
  cmake_parse_arguments(ARG "" "" "LABELS" ${ARGN})
  add_executable(${name} ${ARG_UNPARSED_ARGUMENTS})
  target_compile_definitions(${name} PRIVATE AMPHORA_TEST_BACKEND=Kokkos::DefaultHostExecutionSpace)
  target_link_libraries(${name} PRIVATE amphora_test_main amphora_warnings)
  add_test(NAME ${name} COMMAND ${name})
  _amphora_set_test_env(${name} 1)
  set_tests_properties(${name} PROPERTIES LABELS "unit;${ARG_LABELS}")
endfunction()

# amphora_mpi_test(NAME src...): default execution space, run at 1 and 2 ranks, 1 thread each.
function(amphora_mpi_test name)
  add_executable(${name} ${ARGN})
  target_compile_definitions(${name} PRIVATE AMPHORA_TEST_BACKEND=Kokkos::DefaultExecutionSpace)
  target_link_libraries(${name} PRIVATE amphora_test_main amphora_warnings)
  foreach(ranks 1 2)
    add_test(NAME ${name}.mpi${ranks}
      COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${ranks} ${MPIEXEC_PREFLAGS}
              $<TARGET_FILE:${name}> ${MPIEXEC_POSTFLAGS})
    _amphora_set_test_env(${name}.mpi${ranks} 1)
    set_tests_properties(${name}.mpi${ranks} PROPERTIES PROCESSORS ${ranks} LABELS "mpi")
  endforeach()
endfunction()

# amphora_app_test(NAME script [LABELS l...]): a bash script driving the real `amphora` binary.
function(amphora_app_test name script)
  cmake_parse_arguments(ARG "" "" "LABELS" ${ARGN})
  add_test(NAME app.${name}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/${script}
    WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(app.${name} PROPERTIES
    LABELS "app;${ARG_LABELS}"
    ENVIRONMENT "${AMPHORA_TEST_ENVIRONMENT};OMP_NUM_THREADS=1;KOKKOS_NUM_THREADS=1;AMPHORA=$<TARGET_FILE:amphora>;AMPHORA_SOURCE_DIR=${PROJECT_SOURCE_DIR};AMPHORA_BUILD_DIR=${PROJECT_BINARY_DIR};MPIEXEC=${MPIEXEC_EXECUTABLE};AMPHORA_PYTHON=${AMPHORA_PYTHON}")
endfunction()
