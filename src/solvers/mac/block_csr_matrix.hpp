#pragma once
// This block's rows of a matrix whose columns are the unknowns of a tall-cell grid split over
// ranks (a tall-cell matrix, or a transfer from another level's unknowns), as an operator:
// columns of this block's unknowns first, then the ghost ring's slots, whose values arrive
// through the lattice ghost exchange (every unknown is carried by one lattice cell:
// tall_cell_carriers, kernels::mac::TallCellRing::slot_cell), so no communication pattern of
// its own is needed. On one block it is the plain CSR product.
#include <utility>

#include "mesh/mac/lattice_halo.hpp"
#include "mesh/mac/tall_cell_grid.hpp"
#include "kernels/blas1.hpp"
#include "solvers/device_csr.hpp"

namespace amphora::solvers::mac {

template <class MemSpace>
struct BlockCsrMatrix {
  using Vector = Kokkos::View<double*, MemSpace>;
  int n = 0;        ///< this block's rows
  int columns = 0;  ///< this block's unknowns of the column grid (n for a square matrix)
  int ghosts = 0;   ///< columns of the ghost ring (its slots)
  DeviceCsrMatrix<MemSpace> local;  ///< columns [0, columns): this block's, then the ring's
  Vector inverse_diagonal;
  kernels::mac::MacGrid grid;
  mesh::mac::LatticeGhostExchange halo;
  Kokkos::View<int*, MemSpace> own_cells, ghost_cells;  ///< lattice cells carrying the unknowns
  Vector lattice, extended;                             ///< scratch of apply()

  BlockCsrMatrix() = default;
  /// M: this block's rows of a square matrix over T's unknowns with local columns (this block's
  /// unknowns, then the ring's slots: kernels::mac::TallCellRing), assembled in MemSpace;
  /// carriers: the lattice cell of each of T's unknowns (tall_cell_carriers). No host work.
  BlockCsrMatrix(DeviceCsrMatrix<MemSpace> M, const mesh::mac::TallCellGrid& T,
                 const Kokkos::View<int*, MemSpace>& carriers)
      : local(std::move(M)), grid(T.grid()), halo(T.block()) {
    n = local.n;
    columns = static_cast<int>(T.unknowns());
    inverse_diagonal = local.inverse_diagonal;
    if (!halo.block().split()) return;
    const auto ring = T.map<MemSpace>().ring;
    ghosts = ring.slots;
    own_cells = carriers;
    ghost_cells = ring.slot_cell;
    extended = Vector("amphora::block_csr::extended", columns + ghosts);
    lattice = Vector("amphora::block_csr::lattice", grid.padded_size());
  }

  /// y = A x (x: this block's unknowns of the column grid, y: its rows). Collective on a split
  /// grid.
  template <class ExecSpace, class X, class Y>
  void apply(const ExecSpace& exec, const X& x, const Y& y) const {
    if (!halo.block().split()) {
      local.apply(exec, x, y);
      return;
    }
    const Vector L = lattice, E = extended;
    const auto own = own_cells, ring = ghost_cells;
    const int first_ghost = columns;
    Kokkos::parallel_for(
        "amphora::block_csr::to_lattice", kernels::RangePolicy<ExecSpace>(exec, 0, columns),
        KOKKOS_LAMBDA(int u) {
          L(own(u)) = x(u);
          E(u) = x(u);
        });
    halo.exchange(exec, grid, L);
    Kokkos::parallel_for(
        "amphora::block_csr::from_ring", kernels::RangePolicy<ExecSpace>(exec, 0, ghosts),
        KOKKOS_LAMBDA(int g) { E(first_ghost + g) = L(ring(g)); });
    local.apply(exec, E, y);
  }

  /// r = b - A x. Collective on a split grid.
  template <class ExecSpace, class B, class X, class R>
  void residual(const ExecSpace& exec, const B& b, const X& x, const R& r) const {
    if (!halo.block().split()) {
      solvers::residual_csr(exec, local, b, x, r);
      return;
    }
    apply(exec, x, r);
    kernels::blas1::axpby(exec, 1.0, b, -1.0, r);
  }
};

}  // namespace amphora::solvers::mac
