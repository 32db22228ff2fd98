#include "mesh/hex/distributed_qk_space.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/blas1.hpp"
#include "kernels/spaces.hpp"
#include "mesh/box_decomposition.hpp"

namespace amphora::mesh::hex {

namespace {

constexpr int kGhostTag = 7101, kCompressTag = 7102;

/// Sends `count` doubles at `send` to `dest` and receives `count` into `recv` from `source`
/// (either may be MPI_PROC_NULL), through host buffers when the memory space is a device's.
template <class Send, class Recv>
void exchange_layer(const Communicator& comm, const Send& send, int dest, const Recv& recv,
                    int source, int tag) {
  auto hs = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), send);
  auto hr = Kokkos::create_mirror_view(Kokkos::HostSpace(), recv);
  const int n = static_cast<int>(send.extent(0));
  MPI_Sendrecv(hs.data(), dest == MPI_PROC_NULL ? 0 : n, MPI_DOUBLE, dest, tag, hr.data(),
               source == MPI_PROC_NULL ? 0 : n, MPI_DOUBLE, source, tag, comm.get(),
               MPI_STATUS_IGNORE);
  if (source != MPI_PROC_NULL) Kokkos::deep_copy(recv, hr);
}

}  // namespace

namespace {
/// This rank's cells along the last direction: the foundation's box decomposition, allowed to
/// split that direction only (throws DecompositionError for more ranks than cells).
template <int dim>
Box slab_of(const StructuredHexMesh<dim>& m, const Communicator& comm) {
  Index3 cells{1, 1, 1};
  std::array<bool, 3> periodic{false, false, false}, split{false, false, false};
  for (int d = 0; d < dim; ++d) {
    cells[d] = m.cells[d];
    periodic[d] = m.periodic(d);
  }
  split[dim - 1] = true;
  return BoxDecomposition(cells, periodic, comm.size(), 1, split).box(comm.rank());
}
}  // namespace

template <int dim, class ExecSpace>
DistributedQkSpace<dim, ExecSpace>::DistributedQkSpace(const StructuredHexMesh<dim>& global,
                                                       int degree, const Communicator& comm)
    : DistributedQkSpace(global, degree, comm, slab_of(global, comm)) {}

template <int dim, class ExecSpace>
DistributedQkSpace<dim, ExecSpace>::DistributedQkSpace(const StructuredHexMesh<dim>& global,
                                                       int degree, const Communicator& comm,
                                                       const Box& slab)
    : DistributedQkSpace(global, degree, comm, slab.lo[dim - 1], slab.hi[dim - 1]) {}

template <int dim, class ExecSpace>
DistributedQkSpace<dim, ExecSpace>::DistributedQkSpace(const StructuredHexMesh<dim>& global,
                                                       int degree, const Communicator& comm,
                                                       int first_cell, int end_cell)
    : global_(global), comm_(comm), first_cell_(first_cell), end_cell_(end_cell) {
  global.validate();
  constexpr int s = dim - 1;  // the split direction
  const int ranks = comm.size(), r = comm.rank(), n = global.cells[s];
  // Every rank checks every slab, so a bad partition throws on all ranks alike.
  const std::vector<int> bounds = comm.allgatherv(std::vector<int>{first_cell, end_cell});
  bool tiles = bounds.front() == 0 && bounds.back() == n;
  for (int q = 0; q < ranks; ++q)
    tiles = tiles && bounds[2 * q] < bounds[2 * q + 1] &&
            (q == 0 || bounds[2 * q] == bounds[2 * q - 1]);
  if (!tiles)
    throw std::invalid_argument(
        "DistributedQkSpace: the ranks' slabs (rank " + std::to_string(r) + ": cells [" +
        std::to_string(first_cell) + ", " + std::to_string(end_cell) + ")) do not tile the " +
        std::to_string(n) + " cells along the last direction in rank order, each non-empty");

  StructuredHexMesh<dim> slab = global;
  if (ranks > 1) {
    const double h = (global.upper[s] - global.lower[s]) / n;
    slab.cells[s] = end_cell - first_cell_;
    slab.lower[s] = first_cell_ == 0 ? global.lower[s] : global.lower[s] + h * first_cell_;
    slab.upper[s] = end_cell == n ? global.upper[s] : global.lower[s] + h * end_cell;
    // Faces between slabs are natural: each side adds its cells' share, compress_add sums them.
    const bool periodic = global.periodic(s);
    if (periodic || r > 0) slab.faces[2 * s] = FaceCondition::interface;
    if (periodic || r < ranks - 1) slab.faces[2 * s + 1] = FaceCondition::interface;
    prev_ = r > 0 ? r - 1 : (periodic ? ranks - 1 : MPI_PROC_NULL);
    next_ = r < ranks - 1 ? r + 1 : (periodic ? 0 : MPI_PROC_NULL);
  } else {
    prev_ = next_ = MPI_PROC_NULL;
  }
  local_ = std::make_unique<Space>(slab, degree);

  const auto& lat = local_->lattice();
  layer_ = 1;
  for (int d = 0; d < s; ++d) layer_ *= lat.dofs[d];
  n_owned_ = local_->n_dofs() - (next_ != MPI_PROC_NULL ? layer_ : 0);

  // Constrained DoFs of the bottom layer (Dirichlet faces of the other directions).
  free_bottom_ = Vector("amphora::DistributedQkSpace::free_bottom", layer_);
  auto fh = Kokkos::create_mirror_view(free_bottom_);
  for (long i = 0; i < layer_; ++i) fh(i) = 1.0;
  auto ch = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), local_->constrained_dofs());
  for (std::size_t a = 0; a < ch.extent(0); ++a)
    if (ch(a) < layer_) fh(ch(a)) = 0.0;
  Kokkos::deep_copy(free_bottom_, fh);
  received_ = Vector(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::DistributedQkSpace::received"),
      layer_);
}

