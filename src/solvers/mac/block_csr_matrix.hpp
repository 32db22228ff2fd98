#pragma once
// This block's rows of a matrix whose columns are the unknowns of a tall-cell grid split over
// ranks (a tall-cell matrix, or a transfer from another level's unknowns), as an operator:
// columns of this block's unknowns first, then those of the ghost ring, whose values arrive
// through the lattice ghost exchange (every unknown is carried by one lattice cell,
// mesh::mac::TallCellGrid::unknown_cells), so no communication pattern of its own is needed. On one
// block it is the plain CSR product.
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

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
  int ghosts = 0;   ///< columns of the ghost ring
  DeviceCsrMatrix<MemSpace> local;  ///< columns [0, columns): this block's, then the ring's
  Vector inverse_diagonal;
  kernels::mac::MacGrid grid;
  mesh::mac::LatticeGhostExchange halo;
  Kokkos::View<int*, MemSpace> own_cells, ghost_cells;  ///< lattice cells carrying the unknowns
  Vector lattice, extended;                             ///< scratch of apply()

  BlockCsrMatrix() = default;
  /// M: this block's rows with global columns, the unknowns of T (assemble_tall_cell_matrix:
  /// T's own rows; a level transfer: another grid's, with_inverse_diagonal false as it has
  /// none).
  BlockCsrMatrix(const CsrMatrix& M, const mesh::mac::TallCellGrid& T,
                 bool with_inverse_diagonal = true)
      : BlockCsrMatrix(CsrMatrix(M), T, with_inverse_diagonal) {}
  /// The same, keeping M's arrays where it can (DeviceCsrMatrix).
  BlockCsrMatrix(CsrMatrix&& M, const mesh::mac::TallCellGrid& T, bool with_inverse_diagonal)
      : grid(T.grid()), halo(T.block()) {
    n = static_cast<int>(M.n);
    columns = static_cast<int>(T.unknowns());
    if (!halo.block()
             .split()) {  // one block: global columns are local ones, apply() the plain product
      local = DeviceCsrMatrix<MemSpace>(std::move(M), with_inverse_diagonal);
      inverse_diagonal = local.inverse_diagonal;
      return;
    }
    CsrMatrix C = std::move(M);
    const long first = T.first_unknown();
    std::unordered_map<long, int> ring;  // global unknown -> lattice cell
    for (const auto& [u, cell] : T.ring_unknown_cells()) ring.emplace(u, cell);
    std::unordered_map<long, int> column;  // global unknown of the ring -> local column
    std::vector<int> ghost;
    for (auto& c : C.cols) {
      const long g = c;
      if (g >= first && g < first + columns) {
        c = static_cast<int>(g - first);
        continue;
      }
      auto it = column.find(g);
      if (it == column.end()) {
        const auto r = ring.find(g);
        if (r == ring.end())
          throw std::logic_error("BlockCsrMatrix: a column is neither this block's nor its ring's");
        it = column.emplace(g, columns + static_cast<int>(ghost.size())).first;
        ghost.push_back(r->second);
      }
      c = it->second;
    }
    ghosts = static_cast<int>(ghost.size());
    local = DeviceCsrMatrix<MemSpace>(std::move(C), with_inverse_diagonal);
    inverse_diagonal = local.inverse_diagonal;
    own_cells = kernels::to_view<MemSpace>(T.unknown_cells(), "amphora::block_csr::own_cells");
    ghost_cells = kernels::to_view<MemSpace>(ghost, "amphora::block_csr::ghost_cells");
    extended = Vector("amphora::block_csr::extended", columns + ghosts);
    lattice = Vector("amphora::block_csr::lattice", grid.padded_size());
  }

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
