#include "base/communicator.hpp"

namespace amphora {

Communicator::Communicator(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

namespace {
template <class T>
T allreduce(MPI_Comm comm, T x, MPI_Datatype type, MPI_Op op) {
  T y{};
  MPI_Allreduce(&x, &y, 1, type, op, comm);
  return y;
}
}  // namespace

double Communicator::sum(double x) const { return allreduce(comm_, x, MPI_DOUBLE, MPI_SUM); }
double Communicator::max(double x) const { return allreduce(comm_, x, MPI_DOUBLE, MPI_MAX); }
double Communicator::min(double x) const { return allreduce(comm_, x, MPI_DOUBLE, MPI_MIN); }
long long Communicator::sum(long long x) const {
  return allreduce(comm_, x, MPI_LONG_LONG, MPI_SUM);
}
long long Communicator::max(long long x) const {
  return allreduce(comm_, x, MPI_LONG_LONG, MPI_MAX);
}
bool Communicator::any(bool flag) const {
  return allreduce(comm_, static_cast<int>(flag), MPI_INT, MPI_LOR) != 0;
}
void Communicator::barrier() const { MPI_Barrier(comm_); }

int Communicator::layout(int n, std::vector<int>& counts, std::vector<int>& displs,
                         int root) const {
  counts.assign(size_, 0);
  displs.assign(size_, 0);
  if (root < 0) {
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  } else {
    MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm_);
  }
  int total = 0;
  for (int r = 0; r < size_; ++r) {
    displs[r] = total;
    total += counts[r];
  }
  return total;
}

std::string Communicator::broadcast(const std::string& s, int root) const {
  long long n = static_cast<long long>(s.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, root, comm_);
  std::string out = rank_ == root ? s : std::string(static_cast<size_t>(n), '\0');
  if (n > 0) MPI_Bcast(out.data(), static_cast<int>(n), MPI_CHAR, root, comm_);
  return out;
}

}  // namespace amphora
