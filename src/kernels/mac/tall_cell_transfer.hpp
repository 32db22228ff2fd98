#pragma once
// The linear-in-height prolongation P of a tall-cell grid and its transpose, as kernels:
// lattice = P y (one work item per lattice cell) and y = P^T lattice (one work item per column,
// so the sums over a tall cell need no atomics), and y = (P^T P)^-1 y (per column: a 2x2 solve
// for the tall samples, identity for the uniform cells): the least-squares fit of a lattice
// function by tall-cell unknowns, which the water module uses to start a pressure solve from the
// last one on a rebuilt grid.
#include "kernels/mac/tall_cell_layout.hpp"

namespace amphora::kernels::mac {

template <class ExecSpace, class MemSpace, class Y, class L>
void tall_cell_prolongate(const ExecSpace& exec, const kernels::mac::TallCellLayout<MemSpace>& T,
                          const Y& y, const L& lattice) {
  const kernels::mac::MacGrid g = T.grid;
  Kokkos::parallel_for(
      "amphora::mac::tall_cell_prolongate",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {g.nz, g.ny, g.nx}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        lattice(g.index(i, j, k)) = T.lattice_value(i, j, k, y);
      });
}

template <class ExecSpace, class MemSpace, class L, class Y>
void tall_cell_restrict(const ExecSpace& exec, const kernels::mac::TallCellLayout<MemSpace>& T,
                        const L& lattice, const Y& y) {
  const kernels::mac::MacGrid g = T.grid;
  Kokkos::parallel_for(
      "amphora::mac::tall_cell_restrict", RangePolicy<ExecSpace>(exec, 0, g.nx * g.nz),
      KOKKOS_LAMBDA(int col) {
        const int i = col % g.nx, k = col / g.nx;
        const int j0 = T.terrain(col), jb = T.band(col);
        if (jb > j0) {
          double bottom = 0.0, top = 0.0;
          const double dt = 1.0 / double(jb - 1 - j0);
          for (int j = j0; j < jb; ++j) {
            const double t = (j - j0) * dt, v = lattice(g.index(i, j, k));
            bottom += (1.0 - t) * v;
            top += t * v;
          }
          y(T.first_unknown(col)) = bottom;
          y(T.first_unknown(col) + 1) = top;
        }
        for (int j = jb; j < g.ny; ++j) {
          const int c = g.index(i, j, k), u = T.cell_unknown(c);
          if (u >= 0) y(u) = lattice(c);
        }
      });
}

/// G = P^T P of a tall cell of L rows: sum_j [(1-t)^2, t(1-t); t(1-t), t^2], t = j/(L-1), in
/// closed form: sum t^2 = sum (1-t)^2 = L(2L-1) / (6(L-1)) ("square"), sum t(1-t) = L/2 - that.
struct TallCellGram {
  double square, cross;
  KOKKOS_INLINE_FUNCTION explicit TallCellGram(int rows)
      : square(rows * (2.0 * rows - 1) / (6.0 * (rows - 1))), cross(0.5 * rows - square) {}
  /// One component of G^-1 (a, b) (G is symmetric with equal diagonal): the first for (a, b),
  /// the second for (b, a).
  KOKKOS_INLINE_FUNCTION double solve(double a, double b) const {
    return (square * a - cross * b) / (square * square - cross * cross);
  }
};

/// y = (P^T P)^-1 y, tall cell by tall cell.
template <class ExecSpace, class MemSpace, class Y>
void tall_cell_gram_solve(const ExecSpace& exec, const kernels::mac::TallCellLayout<MemSpace>& T,
                          const Y& y) {
  const kernels::mac::MacGrid g = T.grid;
  Kokkos::parallel_for(
      "amphora::mac::tall_cell_gram_solve", RangePolicy<ExecSpace>(exec, 0, g.nx * g.nz),
      KOKKOS_LAMBDA(int col) {
        const int j0 = T.terrain(col), jb = T.band(col);
        if (jb <= j0) return;
        const TallCellGram G(jb - j0);
        const int u = T.first_unknown(col);
        const double y0 = y(u), y1 = y(u + 1);
        y(u) = G.solve(y0, y1);
        y(u + 1) = G.solve(y1, y0);
      });
}

}  // namespace amphora::kernels::mac
