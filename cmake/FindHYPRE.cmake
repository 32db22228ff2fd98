# FindHYPRE
# ---------
# Finds the hypre library (https://github.com/hypre-space/hypre).
#
# Result: target HYPRE::HYPRE, HYPRE_FOUND, HYPRE_VERSION, HYPRE_INCLUDE_DIR, HYPRE_LIBRARY.
# Hints: HYPRE_ROOT (CMake or environment variable).

find_path(HYPRE_INCLUDE_DIR NAMES HYPRE.h
  HINTS ${HYPRE_ROOT} ENV HYPRE_ROOT
  PATH_SUFFIXES include include/hypre hypre)
find_library(HYPRE_LIBRARY NAMES HYPRE
  HINTS ${HYPRE_ROOT} ENV HYPRE_ROOT
  PATH_SUFFIXES lib lib64)

if(HYPRE_INCLUDE_DIR AND EXISTS "${HYPRE_INCLUDE_DIR}/HYPRE_config.h")
  file(STRINGS "${HYPRE_INCLUDE_DIR}/HYPRE_config.h" _hypre_version_line
       REGEX "^#define HYPRE_RELEASE_VERSION")
  string(REGEX MATCH "[0-9]+\\.[0-9]+\\.[0-9]+" HYPRE_VERSION "${_hypre_version_line}")
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(HYPRE
  REQUIRED_VARS HYPRE_LIBRARY HYPRE_INCLUDE_DIR
  VERSION_VAR HYPRE_VERSION)

if(HYPRE_FOUND AND NOT TARGET HYPRE::HYPRE)
  add_library(HYPRE::HYPRE UNKNOWN IMPORTED)
  set_target_properties(HYPRE::HYPRE PROPERTIES
    IMPORTED_LOCATION "${HYPRE_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${HYPRE_INCLUDE_DIR}")
  find_package(MPI REQUIRED COMPONENTS C)
  target_link_libraries(HYPRE::HYPRE INTERFACE MPI::MPI_C)
endif()
mark_as_advanced(HYPRE_INCLUDE_DIR HYPRE_LIBRARY)
