#pragma once
// The columns and unknowns of a tall-cell grid (Irving, Guendelman, Losasso & Fedkiw 2006,
// sec. 3), built by kernels in the grid's memory space: per (x, z) column its terrain and band
// (a rule given as a functor), the unknowns numbered column by column (x fastest; a tall cell's
// bottom and top samples, then the column's uniform fluid cells upwards) by a running sum over
// the columns, so the numbering is the serial one on every backend. On a block of a split grid
// the ghost ring's columns and global unknowns are read back from per-cell codes that the
// lattice ghost exchange has filled (mesh::mac::TallCellGrid does the exchange).
#include <cstddef>
#include <string>

#include "kernels/mac/tall_cell_columns.hpp"
#include "kernels/mac/tall_cell_layout.hpp"
#include "kernels/spaces.hpp"

namespace amphora::kernels::mac {

/// A fluid cell is one with a nonzero diagonal in the pressure stencil.
template <class Diagonal>
struct NonzeroDiagonal {
  Diagonal d;
  KOKKOS_INLINE_FUNCTION bool operator()(int c) const { return d(c) != 0.0; }
};

/// The water module's rule (tall_cell_rows): the band optical_depth rows below the top of the
/// lowest fluid run.
struct OpticalDepthBand {
  int optical_depth;
  KOKKOS_INLINE_FUNCTION int operator()(int, int, int terrain, int fluid_top) const {
    return tall_cell_band(terrain, fluid_top - optical_depth);
  }
};

/// A coarser multigrid level's rule: a tall cell where the four finer columns under the column
/// all have one, its band the coarse row holding the lowest of their bands (rounded up).
template <class MemSpace>
struct FollowFinerBand {
  Kokkos::View<int*, MemSpace> terrain, band;  ///< the finer level's own columns
  int finer_nx = 0, finer_ny = 0;
  KOKKOS_INLINE_FUNCTION int operator()(int i, int k, int terrain_here, int fluid_top) const {
    int lowest = finer_ny;
    for (int c = 0; c < 2; ++c)
      for (int a = 0; a < 2; ++a) {
        const int child = (2 * i + a) + finer_nx * (2 * k + c);
        if (band(child) <= terrain(child)) return terrain_here;
        lowest = band(child) < lowest ? band(child) : lowest;
      }
    const int coarse = (lowest + 1) / 2;
    return tall_cell_band(terrain_here, coarse < fluid_top ? coarse : fluid_top);
  }
};

/// L's columns (terrain: the lowest fluid row; band = band_of(i, k, terrain, top of the fluid
/// run above it)) and numbering, in arrays allocated here at L.grid's size. Returns the number
/// of unknowns (the running sum's total, one scalar to the host).
template <class ExecSpace, class MemSpace, class IsFluid, class Band>
long number_tall_cells(const ExecSpace& exec, TallCellLayout<MemSpace>& L, const IsFluid& fluid,
                       const Band& band_of) {
  const MacGrid g = L.grid;
  const int columns = g.nx * g.nz;
  const auto alloc = [](const char* label, long n) {
    return Kokkos::View<int*, MemSpace>(
        Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(label)),
        static_cast<std::size_t>(n));
  };
  L.terrain = alloc("amphora::tall::terrain", columns);
  L.band = alloc("amphora::tall::band", columns);
  L.first_unknown = alloc("amphora::tall::first_unknown", columns);
  L.cell_unknown = alloc("amphora::tall::cell_unknown", g.padded_size());
  const auto terrain = L.terrain, band = L.band, first = L.first_unknown, cell = L.cell_unknown;
  Kokkos::parallel_for(
      "amphora::tall::grid_columns", RangePolicy<ExecSpace>(exec, 0, columns),
      KOKKOS_LAMBDA(int col) {
        const int i = col % g.nx, k = col / g.nx;
        int t, top;
        fluid_run(
            g.ny, [&](int j) { return fluid(g.index(i, j, k)); }, t, top);
        const int b = band_of(i, k, t, top);
        terrain(col) = t;
        band(col) = b;
        int n = b > t ? 2 : 0;
        for (int j = b; j < g.ny; ++j) n += fluid(g.index(i, j, k)) ? 1 : 0;
        first(col) = n;  // the count, until the running sum
      });
  long total = 0;
  Kokkos::parallel_scan(
      "amphora::tall::grid_scan", RangePolicy<ExecSpace>(exec, 0, columns),
      KOKKOS_LAMBDA(int col, long& partial, bool final) {
        const int n = first(col);
        if (final) first(col) = static_cast<int>(partial);
        partial += n;
      },
      total);
  Kokkos::deep_copy(exec, cell, -1);
  Kokkos::parallel_for(
      "amphora::tall::grid_numbering", RangePolicy<ExecSpace>(exec, 0, columns),
      KOKKOS_LAMBDA(int col) {
        const int i = col % g.nx, k = col / g.nx;
        int u = first(col) + (band(col) > terrain(col) ? 2 : 0);
        for (int j = band(col); j < g.ny; ++j) {
          const int c = g.index(i, j, k);
          if (fluid(c)) cell(c) = u++;
        }
      });
  return total;
}

/// The number of L's columns with a tall cell (one scalar to the host).
template <class ExecSpace, class MemSpace>
long count_tall_cells(const ExecSpace& exec, const TallCellLayout<MemSpace>& L) {
  const auto terrain = L.terrain, band = L.band;
  long n = 0;
  Kokkos::parallel_reduce(
      "amphora::tall::count_tall_cells", RangePolicy<ExecSpace>(exec, 0, L.grid.nx * L.grid.nz),
      KOKKOS_LAMBDA(int c, long& sum) { sum += band(c) > terrain(c) ? 1 : 0; }, n);
  return n;
}

