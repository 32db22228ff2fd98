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

# A unity build (CMAKE_UNITY_BUILD, the cuda-check preset's) bundles the unit tests: instead of
# one executable per test, the sources of each kind (backend, host, MPI; slow ones apart) make
# one executable, CMAKE_UNITY_BUILD_BATCH_SIZE files to a translation unit. nvcc's fixed cost per
# file (about 15 s) is most of a test object's compile time; the code compiled is the same.
set(AMPHORA_TEST_UNITY ${CMAKE_UNITY_BUILD})

function(_amphora_register_backend_tests name exe backend labels)
  string(TOLOWER ${backend} lower)
  if(backend STREQUAL "OpenMP")
    foreach(threads 1 2)
      add_test(NAME ${name}.openmp.${threads}threads COMMAND ${exe})
      _amphora_set_test_env(${name}.openmp.${threads}threads ${threads})
      set_tests_properties(${name}.openmp.${threads}threads PROPERTIES
        PROCESSORS ${threads} LABELS "unit;${labels}")
    endforeach()
  else()
    add_test(NAME ${name}.${lower} COMMAND ${exe})
    _amphora_set_test_env(${name}.${lower} 1)
    set_tests_properties(${name}.${lower} PROPERTIES LABELS "unit;${labels}")
  endif()
endfunction()

function(_amphora_register_host_test name exe labels)
  add_test(NAME ${name} COMMAND ${exe})
  _amphora_set_test_env(${name} 1)
  set_tests_properties(${name} PROPERTIES LABELS "unit;${labels}")
endfunction()

function(_amphora_register_mpi_tests name exe)
  foreach(ranks 1 2)
    add_test(NAME ${name}.mpi${ranks}
      COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${ranks} ${MPIEXEC_PREFLAGS}
              $<TARGET_FILE:${exe}> ${MPIEXEC_POSTFLAGS})
    _amphora_set_test_env(${name}.mpi${ranks} 1)
    set_tests_properties(${name}.mpi${ranks} PROPERTIES PROCESSORS ${ranks} LABELS "mpi")
  endforeach()
endfunction()

function(_amphora_test_executable exe backend)
  add_executable(${exe} ${ARGN})
  target_compile_definitions(${exe} PRIVATE AMPHORA_TEST_BACKEND=${backend})
  target_link_libraries(${exe} PRIVATE amphora_test_main amphora_warnings)
endfunction()

# With AMPHORA_TEST_UNITY, a test's sources join the bundle KIND (absolute paths).
function(_amphora_bundle kind)
  foreach(src IN LISTS ARGN)
    get_filename_component(abs ${src} ABSOLUTE)
    set_property(GLOBAL APPEND PROPERTY AMPHORA_TEST_BUNDLE_${kind} ${abs})
  endforeach()
  set_property(GLOBAL APPEND PROPERTY AMPHORA_TEST_BUNDLES ${kind})
endfunction()

# amphora_backend_test(NAME src... [LABELS l...]): one executable and test set per backend.
function(amphora_backend_test name)
  cmake_parse_arguments(ARG "" "" "LABELS" ${ARGN})
  if(AMPHORA_TEST_UNITY)
    set(kind backend)
    if("slow" IN_LIST ARG_LABELS)
      set(kind backend_slow)
    endif()
    _amphora_bundle(${kind} ${ARG_UNPARSED_ARGUMENTS})
    return()
  endif()
  foreach(backend IN LISTS AMPHORA_TEST_BACKENDS)
    string(TOLOWER ${backend} lower)
    _amphora_test_executable(${name}_${lower} Kokkos::${backend} ${ARG_UNPARSED_ARGUMENTS})
    _amphora_register_backend_tests(${name} ${name}_${lower} ${backend} "${ARG_LABELS}")
  endforeach()
endfunction()

# amphora_host_test(NAME src... [LABELS l...]): host-only code (no kernels), one executable.
function(amphora_host_test name)
  cmake_parse_arguments(ARG "" "" "LABELS" ${ARGN})
  if(AMPHORA_TEST_UNITY)
    _amphora_bundle(host ${ARG_UNPARSED_ARGUMENTS})
    return()
  endif()
  _amphora_test_executable(${name} Kokkos::DefaultHostExecutionSpace ${ARG_UNPARSED_ARGUMENTS})
  _amphora_register_host_test(${name} ${name} "${ARG_LABELS}")
endfunction()

# amphora_mpi_test(NAME src...): default execution space, run at 1 and 2 ranks, 1 thread each.
function(amphora_mpi_test name)
  if(AMPHORA_TEST_UNITY)
    _amphora_bundle(mpi ${ARGN})
    return()
  endif()
  _amphora_test_executable(${name} Kokkos::DefaultExecutionSpace ${ARGN})
  _amphora_register_mpi_tests(${name} ${name})
endfunction()

# amphora_test_bundles(): with AMPHORA_TEST_UNITY, the bundles' executables and tests
# (unity_<kind>...), called once all tests are declared.
function(amphora_test_bundles)
  get_property(kinds GLOBAL PROPERTY AMPHORA_TEST_BUNDLES)
  if(NOT kinds)
    return()
  endif()
  list(REMOVE_DUPLICATES kinds)
  foreach(kind IN LISTS kinds)
    get_property(sources GLOBAL PROPERTY AMPHORA_TEST_BUNDLE_${kind})
    set(labels "")
    if(kind STREQUAL "backend_slow")
      set(labels slow)
    endif()
    if(kind MATCHES "^backend")
      foreach(backend IN LISTS AMPHORA_TEST_BACKENDS)
        string(TOLOWER ${backend} lower)
        set(exe tests_unity_${kind}_${lower})
        _amphora_test_executable(${exe} Kokkos::${backend} ${sources})
        _amphora_register_backend_tests(unity_${kind} ${exe} ${backend} "${labels}")
      endforeach()
    else()
      set(exe tests_unity_${kind})
      if(kind STREQUAL "host")
        _amphora_test_executable(${exe} Kokkos::DefaultHostExecutionSpace ${sources})
        _amphora_register_host_test(unity_${kind} ${exe} "")
      else()
        _amphora_test_executable(${exe} Kokkos::DefaultExecutionSpace ${sources})
        _amphora_register_mpi_tests(unity_${kind} ${exe})
      endif()
    endif()
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
