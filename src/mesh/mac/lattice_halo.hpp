#pragma once
// A block of a MAC grid split horizontally over ranks (x and z; columns stay whole), and the
// exchange of the ghost layer of its padded-lattice fields with the neighbouring blocks: the x
// faces first (the block's own planes), then the z faces including the x ghosts just received,
// so the edge ghosts a 3x3x3 neighbourhood reads are filled too; and a copy of a field on the
// block widened by several cells (WideGrid) for stencils deeper than the ghost layer. Any value
// type (cell types, float conductances, vectors); packed on the device, staged through the host.
#include <mpi.h>

#include <array>
#include <string>

#include "mesh/box_decomposition.hpp"
#include "kernels/mac/mac_grid.hpp"

namespace amphora::mesh::mac {

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
  /// The faces that end the domain (no neighbour there).
  kernels::mac::MacEdges edges() const {
    kernels::mac::MacEdges e;
    for (int f = 0; f < 6; ++f) e[f] = neighbours[f] < 0;
    return e;
  }
  /// The box faces of the block: `neighbour` towards another block, `outer` elsewhere.
  kernels::mac::MacBoxBoundaries faces(const kernels::mac::MacBoxBoundaries& outer) const {
    kernels::mac::MacBoxBoundaries f = outer;
    for (int s = 0; s < 6; ++s)
      if (neighbours[s] >= 0) f[s] = kernels::mac::MacBoundary::neighbour;
    return f;
  }
};

/// A block's grid widened by `width` cells towards each neighbouring block (the faces of the
/// global box stay where they are), for stencils wider than the ghost layer (semi-Lagrangian
/// traces): block cell (i, j, k) is wide cell (i + offset[0], j, k + offset[2]).
struct WideGrid {
  kernels::mac::MacGrid grid;
  int offset[3] = {0, 0, 0};
  int width = 0;
};

class LatticeGhostExchange {
 public:
  /// Padded indices of a box of lattice entries, x fastest (public, as shift() is: CUDA names a
  /// lambda's captured types outside the class).
  struct Region {
    kernels::mac::MacGrid g;
    int i0, ni, j0, nj, k0, nk;
    KOKKOS_INLINE_FUNCTION int operator()(int m) const {
      const int r = m / ni;
      return g.index(i0 + m % ni, j0 + r % nj, k0 + r / nj);
    }
    int size() const { return ni * nj * nk; }
  };

 public:
  LatticeGhostExchange() = default;
  explicit LatticeGhostExchange(const MacBlock& block) : block_(block) {}
  const MacBlock& block() const { return block_; }

  /// Fills the ghost cells of v (padded lattice of g) beyond the block's neighbour faces.
  template <class ExecSpace, class View>
  void exchange(const ExecSpace& exec, const kernels::mac::MacGrid& g, const View& v) const {
    if (!block_.split()) return;
    // x planes: rows j = -1..ny of planes k = 0..nz-1; z planes: i = -1..nx, j = -1..ny
    for (int side = 0; side < 2; ++side) {
      const int out = side == 0 ? 0 : g.nx - 1, in = side == 0 ? g.nx : -1;
      shift(exec, v, Region{g, out, 1, -1, g.ny + 2, 0, g.nz}, v,
            Region{g, in, 1, -1, g.ny + 2, 0, g.nz}, 0, side);
    }
    for (int side = 0; side < 2; ++side) {
      const int out = side == 0 ? 0 : g.nz - 1, in = side == 0 ? g.nz : -1;
      shift(exec, v, Region{g, -1, g.nx + 2, -1, g.ny + 2, out, 1}, v,
            Region{g, -1, g.nx + 2, -1, g.ny + 2, in, 1}, 2, side);
    }
    exec.fence();
  }

  /// The block's grid g widened by `width` cells towards its neighbours (width <= the block's
  /// extent in each split direction).
  WideGrid widened(const kernels::mac::MacGrid& g, int width) const {
    WideGrid w;
    w.width = width;
    w.grid = g;
    const int lo_x = block_.neighbours[0] >= 0 ? width : 0,
              lo_z = block_.neighbours[4] >= 0 ? width : 0;
    w.offset[0] = lo_x;
    w.offset[2] = lo_z;
    w.grid.nx = g.nx + lo_x + (block_.neighbours[1] >= 0 ? width : 0);
    w.grid.nz = g.nz + lo_z + (block_.neighbours[5] >= 0 ? width : 0);
    w.grid.origin[0] = g.origin[0] - lo_x * g.h;
    w.grid.origin[2] = g.origin[2] - lo_z * g.h;
    return w;
  }