/// code = per padded cell of the block: the global unknown of a uniform fluid cell (>= 0),
/// -(global first unknown + 2) for a cell of a tall cell, -1 elsewhere (what a neighbouring
/// block reads its ring from, after the ghost exchange).
template <class ExecSpace, class MemSpace, class Code>
void tall_cell_ring_codes(const ExecSpace& exec, const TallCellLayout<MemSpace>& L,
                          long first_global, const Code& code) {
  const MacGrid g = L.grid;
  const auto terrain = L.terrain, band = L.band, first = L.first_unknown, cell = L.cell_unknown;
  Kokkos::deep_copy(exec, code, -1L);
  Kokkos::parallel_for(
      "amphora::tall::ring_codes", RangePolicy<ExecSpace>(exec, 0, g.nx * g.nz),
      KOKKOS_LAMBDA(int col) {
        const int i = col % g.nx, k = col / g.nx;
        for (int j = terrain(col); j < g.ny; ++j) {
          const int c = g.index(i, j, k);
          if (j < band(col))
            code(c) = -(first_global + first(col) + 2);
          else if (cell(c) >= 0)
            code(c) = first_global + cell(c);
        }
      });
}

/// The ring's columns and unknowns from the exchanged codes (tall_cell_ring_codes), in arrays
/// allocated here.
template <class ExecSpace, class MemSpace, class Code>
TallCellRing<MemSpace> read_tall_cell_ring(const ExecSpace& exec, const MacGrid& g,
                                           const Code& code) {
  const int columns = (g.nx + 2) * (g.nz + 2);
  TallCellRing<MemSpace> R;
  R.terrain = Kokkos::View<int*, MemSpace>("amphora::tall::ring_terrain", columns);
  R.band = Kokkos::View<int*, MemSpace>("amphora::tall::ring_band", columns);
  R.first_unknown = Kokkos::View<int*, MemSpace>("amphora::tall::ring_first_unknown", columns);
  R.unknown = Kokkos::View<int*, MemSpace>(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall::ring_unknown")),
      g.padded_size());
  R.first_slot = Kokkos::View<int*, MemSpace>("amphora::tall::ring_first_slot", columns);
  R.slot = Kokkos::View<int*, MemSpace>(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall::ring_slot")),
      g.padded_size());
  const auto terrain = R.terrain, band = R.band, first = R.first_unknown, unknown = R.unknown;
  Kokkos::deep_copy(exec, unknown, -1);
  Kokkos::parallel_for(
      "amphora::tall::read_ring", RangePolicy<ExecSpace>(exec, 0, columns), KOKKOS_LAMBDA(int col) {
        const int i = col % (g.nx + 2) - 1, k = col / (g.nx + 2) - 1;
        if (i >= 0 && i < g.nx && k >= 0 && k < g.nz) return;
        int j = 0;
        while (j < g.ny && code(g.index(i, j, k)) == -1) ++j;
        int b = j;
        first(col) = -1;
        if (j < g.ny && code(g.index(i, j, k)) < -1) {
          first(col) = static_cast<int>(-code(g.index(i, j, k)) - 2);
          while (b < g.ny && code(g.index(i, b, k)) < -1) ++b;
        }
        terrain(col) = j;
        band(col) = b;
        for (int jj = b; jj < g.ny; ++jj)
          unknown(g.index(i, jj, k)) = static_cast<int>(code(g.index(i, jj, k)));
      });
  // the slots: a running sum over the ring's columns of their unknowns
  const auto first_slot = R.first_slot, slot = R.slot;
  Kokkos::parallel_for(
      "amphora::tall::ring_counts", RangePolicy<ExecSpace>(exec, 0, columns),
      KOKKOS_LAMBDA(int col) {
        const int i = col % (g.nx + 2) - 1, k = col / (g.nx + 2) - 1;
        int n = 0;
        if (!(i >= 0 && i < g.nx && k >= 0 && k < g.nz)) {
          n = band(col) > terrain(col) ? 2 : 0;
          for (int j = band(col); j < g.ny; ++j) n += unknown(g.index(i, j, k)) >= 0 ? 1 : 0;
        }
        first_slot(col) = n;
      });
  int slots = 0;
  Kokkos::parallel_scan(
      "amphora::tall::ring_scan", RangePolicy<ExecSpace>(exec, 0, columns),
      KOKKOS_LAMBDA(int col, int& partial, bool final) {
        const int n = first_slot(col);
        if (final) first_slot(col) = partial;
        partial += n;
      },
      slots);
  R.slots = slots;
  R.slot_cell = Kokkos::View<int*, MemSpace>(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall::ring_slot_cell")),
      slots);
  const auto slot_cell = R.slot_cell;
  Kokkos::deep_copy(exec, slot, -1);
  Kokkos::parallel_for(
      "amphora::tall::ring_slots", RangePolicy<ExecSpace>(exec, 0, columns),
      KOKKOS_LAMBDA(int col) {
        const int i = col % (g.nx + 2) - 1, k = col / (g.nx + 2) - 1;
        if (i >= 0 && i < g.nx && k >= 0 && k < g.nz) return;
        int s = first_slot(col);
        if (band(col) > terrain(col)) {
          slot_cell(s++) = g.index(i, terrain(col), k);
          slot_cell(s++) = g.index(i, terrain(col) + 1, k);
        }
        for (int j = band(col); j < g.ny; ++j) {
          const int c = g.index(i, j, k);
          if (unknown(c) < 0) continue;
          slot(c) = s;
          slot_cell(s++) = c;
        }
      });
  return R;
}

}  // namespace amphora::kernels::mac
