#pragma once
// The column structure of a tall-cell grid (Irving, Guendelman, Losasso & Fedkiw 2006, sec. 3)
// in a memory space: per (x, z) column the lowest fluid row (the terrain) and the lowest uniform
// row (the band); rows [terrain, band) form the column's tall cell. Built on the device from the
// cell types every sub-step, so the grid follows the surface; mesh::mac::TallCellGrid uses the same
// rule (tall_cell_rows) for the pressure unknowns.
//
// On a block of a grid split over ranks the columns of the ghost ring (i = -1 or nx, k = -1 or
// nz, from the exchanged cell types) are known too, so the face samples on the block's faces
// see the tall cells on both sides, as on one block; `edges` marks the faces of the global box,
// where face samples are never in tall cells.
//
// A tall cell carries every field as a linear function of height through two samples (bottom
// and top). The water module stores the fields expanded on the lattice; tall_rows() names the
// lattice samples of a field that lie inside tall cells, where the tall-cell schemes apply.
#include "kernels/mac/mac_grid.hpp"

namespace amphora::kernels::mac {

/// The lowest run of fluid rows of a column, [terrain, top).
AMPHORA_EXEC_CHECK_DISABLE
template <class IsFluid>
KOKKOS_INLINE_FUNCTION void fluid_run(int ny, const IsFluid& fluid, int& terrain, int& top) {
  terrain = 0;
  while (terrain < ny && !fluid(terrain)) ++terrain;
  top = terrain;
  while (top < ny && fluid(top)) ++top;
}

/// A column's band for a tall cell from the terrain up to `band`: band itself, or the terrain
/// (no tall cell) if that leaves fewer than the two rows its two samples need.
KOKKOS_INLINE_FUNCTION int tall_cell_band(int terrain, int band) {
  return band - terrain < 2 ? terrain : band;
}

/// Rows of one column from its fluid cells: terrain = the lowest fluid row, band = the lowest
/// uniform row, optical_depth uniform rows below the lowest non-fluid row above the terrain
/// (tall_cell_band: no tall cell of fewer than two rows).
AMPHORA_EXEC_CHECK_DISABLE
template <class IsFluid>
KOKKOS_INLINE_FUNCTION void tall_cell_rows(int ny, int optical_depth, const IsFluid& fluid,
                                           int& terrain, int& band) {
  int top;
  fluid_run(ny, fluid, terrain, top);
  band = tall_cell_band(terrain, top - optical_depth);
}

template <class MemSpace>
struct TallCellColumns {
  MacGrid grid;
  MacEdges edges = box_edges();
  /// per column of the block and its ghost ring, at column(i, k)
  Kokkos::View<int*, MemSpace> terrain, band;

  TallCellColumns() = default;
  explicit TallCellColumns(const MacGrid& g, const MacEdges& box_faces = box_edges())
      : grid(g),
        edges(box_faces),
        terrain("amphora::tall::terrain", static_cast<std::size_t>(g.nx + 2) * (g.nz + 2)),
        band("amphora::tall::band", static_cast<std::size_t>(g.nx + 2) * (g.nz + 2)) {}

  /// Index of column (i, k), i = -1..nx, k = -1..nz.
  KOKKOS_INLINE_FUNCTION int column(int i, int k) const {
    return (i + 1) + (grid.nx + 2) * (k + 1);
  }

  /// Rows [lo, hi) of the samples in tall cells of the field with staggering d (-1: cell
  /// centres, 0/1/2: faces normal to x/y/z) in sample column (i, k): the tall cell's rows for
  /// cells, its inner faces for v, and for u and w the rows where the tall cells on both sides
  /// of the face overlap (none at the box faces).
  KOKKOS_INLINE_FUNCTION void tall_rows(int d, int i, int k, int& lo, int& hi) const {
    lo = hi = 0;
    if (d == -1 || d == 1) {
      const int col = column(i, k);
      const int t = terrain(col), b = band(col);
      if (b > t) lo = d == -1 ? t : t + 1, hi = b;
      return;
    }
    const int n = d == 0 ? grid.nx : grid.nz, m = d == 0 ? i : k;
    if ((m == 0 && edges[2 * d]) || (m == n && edges[2 * d + 1])) return;
    const int a = d == 0 ? column(i - 1, k) : column(i, k - 1), c = column(i, k);
    const int ta = terrain(a), ba = band(a), tc = terrain(c), bc = band(c);
    if (ba > ta && bc > tc) {
      lo = math::max(ta, tc);
      hi = math::max(lo, math::min(ba, bc));
    }
  }
  KOKKOS_INLINE_FUNCTION bool in_tall_cell(int d, int i, int j, int k) const {
    int lo, hi;
    tall_rows(d, i, k, lo, hi);
    return j >= lo && j < hi;
  }
};

/// The columns of the fluid cells of `type` (every column uniform if optical_depth == 0), the
/// ghost ring's from type's ghost cells.
template <class ExecSpace, class MemSpace, class Types>
void find_tall_cell_columns(const ExecSpace& exec, const Types& type, int optical_depth,
                            const TallCellColumns<MemSpace>& columns) {
  const MacGrid g = columns.grid;
  const auto terrain = columns.terrain, band = columns.band;
  const int nx2 = g.nx + 2;
  Kokkos::parallel_for(
      "amphora::mac::find_tall_cell_columns", RangePolicy<ExecSpace>(exec, 0, nx2 * (g.nz + 2)),
      KOKKOS_LAMBDA(int col) {
        const int i = col % nx2 - 1, k = col / nx2 - 1;
        const auto fluid = [&](int j) { return type(g.index(i, j, k)) == MacCellType::fluid; };
        int t, b;
        tall_cell_rows(g.ny, optical_depth > 0 ? optical_depth : g.ny, fluid, t, b);
        terrain(col) = t;
        band(col) = b;
      });
}

/// The lowest band over the block's own columns: below this row every cell of the block lies in
/// a tall cell or is solid, so kernels that leave tall cells unchanged can start their rows there
/// (a deep pool keeps about a fifth of its rows). 0 if a column has no tall cell or a non-solid
/// cell under its tall cell.
template <class ExecSpace, class MemSpace, class Types>
int lowest_band(const ExecSpace& exec, const TallCellColumns<MemSpace>& T, const Types& type) {
  const MacGrid g = T.grid;
  int lowest = g.ny;
  Kokkos::parallel_reduce(
      "amphora::mac::lowest_band", RangePolicy<ExecSpace>(exec, 0, g.nx * g.nz),
      KOKKOS_LAMBDA(int m, int& acc) {
        const int i = m % g.nx, k = m / g.nx, col = T.column(i, k), t = T.terrain(col),
                  b = T.band(col);
        int j = 0;
        while (j < t && type(g.index(i, j, k)) == MacCellType::solid) ++j;
        acc = math::min(acc, b > t && j == t ? b : 0);
      },
      Kokkos::Min<int>(lowest));
  return lowest;
}

}  // namespace amphora::kernels::mac
