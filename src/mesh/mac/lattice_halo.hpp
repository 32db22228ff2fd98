#pragma once
// A block of a MAC grid split horizontally over ranks (x and z; columns stay whole), and the
// exchange of the ghost layer of its padded-lattice fields with the neighbouring blocks: the x
// faces first (the block's own planes), then the z faces including the x ghosts just received,
// so the edge ghosts a 3x3x3 neighbourhood reads are filled too. Any value type (cell types,
// float conductances, vectors); planes are packed on the device and staged through the host.
#include <mpi.h>

#include <array>
#include <string>

#include "mesh/box_decomposition.hpp"
#include "mesh/mac/mac_grid.hpp"

namespace amphora::mesh {

/// Where a block lies: its communicator, its first cell in global indices, and the ranks
/// beyond each box face (-1: a face of the global box). Default: the whole grid on one rank.
struct MacBlock {
  MPI_Comm comm = MPI_COMM_SELF;
  std::array<int, 3> global_lower{0, 0, 0};
  std::array<int, 6> neighbours{-1, -1, -1, -1, -1, -1};  ///< -x, +x, -y, +y, -z, +z

  bool split() const {
    for (const int n : neighbours)
      if (n >= 0) return true;
    return false;
  }
  /// This rank's block of a BoxDecomposition (never split along y).
  static MacBlock of(const BoxDecomposition& dec, MPI_Comm comm, int rank) {
    MacBlock b;
    b.comm = comm;
    const Box box = dec.box(rank);
    for (int d = 0; d < 3; ++d) {
      b.global_lower[d] = box.lo[d];
      for (int side = 0; side < 2; ++side) b.neighbours[2 * d + side] = dec.neighbor(rank, d, side);
    }
    return b;
  }
  /// The box faces of the block: `neighbour` towards another block, `outer` elsewhere.
  MacBoxBoundaries faces(const MacBoxBoundaries& outer) const {
    MacBoxBoundaries f = outer;
    for (int s = 0; s < 6; ++s)
      if (neighbours[s] >= 0) f[s] = MacBoundary::neighbour;
    return f;
  }
};

class LatticeGhostExchange {
  /// Padded index of entry m of a packed plane normal to d.
  struct PlaneIndex {
    MacGrid g;
    int d, n_a;
    KOKKOS_INLINE_FUNCTION int operator()(int plane, int m) const {
      const int a = m % n_a - 1, b = m / n_a;
      return d == 0 ? g.index(plane, a, b) : g.index(a, b - 1, plane);
    }
  };

 public:
  LatticeGhostExchange() = default;
  explicit LatticeGhostExchange(const MacBlock& block) : block_(block) {}
  const MacBlock& block() const { return block_; }

  /// Fills the ghost cells of v (padded lattice of g) beyond the block's neighbour faces.
  template <class ExecSpace, class View>
  void exchange(const ExecSpace& exec, const MacGrid& g, const View& v) const {
    if (!block_.split()) return;
    exchange_direction(exec, g, v, 0);
    exchange_direction(exec, g, v, 2);
  }

 private:
  template <class ExecSpace, class View>
  void exchange_direction(const ExecSpace& exec, const MacGrid& g, const View& v, int d) const {
    using T = typename View::non_const_value_type;
    using Buffer = Kokkos::View<T*, typename View::memory_space>;
    // x planes: rows j = -1..ny of planes k = 0..nz-1; z planes: i = -1..nx, j = -1..ny
    const int n_a = d == 0 ? g.ny + 2 : g.nx + 2, n_b = d == 0 ? g.nz : g.ny + 2;
    const int size = n_a * n_b, last = d == 0 ? g.nx - 1 : g.nz - 1;
    Buffer send(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::lattice_halo::send")), size);
    Buffer recv(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::lattice_halo::recv")), size);
    auto send_host = Kokkos::create_mirror_view(send);
    auto recv_host = Kokkos::create_mirror_view(recv);
    const PlaneIndex at{g, d, n_a};
    for (int side = 0; side < 2; ++side) {
      const int to = block_.neighbours[2 * d + side], from = block_.neighbours[2 * d + 1 - side];
      if (to < 0 && from < 0) continue;
      const int out_plane = side == 0 ? 0 : last, in_plane = side == 0 ? last + 1 : -1;
      if (to >= 0) {
        Kokkos::parallel_for(
            "amphora::lattice_halo::pack", RangePolicy<ExecSpace>(exec, 0, size),
            KOKKOS_LAMBDA(int m) { send(m) = v(at(out_plane, m)); });
        Kokkos::deep_copy(exec, send_host, send);
        exec.fence();
      }
      MPI_Sendrecv(send_host.data(), to >= 0 ? static_cast<int>(size * sizeof(T)) : 0, MPI_BYTE,
                   to >= 0 ? to : MPI_PROC_NULL, 300 + 2 * d + side, recv_host.data(),
                   from >= 0 ? static_cast<int>(size * sizeof(T)) : 0, MPI_BYTE, from >= 0 ? from : MPI_PROC_NULL,
                   300 + 2 * d + side, block_.comm, MPI_STATUS_IGNORE);
      if (from >= 0) {
        Kokkos::deep_copy(exec, recv, recv_host);
        Kokkos::parallel_for(
            "amphora::lattice_halo::unpack", RangePolicy<ExecSpace>(exec, 0, size),
            KOKKOS_LAMBDA(int m) { v(at(in_plane, m)) = recv(m); });
      }
    }
    exec.fence();
  }

  MacBlock block_;
};

}  // namespace amphora::mesh
