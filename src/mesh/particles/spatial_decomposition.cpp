#include "mesh/particles/spatial_decomposition.hpp"

#include <algorithm>
#include <cmath>

namespace amphora::mesh::particles {

namespace {
Index3 cells_of(const std::array<double, 3>& lo, const std::array<double, 3>& hi, double w,
                const DecompositionLayout& layout) {
  Index3 n;
  for (int d = 0; d < 3; ++d)
    n[d] =
        layout.cells[d] > 0 ? layout.cells[d] : std::max(1, static_cast<int>((hi[d] - lo[d]) / w));
  return n;
}

/// Cells a block needs along the split directions to be at least w wide.
int min_block_cells(const std::array<double, 3>& lo, const std::array<double, 3>& hi, double w,
                    const Index3& cells, const DecompositionLayout& layout) {
  int m = 1;
  for (int d = 0; d < 3; ++d)
    if (layout.split[d] && layout.cells[d] > 0)
      m = std::max(m, static_cast<int>(std::ceil(w / ((hi[d] - lo[d]) / cells[d]) - 1e-9)));
  return m;
}
}  // namespace

SpatialDecomposition::SpatialDecomposition(const std::array<double, 3>& lo,
                                           const std::array<double, 3>& hi, double min_width,
                                           const Communicator& comm,
                                           const std::array<bool, 3>& periodic,
                                           const DecompositionLayout& layout)
    : comm_(comm),
      lo_(lo),
      hi_(hi),
      boxes_(cells_of(lo, hi, min_width, layout), periodic, comm.size(),
             min_block_cells(lo, hi, min_width, cells_of(lo, hi, min_width, layout), layout),
             layout.split) {
  for (int d = 0; d < 3; ++d) h_[d] = (hi_[d] - lo_[d]) / boxes_.global_cells()[d];
}

std::array<double, 3> SpatialDecomposition::lo(int rank) const {
  const Box b = boxes_.box(rank);
  return {lo_[0] + b.lo[0] * h_[0], lo_[1] + b.lo[1] * h_[1], lo_[2] + b.lo[2] * h_[2]};
}

std::array<double, 3> SpatialDecomposition::hi(int rank) const {
  const Box b = boxes_.box(rank);
  std::array<double, 3> h;
  for (int d = 0; d < 3; ++d)
    h[d] = b.hi[d] == boxes_.global_cells()[d] ? hi_[d] : lo_[d] + b.hi[d] * h_[d];
  return h;
}

double SpatialDecomposition::image_shift(int d, int side) const {
  if (!periodic(d)) return 0.0;
  const int r = comm_.rank();
  if (side == 0) return hi(r)[d] == hi_[d] ? hi_[d] - lo_[d] : 0.0;
  return lo(r)[d] == lo_[d] ? lo_[d] - hi_[d] : 0.0;
}

PeriodicWrap SpatialDecomposition::wrap() const {
  PeriodicWrap w;
  for (int d = 0; d < 3; ++d) {
    w.lo[d] = lo_[d];
    w.length[d] = hi_[d] - lo_[d];
    w.periodic[d] = periodic(d);
  }
  return w;
}

int SpatialDecomposition::owner(const double x[3]) const {
  Index3 c;
  for (int d = 0; d < 3; ++d) {
    const int n = boxes_.global_cells()[d];
    int cell = static_cast<int>(std::floor((x[d] - lo_[d]) / h_[d]));
    cell = cell < 0 ? 0 : (cell >= n ? n - 1 : cell);
    // Which block holds this cell (balanced split: the first n mod p blocks are one longer).
    const int p = boxes_.blocks()[d], base = n / p, extra = n % p;
    const int long_cells = extra * (base + 1);
    c[d] = cell < long_cells ? cell / (base + 1) : extra + (cell - long_cells) / base;
  }
  return boxes_.rank_of(c);
}

std::vector<double> SpatialDecomposition::exchange_all(
    const std::vector<std::vector<double>>& buffers) const {
  const int p = comm_.size();
  std::vector<int> send_counts(p), recv_counts(p), send_displs(p), recv_displs(p);
  std::vector<double> send;
  for (int r = 0; r < p; ++r) {
    send_displs[r] = static_cast<int>(send.size());
    send_counts[r] = static_cast<int>(buffers[r].size());
    send.insert(send.end(), buffers[r].begin(), buffers[r].end());
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm_.get());
  int total = 0;
  for (int r = 0; r < p; ++r) {
    recv_displs[r] = total;
    total += recv_counts[r];
  }
  std::vector<double> recv(static_cast<size_t>(total));
  MPI_Alltoallv(send.data(), send_counts.data(), send_displs.data(), MPI_DOUBLE, recv.data(),
                recv_counts.data(), recv_displs.data(), MPI_DOUBLE, comm_.get());
  return recv;
}

std::vector<double> SpatialDecomposition::exchange_face(int d, int side,
                                                        const std::vector<double>& out) const {
  const int to = neighbor(d, side), from = neighbor(d, 1 - side);
  const int tag = 200 + 2 * d + side;
  int n_out = static_cast<int>(out.size()), n_in = 0;
  MPI_Sendrecv(&n_out, 1, MPI_INT, to >= 0 ? to : MPI_PROC_NULL, tag, &n_in, 1, MPI_INT,
               from >= 0 ? from : MPI_PROC_NULL, tag, comm_.get(), MPI_STATUS_IGNORE);
  std::vector<double> in(static_cast<size_t>(from >= 0 ? n_in : 0));
  exchange_face(d, side, out.data(), n_out, in.data(), static_cast<int>(in.size()));
  return in;
}

void SpatialDecomposition::exchange_face(int d, int side, const double* out, int n_out, double* in,
                                         int n_in) const {
  const int to = neighbor(d, side), from = neighbor(d, 1 - side);
  const int tag = 220 + 2 * d + side;
  MPI_Sendrecv(out, to >= 0 ? n_out : 0, MPI_DOUBLE, to >= 0 ? to : MPI_PROC_NULL, tag, in,
               from >= 0 ? n_in : 0, MPI_DOUBLE, from >= 0 ? from : MPI_PROC_NULL, tag, comm_.get(),
               MPI_STATUS_IGNORE);
}

}  // namespace amphora::mesh::particles