template <int dim, class ExecSpace>
bool DistributedQkSpace<dim, ExecSpace>::can_coarsen() const {
  bool even = first_cell_ % 2 == 0 && end_cell_ % 2 == 0;
  for (int d = 0; d < dim; ++d) even = even && global_.cells[d] % 2 == 0;
  return !comm_.any(!even);
}

template <int dim, class ExecSpace>
std::unique_ptr<DistributedQkSpace<dim, ExecSpace>> DistributedQkSpace<dim, ExecSpace>::coarsened(
    int degree) const {
  if (first_cell_ % 2 != 0 || end_cell_ % 2 != 0)
    throw std::invalid_argument("DistributedQkSpace: slab [" + std::to_string(first_cell_) + ", " +
                                std::to_string(end_cell_) +
                                ") has an odd boundary; cannot coarsen");
  return std::make_unique<DistributedQkSpace>(global_.coarsened(), degree, comm_, first_cell_ / 2,
                                              end_cell_ / 2);
}

template <int dim, class ExecSpace>
std::unique_ptr<DistributedQkSpace<dim, ExecSpace>> DistributedQkSpace<dim, ExecSpace>::with_degree(
    int degree) const {
  return std::make_unique<DistributedQkSpace>(global_, degree, comm_, first_cell_, end_cell_);
}

template <int dim, class ExecSpace>
Kokkos::View<long*, typename ExecSpace::memory_space>
DistributedQkSpace<dim, ExecSpace>::global_indices() const {
  Kokkos::View<long*, memory_space> g("amphora::DistributedQkSpace::global_indices", n_local());
  auto h = Kokkos::create_mirror_view(g);
  for (long i = 0; i < n_local(); ++i) h(i) = global_index(i);
  Kokkos::deep_copy(g, h);
  return g;
}

template <int dim, class ExecSpace>
long DistributedQkSpace<dim, ExecSpace>::n_global() const {
  return comm_.sum(static_cast<long long>(n_owned_));
}

template <int dim, class ExecSpace>
long DistributedQkSpace<dim, ExecSpace>::global_index(long i) const {
  constexpr int s = dim - 1;
  const auto& lat = local_->lattice();
  const int k = lat.degree;
  long rest = i;
  long g = 0, stride = 1;
  for (int d = 0; d < s; ++d) {
    g += (rest % lat.dofs[d]) * stride;
    stride *= lat.dofs[d];
    rest /= lat.dofs[d];
  }
  long layer = rest + static_cast<long>(first_cell_) * k;
  const long layers = static_cast<long>(global_.cells[s]) * k + (global_.periodic(s) ? 0 : 1);
  if (layer >= layers) layer -= layers;  // the periodic wrap
  return g + layer * stride;
}

template <int dim, class ExecSpace>
void DistributedQkSpace<dim, ExecSpace>::update_ghosts(const ExecSpace& exec, const Vector& x,
                                                       int components) const {
  if (prev_ == MPI_PROC_NULL && next_ == MPI_PROC_NULL) return;
  exec.fence();
  const long n = n_local();
  for (int c = 0; c < components; ++c) {
    const long base = c * n;
    const auto bottom = Kokkos::subview(x, Kokkos::make_pair(base, base + layer_));
    const auto top = Kokkos::subview(x, Kokkos::make_pair(base + n - layer_, base + n));
    exchange_layer(comm_, bottom, prev_, top, next_, kGhostTag + 16 * c);
  }
}

