#pragma once
// MPI and Kokkos started together and stopped in reverse order (MPI first, so Kokkos sees the
// rank's environment; Kokkos finalised before MPI so no View outlives MPI's buffers).
#include <memory>

#include "base/communicator.hpp"

namespace amphora {

class Environment {
 public:
  Environment(int& argc, char**& argv);
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

 private:
  void start_kokkos(int& argc, char**& argv);
  bool owns_mpi_ = false;
  struct KokkosGuard;
  std::unique_ptr<KokkosGuard> kokkos_;
};

}  // namespace amphora
