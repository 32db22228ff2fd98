#pragma once
// A thin view of an MPI communicator with the few collectives amphora uses everywhere.
#include <mpi.h>

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace amphora {

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

  /// Every rank's `local`, concatenated in rank order, on every rank.
  template <class T>
  std::vector<T> allgatherv(const std::vector<T>& local) const {
    std::vector<int> counts, displs;
    const int total = layout(static_cast<int>(local.size()), counts, displs, -1);
    std::vector<T> out(static_cast<size_t>(total));
    MPI_Allgatherv(local.data(), static_cast<int>(local.size()), mpi_type<T>(), out.data(),
                   counts.data(), displs.data(), mpi_type<T>(), comm_);
    return out;
  }
  /// Every rank's `local`, concatenated in rank order, on `root` (empty elsewhere).
  template <class T>
  std::vector<T> gatherv(const std::vector<T>& local, int root = 0) const {
    std::vector<int> counts, displs;
    const int total = layout(static_cast<int>(local.size()), counts, displs, root);
    std::vector<T> out(rank_ == root ? static_cast<size_t>(total) : 0);
    MPI_Gatherv(local.data(), static_cast<int>(local.size()), mpi_type<T>(), out.data(),
                counts.data(), displs.data(), mpi_type<T>(), root, comm_);
    return out;
  }

 private:
  template <class T>
  static MPI_Datatype mpi_type() {
    if constexpr (std::is_same_v<T, double>)
      return MPI_DOUBLE;
    else if constexpr (std::is_same_v<T, int>)
      return MPI_INT;
    else if constexpr (std::is_same_v<T, char>)
      return MPI_CHAR;
    else {
      static_assert(std::is_same_v<T, std::int64_t>, "unsupported element type");
      return MPI_INT64_T;
    }
  }
  /// Counts and displacements of every rank's `n` (on all ranks, or only on `root` >= 0).
  int layout(int n, std::vector<int>& counts, std::vector<int>& displs, int root) const;

  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace amphora