  /// wide = v (the block's whole padded lattice) placed in the widened grid, the widening filled
  /// from the neighbouring blocks' cells (x first, then z including the x widening, so corners
  /// come from the diagonal neighbours).
  template <class ExecSpace, class View, class WideView>
  void fill_widened(const ExecSpace& exec, const kernels::mac::MacGrid& g, const View& v,
                    const WideGrid& W, const WideView& wide) const {
    const kernels::mac::MacGrid wg = W.grid;
    const int oi = W.offset[0], ok = W.offset[2], n = W.width;
    Kokkos::parallel_for(
        "amphora::lattice_halo::widen",
        Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0},
                                                          {g.nz + 2, g.ny + 2, g.nx + 2}),
        KOKKOS_LAMBDA(int k, int j, int i) {  // padded (i, j, k) - 1: the ghost layer too
          wide(wg.index(i - 1 + oi, j - 1, k - 1 + ok)) = v(g.index(i - 1, j - 1, k - 1));
        });
    if (!block_.split()) return;
    // towards -x the first n planes go, from +x the neighbour's first n arrive beyond the last
    shift(exec, v, Region{g, 0, n, -1, g.ny + 2, 0, g.nz}, wide,
          Region{wg, oi + g.nx, n, -1, g.ny + 2, ok, g.nz}, 0, 0);
    shift(exec, v, Region{g, g.nx - n, n, -1, g.ny + 2, 0, g.nz}, wide,
          Region{wg, 0, n, -1, g.ny + 2, ok, g.nz}, 0, 1);
    shift(exec, wide, Region{wg, -1, wg.nx + 2, -1, g.ny + 2, ok, n}, wide,
          Region{wg, -1, wg.nx + 2, -1, g.ny + 2, ok + g.nz, n}, 2, 0);
    shift(exec, wide, Region{wg, -1, wg.nx + 2, -1, g.ny + 2, ok + g.nz - n, n}, wide,
          Region{wg, -1, wg.nx + 2, -1, g.ny + 2, 0, n}, 2, 1);
    exec.fence();
  }

 public:  // (CUDA: extended lambdas may not live in private member functions)
  /// Sends `from_region` of `src` to the neighbour across face (d, side) and receives the
  /// opposite neighbour's into `to_region` of `dst` (same sizes on both ends).
  template <class ExecSpace, class Src, class Dst>
  void shift(const ExecSpace& exec, const Src& src, const Region& from_region, const Dst& dst,
             const Region& to_region, int d, int side) const {
    using T = typename Dst::non_const_value_type;
    using Buffer = Kokkos::View<T*, typename Dst::memory_space>;
    const int to = block_.neighbours[2 * d + side], from = block_.neighbours[2 * d + 1 - side];
    if (to < 0 && from < 0) return;
    const int size = from_region.size();
    Buffer send(
        Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::lattice_halo::send")),
        size);
    Buffer recv(
        Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::lattice_halo::recv")),
        size);
    auto send_host = Kokkos::create_mirror_view(send);
    auto recv_host = Kokkos::create_mirror_view(recv);
    if (to >= 0) {
      const Region at = from_region;
      Kokkos::parallel_for(
          "amphora::lattice_halo::pack", kernels::RangePolicy<ExecSpace>(exec, 0, size),
          KOKKOS_LAMBDA(int m) { send(m) = static_cast<T>(src(at(m))); });
      Kokkos::deep_copy(exec, send_host, send);
      exec.fence();
    }
    const int bytes = static_cast<int>(size * sizeof(T));
    MPI_Sendrecv(send_host.data(), to >= 0 ? bytes : 0, MPI_BYTE, to >= 0 ? to : MPI_PROC_NULL,
                 300 + 2 * d + side, recv_host.data(), from >= 0 ? bytes : 0, MPI_BYTE,
                 from >= 0 ? from : MPI_PROC_NULL, 300 + 2 * d + side, block_.comm,
                 MPI_STATUS_IGNORE);
    if (from >= 0) {
      const Region at = to_region;
      Kokkos::deep_copy(exec, recv, recv_host);
      Kokkos::parallel_for(
          "amphora::lattice_halo::unpack", kernels::RangePolicy<ExecSpace>(exec, 0, size),
          KOKKOS_LAMBDA(int m) { dst(at(m)) = recv(m); });
    }
  }

 private:
  MacBlock block_;
};

}  // namespace amphora::mesh::mac