template <int dim, class ExecSpace>
void DistributedQkSpace<dim, ExecSpace>::compress_add(const ExecSpace& exec, const Vector& y,
                                                      int components, int constrained) const {
  if (prev_ == MPI_PROC_NULL && next_ == MPI_PROC_NULL) return;
  exec.fence();
  const long n = n_local();
  const Vector received = received_;
  const Vector free = free_bottom_;
  for (int c = 0; c < components; ++c) {
    const long base = c * n;
    const auto top = Kokkos::subview(y, Kokkos::make_pair(base + n - layer_, base + n));
    exchange_layer(comm_, top, next_, received, prev_, kCompressTag + 16 * c);
    if (prev_ == MPI_PROC_NULL) continue;
    const bool all_free = constrained >= 0 && c >= constrained;
    Kokkos::parallel_for(
        "amphora::DistributedQkSpace::compress_add",
        kernels::RangePolicy<ExecSpace>(exec, 0, layer_),
        KOKKOS_LAMBDA(long i) { y(base + i) += (all_free ? 1.0 : free(i)) * received(i); });
  }
  exec.fence();
}

template <int dim, class ExecSpace>
std::vector<double> DistributedQkSpace<dim, ExecSpace>::gather(const Vector& x,
                                                               int components) const {
  const auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x);
  std::vector<double> whole;
  for (int c = 0; c < components; ++c) {
    const double* owned_c = h.data() + c * n_local();
    const std::vector<double> all =
        comm_.allgatherv(std::vector<double>(owned_c, owned_c + n_owned_));
    whole.insert(whole.end(), all.begin(), all.end());
  }
  return whole;
}

template <int dim, class ExecSpace>
std::vector<double> DistributedQkSpace<dim, ExecSpace>::local_entries(
    const std::vector<double>& whole, int components) const {
  const long n = n_local(), total = static_cast<long>(whole.size()) / components;
  std::vector<double> local(static_cast<std::size_t>(n) * components);
  for (long i = 0; i < n; ++i) {
    const long g = global_index(i);
    for (int c = 0; c < components; ++c) local[c * n + i] = whole[c * total + g];
  }
  return local;
}

template <int dim, class ExecSpace>
void DistributedQkSpace<dim, ExecSpace>::scatter(const std::vector<double>& whole, const Vector& x,
                                                 int components) const {
  const std::vector<double> local = local_entries(whole, components);
  Kokkos::deep_copy(x, Kokkos::View<const double*, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>(
                           local.data(), local.size()));
}

template <int dim, class ExecSpace>
double DistributedQkSpace<dim, ExecSpace>::dot(const ExecSpace& exec, const Vector& x,
                                               const Vector& y, int components) const {
  double local = 0.0;
  if (n_owned_ == n_local()) {  // no ghost layer: one pass over the blocks
    const Kokkos::pair<long, long> all(0, components * n_local());
    local = kernels::blas1::dot(exec, Kokkos::subview(x, all), Kokkos::subview(y, all));
  } else {
    for (int c = 0; c < components; ++c)
      local +=
          kernels::blas1::dot(exec, Kokkos::subview(x, owned(c)), Kokkos::subview(y, owned(c)));
  }
  return comm_.sum(local);
}

template <int dim, class ExecSpace>
double DistributedQkSpace<dim, ExecSpace>::fused_cg_update(const ExecSpace& exec, double alpha,
                                                           const Vector& p, const Vector& q,
                                                           const Vector& x, const Vector& r,
                                                           int components) const {
  if (n_owned_ == n_local()) {  // no ghost layer: one pass over the blocks
    const Kokkos::pair<long, long> o(0, components * n_local());
    return comm_.sum(kernels::blas1::cg_update(exec, alpha, Kokkos::subview(p, o),
                                               Kokkos::subview(q, o), Kokkos::subview(x, o),
                                               Kokkos::subview(r, o)));
  }
  double local = 0.0;
  for (int c = 0; c < components; ++c) {
    const auto o = owned(c);
    local += kernels::blas1::cg_update(exec, alpha, Kokkos::subview(p, o), Kokkos::subview(q, o),
                                       Kokkos::subview(x, o), Kokkos::subview(r, o));
  }
  return comm_.sum(local);
}

#define AMPHORA_DISTRIBUTED_QK_SPACE(E)    \
  template class DistributedQkSpace<2, E>; \
  template class DistributedQkSpace<3, E>;
AMPHORA_IF_SERIAL(AMPHORA_DISTRIBUTED_QK_SPACE(Kokkos::Serial))
AMPHORA_IF_OPENMP(AMPHORA_DISTRIBUTED_QK_SPACE(Kokkos::OpenMP))
AMPHORA_IF_CUDA(AMPHORA_DISTRIBUTED_QK_SPACE(Kokkos::Cuda))

}  // namespace amphora::mesh::hex
