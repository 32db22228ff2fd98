#pragma once
// The order in which the rows of a half pair list run so that pair sums need no atomics and do
// not depend on threads or ranks: rows in slabs of two cell layers across z, each at least two
// cutoffs thick, so the particles touched by rows of slabs two apart are disjoint. Slabs of one
// colour (even or odd) run in parallel; a slab's rows run in (cell, key) order.
#include "kernels/particles/binning.hpp"

namespace amphora::kernels::particles {

/// Slab u holds rows order(start(u)) .. order(start(u + 1) - 1); the slabs of colour c are
/// colour_slabs[c] .. colour_slabs[c + 1] - 1. Passed back to slab_schedule, a schedule is
/// rebuilt in its own arrays, which only grow (bins is its binning workspace).
template <class Mem>
struct SlabSchedule {
  Kokkos::View<int*, Mem> order, start;
  int colour_slabs[3] = {0, 0, 0};
  Bins<Mem> bins;
};

/// Whether row a of the ordered rows starts a slab: its slab, cell(order(a)) / layer / 2,
/// differs from the row before's.
template <class Mem>
struct SlabStarts {
  Kokkos::View<int*, Mem> order, cell;
  int layer, total;
  KOKKOS_INLINE_FUNCTION int slab(int a) const { return cell(order(a)) / layer / 2; }
  KOKKOS_INLINE_FUNCTION bool operator()(int a) const {
    return a < total && (a == 0 || slab(a) != slab(a - 1));
  }
};

/// The schedule of points x(0 .. total) binned on `cells` (cells at least one cutoff wide, so a
/// slab of two layers is two cutoffs thick), in the order (colour = slab % 2, slab, cell (k, j,
/// i), key): binning gives (cell, key), as cell indices run k slowest; a stable partition by
/// colour follows.
template <class ExecSpace, class Positions, class Keys>
void slab_schedule(const ExecSpace& exec, const CellGrid& cells, const Positions& x, int total,
                   const Keys& key, SlabSchedule<typename ExecSpace::memory_space>& s) {
  using Mem = typename ExecSpace::memory_space;
  const int layer = cells.n[0] * cells.n[1];
  bin_points(exec, cells, x, total, key, s.bins);
  const auto perm = s.bins.permutation;
  const auto cell = s.bins.cell;
  grow_uninitialized(s.order, total, "amphora::particles::row_order");
  const auto order = s.order;
  int first_odd = 0;  // rows of colour 0
  Kokkos::parallel_reduce(
      "amphora::particles::slab_schedule::colours", RangePolicy<ExecSpace>(exec, 0, total),
      KOKKOS_LAMBDA(int a, int& even) { even += (cell(a) / layer / 2) % 2 == 0; }, first_odd);
  Kokkos::parallel_scan(
      "amphora::particles::slab_schedule::partition", RangePolicy<ExecSpace>(exec, 0, total),
      KOKKOS_LAMBDA(int a, int& even_before, bool final) {
        const int p = perm(a);
        const bool even = (cell(p) / layer / 2) % 2 == 0;
        if (final) order(even ? even_before : first_odd + (a - even_before)) = p;
        even_before += even;
      });
  const SlabStarts<Mem> starts{order, cell, layer, total};
  int slabs = 0, even_slabs = 0;
  Kokkos::parallel_reduce(
      "amphora::particles::slab_schedule::count_slabs", RangePolicy<ExecSpace>(exec, 0, total),
      KOKKOS_LAMBDA(int a, int& all) { all += starts(a); }, slabs);
  Kokkos::parallel_reduce(
      "amphora::particles::slab_schedule::count_even_slabs",
      RangePolicy<ExecSpace>(exec, 0, first_odd),
      KOKKOS_LAMBDA(int a, int& even) { even += starts(a); }, even_slabs);
  grow_uninitialized(s.start, slabs + 1, "amphora::particles::slab_start");
  const auto start = s.start;
  Kokkos::parallel_scan(
      "amphora::particles::slab_schedule::slab_starts", RangePolicy<ExecSpace>(exec, 0, total + 1),
      KOKKOS_LAMBDA(int a, int& before, bool final) {
        const bool first = a == total || starts(a);
        if (final && first) start(before) = a;
        before += first;
      });
  s.colour_slabs[0] = 0;
  s.colour_slabs[1] = even_slabs;
  s.colour_slabs[2] = slabs;
}

/// As above, into a new schedule.
template <class ExecSpace, class Positions, class Keys>
SlabSchedule<typename ExecSpace::memory_space> slab_schedule(const ExecSpace& exec,
                                                             const CellGrid& cells,
                                                             const Positions& x, int total,
                                                             const Keys& key) {
  SlabSchedule<typename ExecSpace::memory_space> s;
  slab_schedule(exec, cells, x, total, key, s);
  return s;
}

}  // namespace amphora::kernels::particles
