#pragma once
// Halo exchange of a field on the padded MAC lattice of a block of a BoxDecomposition: the
// padded lattice is exactly HaloExchange's LayoutLeft field with one ghost layer, so the field
// is staged through one (double) and exchanged there. Any value type (cell types, float
// conductances, doubles); setup-time use (one copy each way).
#include "mesh/halo_exchange.hpp"
#include "mesh/mac/mac_grid.hpp"

namespace amphora::mesh {

template <class ExecSpace, class MemSpace, class View>
void exchange_lattice_ghosts(const ExecSpace& exec, const HaloExchange<MemSpace>& halo, const MacGrid& g,
                             const View& v) {
  using T = typename View::non_const_value_type;
  typename HaloExchange<MemSpace>::Field f("amphora::lattice_halo", g.nx + 2, g.ny + 2, g.nz + 2);
  const int n = static_cast<int>(g.padded_size());
  Kokkos::parallel_for(
      "amphora::lattice_halo::in", RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int c) { f.data()[c] = static_cast<double>(v(c)); });
  halo.exchange(exec, f);
  Kokkos::parallel_for(
      "amphora::lattice_halo::out", RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int c) { v(c) = static_cast<T>(f.data()[c]); });
  exec.fence();
}

}  // namespace amphora::mesh
