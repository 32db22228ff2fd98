#pragma once
// Versions of amphora and of everything it is built on, for `amphora info` and the
// benchmark context.
#include <string>
#include <utility>
#include <vector>

namespace amphora::io {

/// (name, value) rows: amphora version and revision, compiler, Kokkos version and backends,
/// threads, MPI library and ranks, HDF5, hypre, Eigen, toml++, CLI11. Needs MPI and Kokkos
/// initialised.
std::vector<std::pair<std::string, std::string>> build_info();

}  // namespace amphora::io
