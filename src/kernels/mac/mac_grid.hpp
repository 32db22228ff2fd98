#pragma once
// A uniform 3D MAC grid (Harlow & Welch 1965): pressure and level set at cell centres, each
// velocity component on the faces normal to it. y is up; columns are (x, z) pairs.
//
// Every field lives on one padded lattice of (nx+2)(ny+2)(nz+2) entries, x fastest: cell
// (i, j, k), i in [-1, nx], sits at index(i, j, k). The ghost layer holds zeros (pressure) or
// boundary values, so stencils need no branches at the box faces. A face velocity shares the
// index of the cell on its + side: u(index(i, j, k)) is on the face between cells i-1 and i,
// so faces i = 0..nx of an x-row are indices index(0..nx, j, k).
#include <array>
#include <cstdint>

#include "kernels/spaces.hpp"

namespace amphora::kernels::mac {

enum class MacCellType : std::uint8_t { fluid = 0, air = 1, solid = 2 };

struct MacGrid {
  int nx = 0, ny = 0, nz = 0;
  double h = 1.0;  ///< cell width (cubic cells)
  /// lower corner of cell (0, 0, 0); a Kokkos::Array, as kernels read it (std::array's
  /// operator[] is host-only on CUDA without relaxed constexpr)
  Kokkos::Array<double, 3> origin{0, 0, 0};

  KOKKOS_INLINE_FUNCTION int stride_y() const { return nx + 2; }
  KOKKOS_INLINE_FUNCTION int stride_z() const { return (nx + 2) * (ny + 2); }
  KOKKOS_INLINE_FUNCTION long padded_size() const { return long(nx + 2) * (ny + 2) * (nz + 2); }
  KOKKOS_INLINE_FUNCTION long cells() const { return long(nx) * ny * nz; }
  KOKKOS_INLINE_FUNCTION int index(int i, int j, int k) const {
    return (i + 1) + (nx + 2) * ((j + 1) + (ny + 2) * (k + 1));
  }
  /// Inverse of index(): (i, j, k) with i in [-1, nx].
  KOKKOS_INLINE_FUNCTION void ijk(int c, int& i, int& j, int& k) const {
    i = c % (nx + 2) - 1;
    const int r = c / (nx + 2);
    j = r % (ny + 2) - 1;
    k = r / (ny + 2) - 1;
  }
  /// The padded index range that covers every interior cell (whole padded planes 0..nz-1):
  /// loops over it see each interior cell once and some ghost cells, and every +-1, +-stride
  /// neighbour stays inside the padded array.
  KOKKOS_INLINE_FUNCTION int first_plane_index() const { return stride_z(); }
  KOKKOS_INLINE_FUNCTION int end_plane_index() const { return stride_z() * (nz + 1); }
  KOKKOS_INLINE_FUNCTION bool interior(int i, int j, int k) const {
    return i >= 0 && i < nx && j >= 0 && j < ny && k >= 0 && k < nz;
  }
  std::array<double, 3> cell_centre(int i, int j, int k) const {
    return {origin[0] + (i + 0.5) * h, origin[1] + (j + 0.5) * h, origin[2] + (k + 0.5) * h};
  }
  /// The grid with cells twice as wide (dimensions must be even).
  MacGrid coarsened() const { return MacGrid{nx / 2, ny / 2, nz / 2, 2 * h, origin}; }
};

/// What lies beyond each face of the box: a wall (no flow through it; pressure Neumann), open
/// air (pressure zero on the face), or another rank's block (its cells are in the ghost layer,
/// filled by a halo exchange). Order: -x, +x, -y, +y, -z, +z.
enum class MacBoundary : std::uint8_t { wall = 0, open = 1, neighbour = 2 };
using MacBoxBoundaries = std::array<MacBoundary, 6>;

/// Which faces of a grid's box end the domain (true) rather than meet another block (false), as
/// a device-copyable array: kernels stop at the former and read the ghost layer across the latter.
using MacEdges = Kokkos::Array<bool, 6>;
inline MacEdges box_edges() {
  MacEdges e;
  for (int f = 0; f < 6; ++f) e[f] = true;
  return e;
}

}  // namespace amphora::kernels::mac
