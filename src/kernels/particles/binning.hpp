#pragma once
// Binning of points into a uniform cell grid by counting sort (Cabana's LinkedCellList idea):
// counts, an exclusive scan into cell offsets, a fill, and a sort of each cell's short list by
// point index, so the result does not depend on thread timing. Generic: it serves contact
// detection, and later void fractions and particle-cell maps.
#include <string>

#include "kernels/grow_view.hpp"
#include "kernels/spaces.hpp"

namespace amphora::kernels::particles {

/// A uniform grid of cubic cells of side h covering [lo, lo + n h). Points outside are clamped
/// into the boundary cells.
struct CellGrid {
  double lo[3] = {0, 0, 0};
  double h = 1.0;
  int n[3] = {1, 1, 1};

  /// The coarsest grid over [lo, hi] whose cells are at least `min_cell` wide.
  static CellGrid covering(const double lo_[3], const double hi_[3], double min_cell) {
    CellGrid g;
    g.h = min_cell;
    for (int d = 0; d < 3; ++d) {
      g.lo[d] = lo_[d];
      const double len = hi_[d] - lo_[d];
      g.n[d] = len > 0 ? static_cast<int>(len / min_cell) : 1;
      if (g.n[d] < 1) g.n[d] = 1;
    }
    // Cells must be at least min_cell wide: widen h so n cells span the box exactly or more.
    double h = min_cell;
    for (int d = 0; d < 3; ++d) {
      const double len = hi_[d] - lo_[d];
      if (len > 0) h = math::max(h, len / g.n[d]);
    }
    g.h = h;
    return g;
  }
  KOKKOS_INLINE_FUNCTION int num_cells() const { return n[0] * n[1] * n[2]; }
  KOKKOS_INLINE_FUNCTION int coord(double x, int d) const {
    const int c = static_cast<int>((x - lo[d]) / h);
    return c < 0 ? 0 : (c >= n[d] ? n[d] - 1 : c);
  }
  KOKKOS_INLINE_FUNCTION int index(int i, int j, int k) const { return i + n[0] * (j + n[1] * k); }
  KOKKOS_INLINE_FUNCTION int cell_of(double x, double y, double z) const {
    return index(coord(x, 0), coord(y, 1), coord(z, 2));
  }
};

/// Points sorted by cell: the points of cell c are permutation[offsets(c) .. offsets(c+1)),
/// in increasing key (the point index, unless bin_points is given keys).
/// Kept and passed back to bin_points, a Bins is a workspace: its arrays only grow, so binning
/// the same points again allocates nothing (their extents may exceed the points and cells).
template <class MemSpace>
struct Bins {
  Kokkos::View<int*, MemSpace> offsets;
  Kokkos::View<int*, MemSpace> permutation;
  Kokkos::View<int*, MemSpace> cell;  ///< cell of each point
  Kokkos::View<int*, MemSpace> fill;  ///< scratch: points placed per cell
};

/// The point index as the key of bin_points' order within a cell.
struct PointIndex {
  KOKKOS_INLINE_FUNCTION int operator()(int i) const { return i; }
};

/// Bins points x(0 .. n) (x is any View indexable as x(i, d)) into b (a workspace, above);
/// within a cell, points are in increasing key(i) (distinct keys: a global id, say).
template <class ExecSpace, class Positions, class Keys>
void bin_points(const ExecSpace& exec, const CellGrid& grid, const Positions& x, int n,
                const Keys& key, Bins<typename ExecSpace::memory_space>& b) {
  const int nc = grid.num_cells();
  grow_uninitialized(b.offsets, nc + 1, "amphora::bin_points::offsets");
  grow_uninitialized(b.permutation, n, "amphora::bin_points::permutation");
  grow_uninitialized(b.cell, n, "amphora::bin_points::cell");
  grow_uninitialized(b.fill, nc, "amphora::bin_points::fill");
  const auto fill = b.fill;
  const auto offsets = b.offsets;
  const auto perm = b.permutation;
  const auto cell = b.cell;
  Kokkos::parallel_for(
      "amphora::bin_points::zero", RangePolicy<ExecSpace>(exec, 0, nc + 1), KOKKOS_LAMBDA(int c) {
        offsets(c) = 0;
        if (c < nc) fill(c) = 0;
      });

  Kokkos::parallel_for(
      "amphora::bin_points::count", RangePolicy<ExecSpace>(exec, 0, n), KOKKOS_LAMBDA(int i) {
        const int c = grid.cell_of(x(i, 0), x(i, 1), x(i, 2));
        cell(i) = c;
        Kokkos::atomic_add(&offsets(c + 1), 1);  // counts commute: the result is deterministic
      });
  Kokkos::parallel_scan(
      "amphora::bin_points::scan", RangePolicy<ExecSpace>(exec, 0, nc + 1),
      KOKKOS_LAMBDA(int c, int& partial, bool final) {
        partial += offsets(c);
        if (final) offsets(c) = partial;
      });
  Kokkos::parallel_for(
      "amphora::bin_points::fill", RangePolicy<ExecSpace>(exec, 0, n), KOKKOS_LAMBDA(int i) {
        const int c = cell(i);
        perm(offsets(c) + Kokkos::atomic_fetch_add(&fill(c), 1)) = i;
      });
  // The fill order within a cell depends on thread timing: sort each (short) cell list.
  Kokkos::parallel_for(
      "amphora::bin_points::sort_cells", RangePolicy<ExecSpace>(exec, 0, nc), KOKKOS_LAMBDA(int c) {
        for (int a = offsets(c) + 1; a < offsets(c + 1); ++a) {
          const int p = perm(a);
          const auto k = key(p);
          int b2 = a - 1;
          while (b2 >= offsets(c) && key(perm(b2)) > k) {
            perm(b2 + 1) = perm(b2);
            --b2;
          }
          perm(b2 + 1) = p;
        }
      });
  exec.fence();
}

/// Bins points x(0 .. n) (x is any View indexable as x(i, d)) into new arrays; within a cell,
/// points are in increasing key(i) (distinct keys: a global id, say).
template <class ExecSpace, class Positions, class Keys = PointIndex>
Bins<typename ExecSpace::memory_space> bin_points(const ExecSpace& exec, const CellGrid& grid,
                                                  const Positions& x, int n,
                                                  const Keys& key = Keys()) {
  Bins<typename ExecSpace::memory_space> b;
  bin_points(exec, grid, x, n, key, b);
  return b;
}

}  // namespace amphora::kernels::particles
