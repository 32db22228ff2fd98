#pragma once
// The arrays of a tall-cell grid (Irving et al. 2006, sec. 3) in a memory space, for kernels:
// per (x, z) column the terrain, band and first unknown, per lattice cell its uniform unknown.
// mesh::mac::TallCellGrid builds them (mesh::mac::make_layout).
#include "kernels/mac/mac_grid.hpp"

namespace amphora::kernels::mac {

/// The tall-cell grid's arrays in a memory space, for kernels (device-copyable).
template <class MemSpace>
struct TallCellLayout {
  MacGrid grid;
  Kokkos::View<int*, MemSpace> terrain, band, first_unknown;  ///< per column, x fastest
  Kokkos::View<int*, MemSpace> cell_unknown;                  ///< per padded lattice cell

  /// p = sum w y for lattice cell (i, j, k) (zero off the fluid).
  template <class Y>
  KOKKOS_INLINE_FUNCTION double lattice_value(int i, int j, int k, const Y& y) const {
    const int col = i + grid.nx * k;
    const int j0 = terrain(col), jb = band(col);
    if (j >= j0 && j < jb) {
      const double t = double(j - j0) / double(jb - 1 - j0);
      const int u = first_unknown(col);
      return (1.0 - t) * y(u) + t * y(u + 1);
    }
    const int u = cell_unknown(grid.index(i, j, k));
    return u >= 0 ? double(y(u)) : 0.0;
  }
};

/// The ghost ring of a block's tall-cell grid on a split grid (kernels/mac/tall_cell_numbering:
/// read_tall_cell_ring): per column of the ring (at (i + 1) + (nx + 2) (k + 1), i = -1..nx,
/// k = -1..nz; the block's own entries unused) its rows and global first unknown, per padded
/// lattice cell the global unknown of a uniform fluid cell of the ring (-1 elsewhere). The
/// ring's unknowns also have slots 0..slots-1 (column by column, as a column numbers its own):
/// a ring column's first, a ring cell's, and the cell carrying each slot.
template <class MemSpace>
struct TallCellRing {
  Kokkos::View<int*, MemSpace> terrain, band, first_unknown;
  Kokkos::View<int*, MemSpace> unknown;
  Kokkos::View<int*, MemSpace> first_slot, slot, slot_cell;
  int slots = 0;
};

/// A block's tall-cell grid for kernels: its own columns, its ghost ring (on a split grid) and
/// the global number of its first unknown.
template <class MemSpace>
struct TallCellMap {
  TallCellLayout<MemSpace> own;
  TallCellRing<MemSpace> ring;
  long first = 0;
  bool split = false;

  KOKKOS_INLINE_FUNCTION bool owns(int i, int k) const {
    return i >= 0 && i < own.grid.nx && k >= 0 && k < own.grid.nz;
  }
  /// Rows and first unknown of column (i, k): this block's (its own numbering) or the ring's
  /// (global numbering); no fluid (terrain = band = ny) outside the global box.
  KOKKOS_INLINE_FUNCTION void column(int i, int k, int& terrain, int& band,
                                     int& first_unknown) const {
    if (owns(i, k)) {
      const int c = i + own.grid.nx * k;
      terrain = own.terrain(c), band = own.band(c), first_unknown = own.first_unknown(c);
      return;
    }
    if (!split) {
      terrain = band = own.grid.ny, first_unknown = -1;
      return;
    }
    const int c = (i + 1) + (own.grid.nx + 2) * (k + 1);
    terrain = ring.terrain(c), band = ring.band(c), first_unknown = ring.first_unknown(c);
  }
  /// The (at most two) unknowns and weights of lattice cell (i, j, k) of the block or of its
  /// ring, p = sum w u: global numbers (ghost_base < 0), or this block's local columns, its own
  /// unknowns then the ring's slots from ghost_base on.
  KOKKOS_INLINE_FUNCTION int weights(int i, int j, int k, int u[2], double w[2],
                                     int ghost_base = -1) const {
    const MacGrid& g = own.grid;
    if (owns(i, k)) {
      const long base = ghost_base >= 0 ? 0 : first;
      const int col = i + g.nx * k, t = own.terrain(col), b = own.band(col);
      if (j >= t && j < b) return samples(j, t, b, base + own.first_unknown(col), u, w);
      const int unknown = own.cell_unknown(g.index(i, j, k));
      if (unknown < 0) return 0;
      u[0] = static_cast<int>(base + unknown), w[0] = 1.0;
      return 1;
    }
    if (!split) return 0;
    const int col = (i + 1) + (g.nx + 2) * (k + 1), t = ring.terrain(col), b = ring.band(col);
    if (j >= t && j < b)
      return samples(
          j, t, b,
          ghost_base >= 0 ? long(ghost_base) + ring.first_slot(col) : long(ring.first_unknown(col)),
          u, w);
    const int c = g.index(i, j, k), unknown = ring.unknown(c);
    if (unknown < 0) return 0;
    u[0] = ghost_base >= 0 ? ghost_base + ring.slot(c) : unknown, w[0] = 1.0;
    return 1;
  }

 private:
  /// Row j of a tall cell [t, b) whose bottom sample is `bottom`: linear between the two.
  KOKKOS_INLINE_FUNCTION static int samples(int j, int t, int b, long bottom, int u[2],
                                            double w[2]) {
    const double s = double(j - t) / double(b - 1 - t);
    u[0] = static_cast<int>(bottom), w[0] = 1.0 - s;
    u[1] = static_cast<int>(bottom + 1), w[1] = s;
    return 2;
  }
};

}  // namespace amphora::kernels::mac
