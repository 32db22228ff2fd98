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

}  // namespace amphora::kernels::mac
