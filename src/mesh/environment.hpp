#pragma once
// MPI and Kokkos started together and stopped in reverse order (MPI first, so Kokkos sees the
// rank's environment; Kokkos finalised before MPI so no View outlives MPI's buffers).
#include <mpi.h>

#include <memory>
#include <string>

namespace amphora {

class Environment {
 public:
  Environment(int& argc, char**& argv);
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

 private:
  bool owns_mpi_ = false;
  struct KokkosGuard;
  std::unique_ptr<KokkosGuard> kokkos_;
};

/// Thin view of an MPI communicator with the few collectives amphora uses everywhere.
class Communicator {
 public:
  explicit Communicator(MPI_Comm comm = MPI_COMM_WORLD);
  MPI_Comm get() const { return comm_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }

  double sum(double x) const;
  double max(double x) const;
  double min(double x) const;
  long long sum(long long x) const;
  long long max(long long x) const;
  /// True on every rank if it is true on any rank.
  bool any(bool flag) const;
  void barrier() const;
  /// The string on rank `root`, on every rank.
  std::string broadcast(const std::string& s, int root = 0) const;

 private:
  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace amphora
