#pragma once
// Verlet neighbour lists in CSR form, built from bins: row i lists every point j != i with
// |x_i - x_j| < r_i + r_j + skin, sorted by the points' global ids so that whatever sums over a
// row does so in an order independent of threads, ranks and storage order. Full lists (each
// pair in both rows): a row's owner accumulates its own sum with no atomics.
#include <cstdint>
#include <string>

#include "kernels/particles/binning.hpp"

namespace amphora::kernels::particles {

/// Visits, for point i, every other binned point j with |x_i - x_j| < r_i + r_j + skin, by
/// scanning the 27 cells around i's cell.
template <class MemSpace, class Positions, class Radii>
struct CellNeighborSearch {
  CellGrid grid;
  Kokkos::View<int*, MemSpace> cell_start, perm, cell;
  Positions x;
  Radii radius;
  double skin;

  template <class Visitor>
  KOKKOS_INLINE_FUNCTION void for_each(int i, Visitor&& visit) const {
    const int c = cell(i);
    const int ci = c % grid.n[0], cj = (c / grid.n[0]) % grid.n[1],
              ck = c / (grid.n[0] * grid.n[1]);
    const double xi = x(i, 0), yi = x(i, 1), zi = x(i, 2), ri = radius(i);
    for (int kk = ck > 0 ? ck - 1 : 0; kk <= ck + 1 && kk < grid.n[2]; ++kk) {
      for (int jj = cj > 0 ? cj - 1 : 0; jj <= cj + 1 && jj < grid.n[1]; ++jj) {
        for (int ii = ci > 0 ? ci - 1 : 0; ii <= ci + 1 && ii < grid.n[0]; ++ii) {
          const int cc = grid.index(ii, jj, kk);
          for (int a = cell_start(cc); a < cell_start(cc + 1); ++a) {
            const int j = perm(a);
            if (j == i) continue;
            const double dx = x(j, 0) - xi, dy = x(j, 1) - yi, dz = x(j, 2) - zi;
            const double cut = ri + radius(j) + skin;
            if (dx * dx + dy * dy + dz * dz < cut * cut) visit(j);
          }
        }
      }
    }
  }
};

/// A list kept across rebuilds keeps its arrays while they are large enough: offsets holds at
/// least rows() + 1 entries and neighbors at least entries(); only those are the list.
template <class MemSpace>
struct NeighborList {
  Kokkos::View<int*, MemSpace> offsets;    ///< row starts, rows() + 1 of them
  Kokkos::View<int*, MemSpace> neighbors;  ///< point indices, entries() of them
  int n_rows = 0;
  int n_entries = 0;
  int rows() const { return n_rows; }
  int entries() const { return n_entries; }
};

/// Rows for points 0 .. n_rows (owned), columns among all n_points (owned and ghosts), binned
/// in `bins` over `grid` (cells at least max(r_i + r_j) + skin wide), into `list`: its arrays
/// are kept while large enough; the neighbours grow with an eighth to spare, so that a list
/// whose contacts grow slowly does not reallocate at every rebuild.
template <class ExecSpace, class Positions, class Radii, class Ids>
void build_verlet_list(const ExecSpace& exec, const CellGrid& grid,
                       const Bins<typename ExecSpace::memory_space>& bins, const Positions& x,
                       const Radii& radius, const Ids& gid, int n_rows, double skin,
                       NeighborList<typename ExecSpace::memory_space>& list) {
  using Mem = typename ExecSpace::memory_space;
  grow_uninitialized(list.offsets, n_rows + 1, "amphora::build_verlet_list::offsets");
  const auto offsets = list.offsets;

  const CellNeighborSearch<Mem, Positions, Radii> search{
      grid, bins.offsets, bins.permutation, bins.cell, x, radius, skin};
  Kokkos::parallel_for(
      "amphora::build_verlet_list::count", RangePolicy<ExecSpace>(exec, 0, n_rows),
      KOKKOS_LAMBDA(int i) {
        int count = 0;
        search.for_each(i, [&](int) { ++count; });
        offsets(i + 1) = count;
      });
  int total = 0;
  Kokkos::parallel_scan(
      "amphora::build_verlet_list::scan", RangePolicy<ExecSpace>(exec, 0, n_rows + 1),
      KOKKOS_LAMBDA(int r, int& partial, bool final) {
        partial += r > 0 ? offsets(r) : 0;  // a kept offsets(0) is not initialised
        if (final) offsets(r) = partial;
      },
      total);
  if (list.neighbors.extent(0) < size_t(total))
    list.neighbors = Kokkos::View<int*, Mem>(
        Kokkos::view_alloc(Kokkos::WithoutInitializing,
                           std::string("amphora::build_verlet_list::neighbors")),
        size_t(total) + size_t(total) / 8);
  list.n_rows = n_rows;
  list.n_entries = total;
  const auto nbr = list.neighbors;
  Kokkos::parallel_for(
      "amphora::build_verlet_list::fill", RangePolicy<ExecSpace>(exec, 0, n_rows),
      KOKKOS_LAMBDA(int i) {
        int k = offsets(i);
        search.for_each(i, [&](int j) { nbr(k++) = j; });
        // Sort the row by global id (rows are short: insertion sort).
        for (int a = offsets(i) + 1; a < offsets(i + 1); ++a) {
          const int j = nbr(a);
          const std::int64_t key = gid(j);
          int b = a - 1;
          while (b >= offsets(i) && gid(nbr(b)) > key) {
            nbr(b + 1) = nbr(b);
            --b;
          }
          nbr(b + 1) = j;
        }
      });
  exec.fence();
}

/// As above, into a new list.
template <class ExecSpace, class Positions, class Radii, class Ids>
NeighborList<typename ExecSpace::memory_space> build_verlet_list(
    const ExecSpace& exec, const CellGrid& grid, const Bins<typename ExecSpace::memory_space>& bins,
    const Positions& x, const Radii& radius, const Ids& gid, int n_rows, double skin) {
  NeighborList<typename ExecSpace::memory_space> list;
  build_verlet_list(exec, grid, bins, x, radius, gid, n_rows, skin, list);
  return list;
}

/// Where each row's partners of larger key start (the list's rows are sorted by key): the
/// entries from half(i) on are the pairs row i evaluates in a half-pair schedule. half is kept:
/// it is reallocated only when it holds fewer than the list's rows.
template <class ExecSpace, class Ids>
void half_starts(const ExecSpace& exec, const NeighborList<typename ExecSpace::memory_space>& list,
                 const Ids& key, Kokkos::View<int*, typename ExecSpace::memory_space>& half) {
  const int rows = list.rows();
  grow_uninitialized(half, rows, "amphora::particles::half_start");
  const auto h = half;
  const auto off = list.offsets;
  const auto nbr = list.neighbors;
  Kokkos::parallel_for(
      "amphora::particles::half_starts", RangePolicy<ExecSpace>(exec, 0, rows),
      KOKKOS_LAMBDA(int i) {
        int k = off(i);
        while (k < off(i + 1) && key(nbr(k)) < key(i)) ++k;
        h(i) = k;
      });
}

/// As above, into a new View.
template <class ExecSpace, class Ids>
Kokkos::View<int*, typename ExecSpace::memory_space> half_starts(
    const ExecSpace& exec, const NeighborList<typename ExecSpace::memory_space>& list,
    const Ids& key) {
  Kokkos::View<int*, typename ExecSpace::memory_space> half;
  half_starts(exec, list, key, half);
  return half;
}

}  // namespace amphora::kernels::particles
