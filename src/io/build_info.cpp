#include "io/build_info.hpp"

#include <HYPRE_config.h>
#include <hdf5.h>
#include <mpi.h>

#include <Eigen/Core>
#include <toml++/impl/version.h>  // the version only: toml++ itself is compiled in io/scene.cpp

#include "amphora/build_info.hpp"
#include "kernels/spaces.hpp"

namespace amphora::io {

std::vector<std::pair<std::string, std::string>> build_info() {
  std::vector<std::pair<std::string, std::string>> rows;
  rows.emplace_back("amphora", AMPHORA_VERSION);
  rows.emplace_back("git revision", AMPHORA_GIT_REVISION);
#ifdef AMPHORA_CUDA_FAST_COMPILE
  rows.emplace_back("build type", std::string(AMPHORA_BUILD_TYPE) +
                                      " (cuda-check: device -Ofc max, host -O0; not for timing)");
#else
  rows.emplace_back("build type", AMPHORA_BUILD_TYPE);
#endif
  rows.emplace_back("compiler", AMPHORA_CXX_COMPILER);
  const int kv = KOKKOS_VERSION;
  rows.emplace_back("Kokkos", std::to_string(kv / 10000) + "." + std::to_string(kv / 100 % 100) +
                                  "." + std::to_string(kv % 100));
  rows.emplace_back("Kokkos backends", kernels::enabled_backends());
  rows.emplace_back("default execution space", kernels::DefaultExecSpace::name());
  rows.emplace_back("threads", std::to_string(kernels::DefaultExecSpace().concurrency()));
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  rows.emplace_back("MPI ranks", std::to_string(size));
  char mpi[MPI_MAX_LIBRARY_VERSION_STRING];
  int len = 0;
  MPI_Get_library_version(mpi, &len);
  std::string mpi_version(mpi, static_cast<size_t>(len));
  if (auto nl = mpi_version.find_first_of(",\n"); nl != std::string::npos) mpi_version.resize(nl);
  rows.emplace_back("MPI library", mpi_version);
  unsigned maj = 0, min = 0, rel = 0;
  H5get_libversion(&maj, &min, &rel);
  rows.emplace_back("HDF5", std::to_string(maj) + "." + std::to_string(min) + "." +
                                std::to_string(rel) + " (parallel)");
  rows.emplace_back("hypre", HYPRE_RELEASE_VERSION);
  rows.emplace_back("Eigen", std::to_string(EIGEN_WORLD_VERSION) + "." +
                                 std::to_string(EIGEN_MAJOR_VERSION) + "." +
                                 std::to_string(EIGEN_MINOR_VERSION));
  rows.emplace_back("toml++", std::to_string(TOML_LIB_MAJOR) + "." +
                                  std::to_string(TOML_LIB_MINOR) + "." +
                                  std::to_string(TOML_LIB_PATCH));
  return rows;
}

}  // namespace amphora::io
