#pragma once
// Ghost-layer exchange for cell fields on a BoxDecomposition. Fields are 3D Views with
// `ghost` layers on every side, i fastest (LayoutLeft) as in the MAC and hex layouts. Directions
// are exchanged one after another and each includes the ghosts already filled, so edge and
// corner ghosts arrive too. Buffers are packed on the execution space and staged through host
// memory, so no GPU-aware MPI is assumed.
#include <mpi.h>

#include "kernels/spaces.hpp"
#include "mesh/box_decomposition.hpp"
#include "base/communicator.hpp"

namespace amphora::mesh {

template <class MemSpace>
class HaloExchange {
  static_assert(kernels::is_memory_space_v<MemSpace>,
                "HaloExchange is templated on a memory space");

 public:
  using Field = Kokkos::View<double***, Kokkos::LayoutLeft, MemSpace>;
  using Buffer = Kokkos::View<double*, MemSpace>;

  HaloExchange(const BoxDecomposition& decomposition, const Communicator& comm, int ghost)
      : decomposition_(decomposition),
        comm_(comm),
        ghost_(ghost),
        box_(decomposition.box(comm.rank())) {}

  int ghost() const { return ghost_; }
  const Box& box() const { return box_; }

  /// A field with the local box plus ghost layers, zero-initialised.
  Field allocate(const std::string& label) const {
    return Field(label, box_.extent(0) + 2 * ghost_, box_.extent(1) + 2 * ghost_,
                 box_.extent(2) + 2 * ghost_);
  }

  /// Fills the ghost layers of `field` from the neighbouring blocks (periodic images included);
  /// ghosts at a non-periodic boundary of the global box are left as they are.
  template <class ExecSpace>
  void exchange(const ExecSpace& exec, const Field& field) const {
    for (int d = 0; d < 3; ++d) {
      for (int side = 0; side < 2; ++side) {
        const int to = decomposition_.neighbor(comm_.rank(), d, side);
        const int from = decomposition_.neighbor(comm_.rank(), d, 1 - side);
        if (to < 0 && from < 0) continue;
        // Send the interior slab next to `side`; receive into the ghost slab on the other side.
        const Region send = slab(field, d, side, /*ghost=*/false);
        const Region recv = slab(field, d, 1 - side, /*ghost=*/true);
        Buffer send_buf(Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::halo::send"),
                        send.size());
        Buffer recv_buf(Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::halo::recv"),
                        recv.size());
        auto send_host = Kokkos::create_mirror_view(send_buf);
        if (to >= 0) {
          pack(exec, field, send, send_buf);
          exec.fence();
          Kokkos::deep_copy(send_host, send_buf);
        }
        auto recv_host = Kokkos::create_mirror_view(recv_buf);
        MPI_Sendrecv(send_host.data(), static_cast<int>(send.size()), MPI_DOUBLE,
                     to >= 0 ? to : MPI_PROC_NULL, 100 + 2 * d + side, recv_host.data(),
                     static_cast<int>(recv.size()), MPI_DOUBLE, from >= 0 ? from : MPI_PROC_NULL,
                     100 + 2 * d + side, comm_.get(), MPI_STATUS_IGNORE);
        if (from >= 0) {
          Kokkos::deep_copy(recv_buf, recv_host);
          unpack(exec, field, recv, recv_buf);
        }
      }
    }
    exec.fence();
  }

 public:  // (CUDA: extended lambdas may not live in private member functions)
  struct Region {
    Index3 lo, n;
    size_t size() const { return size_t(n[0]) * n[1] * n[2]; }
  };

  /// The slab of thickness `ghost` next to face (d, side): interior cells, or the ghost layer.
  Region slab(const Field& f, int d, int side, bool ghost_layer) const {
    Region r;
    for (int e = 0; e < 3; ++e) {
      r.lo[e] = 0;
      r.n[e] = static_cast<int>(f.extent(e));
    }
    const int n_interior = box_.extent(d);
    r.n[d] = ghost_;
    if (side == 0) {
      r.lo[d] = ghost_layer ? 0 : ghost_;
    } else {
      r.lo[d] = ghost_layer ? ghost_ + n_interior : n_interior;
    }
    return r;
  }

  template <class ExecSpace>
  static void pack(const ExecSpace& exec, const Field& f, const Region& r, const Buffer& buf) {
    // Plain ints are captured (not std::array) so the lambda is device-clean.
    const int l0 = r.lo[0], l1 = r.lo[1], l2 = r.lo[2], n0 = r.n[0], n1 = r.n[1];
    Kokkos::parallel_for(
        "amphora::HaloExchange::pack", kernels::RangePolicy<ExecSpace>(exec, 0, int(r.size())),
        KOKKOS_LAMBDA(int idx) {
          const int i = idx % n0, j = (idx / n0) % n1, k = idx / (n0 * n1);
          buf(idx) = f(l0 + i, l1 + j, l2 + k);
        });
  }

  template <class ExecSpace>
  static void unpack(const ExecSpace& exec, const Field& f, const Region& r, const Buffer& buf) {
    const int l0 = r.lo[0], l1 = r.lo[1], l2 = r.lo[2], n0 = r.n[0], n1 = r.n[1];
    Kokkos::parallel_for(
        "amphora::HaloExchange::unpack", kernels::RangePolicy<ExecSpace>(exec, 0, int(r.size())),
        KOKKOS_LAMBDA(int idx) {
          const int i = idx % n0, j = (idx / n0) % n1, k = idx / (n0 * n1);
          f(l0 + i, l1 + j, l2 + k) = buf(idx);
        });
  }

 private:
  BoxDecomposition decomposition_;
  Communicator comm_;
  int ghost_;
  Box box_;
};

}  // namespace amphora::mesh
